// Errors of the hardware layer. InputError (models/errors.hpp) stays for bad
// files and values (exit 2); these are run-time failures of a session.
#pragma once

#include <stdexcept>
#include <string>

namespace gpm::hw {

// A backend failed: lost connection, timeout, drive fault, implausible reply.
class HardwareError : public std::runtime_error {
 public:
  explicit HardwareError(const std::string& what) : std::runtime_error(what) {}
};

// A lifecycle transition or call not allowed in the current state.
class LifecycleError : public std::logic_error {
 public:
  explicit LifecycleError(const std::string& what) : std::logic_error(what) {}
};

// The safety supervisor refused a command or stopped the robot.
class SafetyError : public HardwareError {
 public:
  explicit SafetyError(const std::string& what) : HardwareError(what) {}
};

}  // namespace gpm::hw

namespace gpm::hw {

// The safety supervisor refused one command (it was not forwarded; the robot
// brakes to a hold). The hardware stays active: the caller may send a valid one.
class CommandRejected : public std::runtime_error {
 public:
  explicit CommandRejected(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace gpm::hw
