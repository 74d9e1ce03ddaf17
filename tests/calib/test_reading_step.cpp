// Tests of calib/reading_step.cpp: readings on a lattice give back its step
// (per joint offsets, a geared encoder's finer step, the coarsest joint's);
// readings off any lattice (averaged, noisy) or too few show none.
#include "calib/reading_step.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/rng.hpp"

namespace gpm::calib {
namespace {

// n readings along a smooth path, quantised to steps q (per joint) with offsets.
std::vector<Eigen::Vector3d> lattice_readings(int n, const Eigen::Vector3d& q, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Eigen::Vector3d> out;
  const Eigen::Vector3d offset(0.123, -1.7, 2.9);
  for (int j = 0; j < n; ++j) {
    Eigen::Vector3d m;
    for (int i = 0; i < 3; ++i) {
      const double a = 0.6 * std::sin(0.001 * j * (i + 1)) + rng.normal(0.0, 0.05);
      m[i] = offset[i] + q[i] * std::round(a / q[i]);
    }
    out.push_back(m);
  }
  return out;
}

TEST(ReadingStep, FindsTheLatticeStepOfEachEncoder) {
  const double q17 = 2.0 * M_PI / std::ldexp(1.0, 17);
  const auto joint = lattice_readings(10000, Eigen::Vector3d::Constant(q17), 1);
  ASSERT_TRUE(reading_step(joint).has_value());
  EXPECT_NEAR(*reading_step(joint), q17, 1e-6 * q17);
  const auto geared = lattice_readings(10000, Eigen::Vector3d::Constant(q17 / 10.0), 2);
  EXPECT_NEAR(*reading_step(geared), q17 / 10.0, 1e-6 * q17);
  const auto mixed = lattice_readings(10000, Eigen::Vector3d(q17 / 10.0, q17, q17 / 10.0), 3);
  EXPECT_NEAR(*reading_step(mixed), q17, 1e-6 * q17);  // the coarsest joint's
}

TEST(ReadingStep, ShowsNoStepOffALatticeOrWithTooFewReadings) {
  const double q17 = 2.0 * M_PI / std::ldexp(1.0, 17);
  auto noisy = lattice_readings(10000, Eigen::Vector3d::Constant(q17), 4);
  Rng rng(5);
  for (Eigen::Vector3d& m : noisy) m[1] += rng.normal(0.0, 0.1 * q17);
  EXPECT_FALSE(reading_step(noisy).has_value());
  EXPECT_FALSE(reading_step(lattice_readings(60, Eigen::Vector3d::Constant(q17), 6)).has_value());
}

}  // namespace
}  // namespace gpm::calib
