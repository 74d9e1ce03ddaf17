// Fuzz target for models/robot_yaml.cpp: any text either loads as a valid
// robot or raises InputError; anything else (another exception, a crash, a
// sanitizer report, a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gpm::Robot r = gpm::parse_robot(text, "fuzz.yaml");
    // A robot that loads must round-trip exactly.
    if (!(gpm::parse_robot(gpm::robot_to_yaml(r), "again.yaml") == r)) __builtin_trap();
  } catch (const gpm::InputError&) {
  }
  return 0;
}
