// Fuzz target for the scenario loaders (sim/scenario.cpp and
// run/run_spec.cpp): any text either loads as a scenario or raises
// InputError; anything else (another exception, a crash, a sanitizer report,
// a hang) is a bug. Relative paths resolve against the source tree.
#include <cstddef>
#include <cstdint>
#include <string>

#include "models/errors.hpp"
#include "run/run_spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    gpm::scenario::parse_run_spec(text, "fuzz.yaml", GPM_SOURCE_DIR);
  } catch (const gpm::InputError&) {
  }
  return 0;
}
