// The project's one source of seeded random numbers: xoshiro256** seeded by
// splitmix64, with uniform, integer and normal draws defined here rather than
// by the standard library's distributions (whose algorithms are
// implementation-defined), so a seed gives the same stream with every
// compiler and standard library.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace gpm {

// splitmix64 step: advances state and returns a well-mixed 64-bit value.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// The independent random streams of a run, each derived from the run's seed
// (derive_seed): a new use of randomness gets a new name here.
enum class Stream : int {
  kActualParameters = 0,  // the actual robot's parameters (perturbed from the nominal)
  kSamplePoses = 1,       // the calibration's sample poses
  kTwinNoise = 2,         // the twin's reading noise and servo state
  kTestPoses = 3,         // the accuracy test's poses (independent of the samples)
  kAccuracyTest = 4,      // the accuracy measurement's own noise
  kEncoderErrors = 5,     // the encoders' drawn error phases
  kRandomizedEffects = 6, // the effects of the `randomized` preset
  kRandomizedMasses = 7,  // the masses of the `randomized` preset
  kDriveTrainPhases = 9,  // the drive trains' error phases (reducer, motor, cogging)
  kHarmonicPhases = 16,   // the phases of the encoders' harmonics
};

// Seed of the independent stream `stream` of a run seeded by `seed`
// (a splitmix64 step of seed + golden ratio x (stream + 1)).
inline std::uint64_t derive_seed(std::uint64_t seed, Stream stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * static_cast<std::uint64_t>(static_cast<int>(stream) + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

class Rng {
 public:
  using result_type = std::uint64_t;

  // A generator whose whole stream is fixed by seed.
  explicit Rng(std::uint64_t seed = 1) {
    std::uint64_t sm = seed;
    for (auto& w : s_) w = splitmix64(sm);
  }

  // A generator at an explicit xoshiro256** state (not all zero).
  static Rng from_state(std::uint64_t s0, std::uint64_t s1, std::uint64_t s2, std::uint64_t s3) {
    Rng r;
    r.s_[0] = s0, r.s_[1] = s1, r.s_[2] = s2, r.s_[3] = s3;
    return r;
  }

  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }

  // 64 random bits (xoshiro256**).
  result_type operator()() { return bits(); }
  std::uint64_t bits() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }

  // Uniform on [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(bits() >> 11) * 0x1.0p-53; }

  // Uniform on [lo, hi].
  double uniform(double lo, double hi) {
    const double v = lo + (hi - lo) * uniform();
    return v > hi ? hi : v;
  }

  // Uniform integer in [0, n), n >= 1, without modulo bias (rejection).
  std::uint64_t below(std::uint64_t n) {
    const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() -
                                std::numeric_limits<std::uint64_t>::max() % n;
    std::uint64_t r;
    do r = bits(); while (r >= limit);
    return r % n;
  }

  // Standard normal draw (Marsaglia's polar method; the second value of each
  // pair is kept for the next call).
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    double u, v, s;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      s = u * u + v * v;
    } while (s >= 1.0 || s == 0.0);
    const double f = std::sqrt(-2.0 * std::log(s) / s);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }

  // Normal draw with mean mu and standard deviation sigma.
  double normal(double mu, double sigma) { return mu + sigma * normal(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace gpm
