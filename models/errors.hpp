// Input errors: bad files, keys, values or arguments. The command line turns
// one into a single line on stderr and exit code 2 (DESIGN.md, exit codes).
#pragma once

#include <stdexcept>
#include <string>

namespace gpm {

// An error in what the user gave: the message names the file, key or line,
// what is wrong and what would be valid.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace gpm
