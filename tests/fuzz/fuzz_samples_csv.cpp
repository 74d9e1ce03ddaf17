// Fuzz target for models/samples.cpp: any text either parses as samples or
// raises InputError; parsed samples must write and read back identically.
#include <cstddef>
#include <cstdint>
#include <string>

#include "models/errors.hpp"
#include "models/samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gpm::Samples s = gpm::parse_samples_csv(text, "fuzz.csv");
    const gpm::Samples b = gpm::parse_samples_csv(gpm::samples_to_csv(s), "again.csv");
    if (b.size() != s.size() || b.has_xy != s.has_xy) __builtin_trap();
    if (b.t != s.t || b.tau != s.tau || b.tau_last != s.tau_last || b.tau_between != s.tau_between) __builtin_trap();
    for (size_t j = 0; j < s.size(); ++j) {
      if (b.theta_m[j] != s.theta_m[j] || b.id[j] != s.id[j]) __builtin_trap();
      if (s.has_xy && b.xy[j] != s.xy[j]) __builtin_trap();
    }
  } catch (const gpm::InputError&) {
  }
  return 0;
}
