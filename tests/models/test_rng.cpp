// Tests of models/rng.hpp: reference outputs of splitmix64 and xoshiro256**,
// and the moments of the uniform, integer and normal draws.
#include "models/rng.hpp"

#include <array>
#include <cmath>
#include <set>

#include <gtest/gtest.h>

namespace gpm {
namespace {

TEST(Rng, Splitmix64MatchesPublishedOutput) {
  // Reference values of Vigna's splitmix64.c seeded with 0.
  std::uint64_t state = 0;
  EXPECT_EQ(splitmix64(state), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(splitmix64(state), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(splitmix64(state), 0x06c45d188009454fULL);
}

TEST(Rng, Xoshiro256StarStarMatchesReferenceImplementation) {
  // First outputs of Vigna's xoshiro256starstar.c from state {1, 2, 3, 4}.
  Rng r = Rng::from_state(1, 2, 3, 4);
  EXPECT_EQ(r.bits(), 11520ULL);
  EXPECT_EQ(r.bits(), 0ULL);
  EXPECT_EQ(r.bits(), 1509978240ULL);
  EXPECT_EQ(r.bits(), 1215971899390074240ULL);
}

TEST(Rng, SameSeedSameStreamDifferentSeedDifferentStream) {
  Rng a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const auto x = a.bits();
    EXPECT_EQ(x, b.bits());
    EXPECT_NE(x, c.bits());
  }
}

// derive_seed is one splitmix64 step from the state seed + golden ratio x stream.
TEST(Rng, DerivedSeedIsASplitmixStepAlongTheStreams) {
  for (const std::uint64_t seed : {0ULL, 7ULL, 0xffffffffffffffffULL}) {
    std::uint64_t state = seed + 0x9e3779b97f4a7c15ULL * 4;
    EXPECT_EQ(derive_seed(seed, Stream::kAccuracyTest), splitmix64(state));
  }
}

// Every named stream of a seed differs from the others and from another seed's.
TEST(Rng, NamedStreamsAreDistinct) {
  const Stream all[] = {Stream::kActualParameters, Stream::kSamplePoses,     Stream::kTwinNoise,
                        Stream::kTestPoses,        Stream::kAccuracyTest,    Stream::kEncoderErrors,
                        Stream::kRandomizedEffects, Stream::kRandomizedMasses, Stream::kDriveTrainPhases,
                        Stream::kHarmonicPhases};
  std::set<std::uint64_t> seen;
  for (const Stream s : all) {
    EXPECT_TRUE(seen.insert(derive_seed(1, s)).second);
    EXPECT_NE(derive_seed(1, s), derive_seed(2, s));
  }
}

TEST(Rng, UniformMomentsAndRange) {
  Rng r(1);
  const int n = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  const double mean = sum / n, var = sum2 / n - mean * mean;
  // Standard errors: 1/sqrt(12 n) = 6.5e-4 for the mean; 5 sigma bounds.
  EXPECT_NEAR(mean, 0.5, 5 * 6.5e-4);
  EXPECT_NEAR(var, 1.0 / 12.0, 5 * 2.0e-4);
  for (int i = 0; i < 1000; ++i) {
    const double v = r.uniform(-2.0, 3.0);
    ASSERT_GE(v, -2.0);
    ASSERT_LE(v, 3.0);
  }
}

TEST(Rng, BelowIsUniformByChiSquare) {
  Rng r(5);
  const int k = 7, n = 70000;
  std::array<int, k> counts{};
  for (int i = 0; i < n; ++i) ++counts[r.below(k)];
  double chi2 = 0;
  for (int c : counts) chi2 += (c - n / k) * double(c - n / k) / (n / k);
  // 6 degrees of freedom: P(chi2 > 22.46) = 0.001.
  EXPECT_LT(chi2, 22.46);
}

TEST(Rng, NormalMomentsAndTail) {
  Rng r(9);
  const int n = 200000;
  double sum = 0, sum2 = 0, sum4 = 0;
  int beyond2 = 0;
  for (int i = 0; i < n; ++i) {
    const double z = r.normal();
    sum += z;
    sum2 += z * z;
    sum4 += z * z * z * z;
    beyond2 += std::abs(z) > 2.0;
  }
  EXPECT_NEAR(sum / n, 0.0, 5 / std::sqrt(double(n)));
  EXPECT_NEAR(sum2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(sum4 / n, 3.0, 5 * std::sqrt(96.0 / n));
  // P(|z| > 2) = 0.0455.
  EXPECT_NEAR(double(beyond2) / n, 0.0455, 5 * std::sqrt(0.0455 * 0.9545 / n));
  EXPECT_NEAR(Rng(3).normal(10.0, 0.0), 10.0, 0.0);
}

}  // namespace
}  // namespace gpm
