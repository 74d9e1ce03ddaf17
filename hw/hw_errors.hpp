// Errors of the hardware layer, under gpm::Error (models/errors.hpp).
// InputError stays for bad files and values (exit 2); HardwareError and its
// children are run-time failures of the robot or of a session (exit 1);
// LifecycleError is a misuse of the RobotHardware lifecycle.
//
//   gpm::Error
//   |-- gpm::InputError
//   |-- HardwareError            backend failed: connection, timeout, fault, reply
//   |   |-- SafetyError          the supervisor stopped the robot
//   |   |-- CommandRejected      the supervisor refused one command (robot holds)
//   |   |-- Interrupted          a stop was requested (signal): drives disabled
//   |   `-- PathEndedEarly       a path sampled on the fly left its plan: retraced, drives off
//   `-- LifecycleError           call not allowed in the current state
#pragma once

#include <string>

#include "models/errors.hpp"

namespace gpm::hw {

// A backend failed: lost connection, timeout, drive fault, implausible reply.
class HardwareError : public Error {
 public:
  explicit HardwareError(const std::string& what) : Error(what) {}
};

// A lifecycle transition or call not allowed in the current state.
class LifecycleError : public Error {
 public:
  explicit LifecycleError(const std::string& what) : Error(what) {}
};

// The safety supervisor refused a command or stopped the robot.
class SafetyError : public HardwareError {
 public:
  explicit SafetyError(const std::string& what) : HardwareError(what) {}
};

// The safety supervisor refused one command (it was not forwarded; the robot
// brakes to a hold). The hardware stays active: the caller may send a valid one.
class CommandRejected : public HardwareError {
 public:
  explicit CommandRejected(const std::string& what) : HardwareError(what) {}
};

// A stop was requested while the robot moved (SIGINT, SIGTERM, SIGHUP): the
// drives were disabled; what was recorded is kept.
class Interrupted : public HardwareError {
 public:
  explicit Interrupted(const std::string& what) : HardwareError(what) {}
};

// A path sampled on the fly ended early: the end-effector from the readings
// left its plan by more than the session's retreat bound; the robot retraced
// the path to its start and the drives were disabled normally; the samples
// taken are kept. duration_s: the session's robot time, the retreat included.
class PathEndedEarly : public HardwareError {
 public:
  PathEndedEarly(const std::string& what, double duration_s) : HardwareError(what), duration_s(duration_s) {}
  double duration_s = 0.0;
};

}  // namespace gpm::hw
