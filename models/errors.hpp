// The project's errors. gpm::Error is the root of every error the toolkit
// raises on purpose; InputError (bad files, keys, values or arguments) is the
// one the command line turns into a single line on stderr and exit code 2
// (docs/ARCHITECTURE.md, exit codes). Layers derive their own run-time errors from
// Error (e.g. gpm::hw::HardwareError), so one catch of gpm::Error sees them all.
#pragma once

#include <stdexcept>
#include <string>

namespace gpm {

// Root of the project's errors: a one-line message for the user.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

// An error in what the user gave: the message names the file, key or line,
// what is wrong and what would be valid.
class InputError : public Error {
 public:
  explicit InputError(const std::string& what) : Error(what) {}
};

}  // namespace gpm
