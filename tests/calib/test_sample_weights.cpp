// Tests of calib/sample_weights.cpp: the variances a rotor that may rest and
// a force sign that may be wrong add, and the weight they give a sample,
// against hand-worked cases (at rest, far above the stick speed, a force at
// zero and far from it, the share through the sensitivities).
#include "calib/sample_weights.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::calib {
namespace {

constexpr double kSigma = 1e-5;

TEST(SampleWeights, StickSpeedIsAReadingStepPerSample) {
  EXPECT_DOUBLE_EQ(stick_speed(4.8e-5, 1e-3), 0.048);
  EXPECT_EQ(stick_speed(0.0, 1e-3), 0.0);
  EXPECT_EQ(stick_speed(4.8e-5, 0.0), 0.0);
}

TEST(SampleWeights, ARotorAtRestHasAThirdOfItsTwistSquared) {
  EXPECT_DOUBLE_EQ(rest_twist_variance(0.0, 3e-5, 0.05), 3e-10);
  const double t = std::tanh(1.0);
  EXPECT_NEAR(rest_twist_variance(-0.05, 3e-5, 0.05), 3e-10 * (1.0 - t * t), 1e-24);
  EXPECT_LT(rest_twist_variance(1.0, 3e-5, 0.05), 1e-25);  // sliding: no doubt
  EXPECT_EQ(rest_twist_variance(0.0, 3e-5, 0.0), 0.0);     // no stick speed
}

TEST(SampleWeights, AForceAtZeroFlipsHalfTheTime) {
  // p = 1/2: (2 k)^2 / 4 = k^2; at 2 sigma p = Phi(-2) = 0.02275.
  EXPECT_DOUBLE_EQ(sign_flip_variance(0.0, 0.4, 0.005), 0.005 * 0.005);
  const double p = 0.0227501319481792;
  EXPECT_NEAR(sign_flip_variance(-0.8, 0.4, 0.005), 4.0 * 0.005 * 0.005 * p * (1.0 - p), 1e-15);
  EXPECT_LT(sign_flip_variance(4.0, 0.4, 0.005), 1e-25);  // 10 sigma: certain
  EXPECT_EQ(sign_flip_variance(0.0, 0.0, 0.005), 0.0);    // no 1-sigma: the signs taken as certain
}

TEST(SampleWeights, TheWeightIsTheNoiseOverTheSamplesSigma) {
  // Variance sigma^2 added to the only reading the residual reads: weight 1 / sqrt(2).
  const Eigen::Vector3d v(kSigma * kSigma, 4e-10, 4e-10);
  EXPECT_NEAR(sample_weight({1.0, 0.0, 0.0}, v, kSigma), 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(sample_weight({2.0, 0.0, 0.0}, v, kSigma), 1.0 / std::sqrt(2.0), 1e-12);  // u normalised
  // Shared by the sensitivities: 0.36 v1 + 0.64 v2.
  EXPECT_NEAR(sample_weight({0.6, 0.8, 0.0}, v, kSigma),
              1.0 / std::sqrt(1.0 + (0.36 * 1e-10 + 0.64 * 4e-10) / (kSigma * kSigma)), 1e-12);
  EXPECT_EQ(sample_weight({0.6, 0.8, 0.0}, Eigen::Vector3d::Zero(), kSigma), 1.0);
  EXPECT_EQ(sample_weight({0.6, 0.8, 0.0}, v, 0.0), 1.0);
  EXPECT_EQ(sample_weight(Eigen::Vector3d::Zero(), v, kSigma), 1.0);
}

}  // namespace
}  // namespace gpm::calib
