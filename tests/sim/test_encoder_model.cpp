// Tests of sim/encoder_model.cpp: quantisation within half a count, wrapping
// to [0, 2 pi), eq. 35 with ideal encoders, seeded noise; behind a gear ratio
// N, 2^bits N counts per joint revolution.
#include "sim/encoder_model.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gpm::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Distance between two angles on the circle.
double circ(double a, double b) {
  const double d = std::fmod(std::abs(a - b), kTwoPi);
  return std::min(d, kTwoPi - d);
}

TEST(EncoderModel, CountIsTwoPiOverTwoToTheBits) {
  EXPECT_DOUBLE_EQ((EncoderModel{17, 0.0}.count_rad()), kTwoPi / 131072.0);
  EXPECT_EQ((EncoderModel{0, 0.0}.count_rad()), 0.0);
}

TEST(EncoderModel, QuantisationErrorIsAtMostHalfACountAndReadingsAreWholeCounts) {
  for (int bits : {8, 13, 17, 20}) {
    const EncoderModel m{bits, 0.0};
    const double q = m.count_rad();
    Rng rng(static_cast<std::uint64_t>(bits));
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
      const double a = rng.uniform(-20.0, 20.0);
      const double r = quantise_reading(m, a);
      ASSERT_GE(r, 0.0);
      ASSERT_LT(r, kTwoPi);
      const double counts = r / q;
      ASSERT_NEAR(counts, std::round(counts), 1e-6);
      worst = std::max(worst, circ(r, a));
    }
    EXPECT_LE(worst, 0.5 * q * (1 + 1e-9)) << bits << " bits";
    EXPECT_GT(worst, 0.45 * q) << "the error should use the whole half count";
  }
}

TEST(EncoderModel, GearRatioGivesTwoToTheBitsTimesRatioCountsPerJointRevolution) {
  const EncoderModel m{17, 0.0};
  Rng rng(3);
  for (double ratio : {10.0, 50.0, 121.0 / 12.0}) {
    const double q = kTwoPi / (131072.0 * ratio);  // a motor count seen at the joint
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
      const double a = rng.uniform(-10.0, 10.0);
      const double r = quantise_reading(m, a, ratio);
      ASSERT_GE(r, 0.0);
      ASSERT_LT(r, kTwoPi);
      worst = std::max(worst, circ(r, a));
    }
    EXPECT_LE(worst, 0.5 * q * (1 + 1e-6)) << ratio;
    EXPECT_GT(worst, 0.45 * q) << ratio;
  }
  // A whole ratio: every reading is a whole number of joint counts.
  for (int k = 0; k < 1000; ++k) {
    const double r = quantise_reading(m, rng.uniform(0.0, kTwoPi), 10.0);
    ASSERT_NEAR(r / (kTwoPi / (131072.0 * 10.0)), std::round(r / (kTwoPi / (131072.0 * 10.0))), 1e-6);
  }
}

TEST(EncoderModel, TopCountWrapsToZero) {
  const EncoderModel m{17, 0.0};
  EXPECT_EQ(quantise_reading(m, kTwoPi - 0.1 * m.count_rad()), 0.0);
  EXPECT_EQ(quantise_reading(m, -0.1 * m.count_rad()), 0.0);
}

TEST(EncoderModel, IdealReadingPlusOffsetIsTheTrueAngle) {
  const EncoderModel m{0, 0.0};
  EncoderNoise n(1);
  for (double theta : {0.3, 1.1111, 3.11, 4.82, 7.0, -1.0}) {
    for (double dth : {0.0, 0.012, -0.5}) {
      const double r = encoder_reading(m, n, theta, dth);
      EXPECT_GE(r, 0.0);
      EXPECT_LT(r, kTwoPi);
      EXPECT_LT(circ(r + dth, theta), 1e-14);  // eq. 35
    }
  }
}

TEST(EncoderModel, NoiseIsSeededAndHasTheConfiguredSpread) {
  const EncoderModel m{0, 1e-3};
  EncoderNoise a(42), b(42), c(43);
  double sum = 0.0, sum2 = 0.0;
  bool differs = false;
  const int n = 20000;
  for (int k = 0; k < n; ++k) {
    const double ra = encoder_reading(m, a, 2.0, 0.0);
    EXPECT_EQ(ra, encoder_reading(m, b, 2.0, 0.0));
    differs |= ra != encoder_reading(m, c, 2.0, 0.0);
    sum += ra - 2.0;
    sum2 += (ra - 2.0) * (ra - 2.0);
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / n, 0.0, 5 * 1e-3 / std::sqrt(n));
  EXPECT_NEAR(std::sqrt(sum2 / n), 1e-3, 0.03e-3);
}

TEST(EncoderModel, NoNoiseDrawsNothing) {
  const EncoderModel m{17, 0.0};
  EncoderNoise a(5), b(5);
  encoder_reading(m, a, 1.0, 0.0);
  EXPECT_EQ(a.rng(), b.rng());
}

}  // namespace
}  // namespace gpm::sim
