// The random numbers of the global optimisers: one 64-bit Mersenne twister,
// with uniform doubles and integers defined here (not by the standard
// library's distributions) so a seed gives the same run on every platform.
#pragma once

#include <cstdint>
#include <random>

namespace gpm::calib::global {

class Rng {
 public:
  explicit Rng(uint64_t seed) : engine_(seed) {}

  // Uniform on [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Uniform on [lo, hi].
  double uniform(double lo, double hi) {
    const double v = lo + (hi - lo) * uniform();
    return v > hi ? hi : v;
  }

  // Uniform integer in [0, n), n >= 1, without modulo bias (rejection).
  uint64_t below(uint64_t n) {
    const uint64_t limit = UINT64_MAX - UINT64_MAX % n;
    uint64_t r;
    do r = engine_(); while (r >= limit);
    return r % n;
  }

  // 64 random bits.
  uint64_t bits() { return engine_(); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace gpm::calib::global
