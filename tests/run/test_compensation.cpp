// Tests of run/compensation.cpp: the internal-preload projection by
// hand, the twin's accuracy with the true model against a wrong one, and
// the test poses visited in a short tour whatever their order, the oracle's
// floor below the true geometry's alone on a twin with encoder errors, and
// the bootstrap interval of an RMS ratio against hand-worked cases.
#include "run/compensation.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::scenario {
namespace {

TEST(Compensation, PreloadIsTheNullSpaceComponentOfTheTorques) {
  const Robot r;
  const Eigen::Vector2d p(230, 240);
  const JointAngles q = inverse_kinematics(r.geometry, p, r.branch);
  const Matrix32d J = active_jacobian(r.geometry, q);
  // Torques J f (any f) only push the end-effector: no preload.
  EXPECT_NEAR(internal_preload(r.geometry, p, J * Eigen::Vector2d(3.0, -1.0), r.branch), 0.0, 1e-12);
  // The null space of J' (the cross product of J's columns) is pure preload.
  const Eigen::Vector3d n = J.col(0).cross(J.col(1)).normalized() * 2.5;
  EXPECT_NEAR(internal_preload(r.geometry, p, n, r.branch), 2.5, 1e-12);
  // Superposition: only the null-space part counts.
  EXPECT_NEAR(internal_preload(r.geometry, p, n + J * Eigen::Vector2d(1, 1), r.branch), 2.5, 1e-9);
}

TEST(Compensation, TrueModelIsAccurateAndAWrongOneIsNot) {
  Robot actual;
  actual.geometry[kLb2] = 244.3;
  actual.geometry[kDth1] = 0.004;
  sim::TwinConfig twin;
  twin.encoder.bits = 0;
  CompensationPlan plan;
  plan.poses = {{216.5, 250}, {250, 280}, {190, 220}};
  plan.path = sim::CirclePath{{216.5, 250}, 30.0, 3.0, 0.25};
  const Accuracy good = measure_accuracy(actual, twin, actual, plan, 1, "true");
  const Accuracy bad = measure_accuracy(actual, twin, Robot{}, plan, 1, "nominal");
  ASSERT_EQ(good.static_error_um.size(), 3u);
  EXPECT_LT(good.static_rms_um, 1.0);
  EXPECT_LT(good.static_preload_rms_nm, 1e-3);
  // 4 mrad at a 244 mm link moves the end-effector by roughly a millimetre.
  EXPECT_GT(bad.static_rms_um, 300.0);
  EXPECT_GT(bad.static_preload_rms_nm, 100 * good.static_preload_rms_nm);
  EXPECT_GT(bad.path_rms_um, 10 * good.path_rms_um);
  EXPECT_FALSE(good.path_log.rows.empty());
}

// The floor's oracle knows the twin's encoder error: with one of 5e-5 rad
// per chain the true geometry alone stands off by it (about 12 um at the
// links), the oracle by the drives' resolution.
TEST(Compensation, TheOracleKnowsTheEncodersErrors) {
  const Robot actual;
  sim::TwinConfig twin;
  twin.encoder.bits = 0;
  for (std::size_t k = 0; k < 3; ++k)
    twin.effects.encoder_cyclic_rad[k] = 5e-5, twin.effects.encoder_phase_rad[k] = 0.7 * static_cast<double>(k);
  CompensationPlan plan;
  plan.poses = {{216.5, 250}, {250, 280}, {190, 220}};
  plan.path = sim::CirclePath{{216.5, 250}, 30.0, 3.0, 0.25};
  const Accuracy geometry = measure_accuracy(actual, twin, actual, plan, 1, "true");
  const Accuracy oracle = measure_accuracy(actual, twin, actual, plan, 1, "oracle", nullptr, 0.0, true);
  EXPECT_GT(geometry.static_rms_um, 3.0);
  EXPECT_LT(oracle.static_rms_um, 1.0);
}

// The interval of rms(a) / rms(b): a fixed multiple has no spread; equal
// errors give an interval round 1; it holds the ratio of the whole sample
// and narrows with more poses; bad input is refused.
TEST(Compensation, RatioIntervalOfPairedErrors) {
  const std::vector<double> b = {1.0, 2.0, 3.0, 4.0, 5.0, 6.0};
  std::vector<double> a = b;
  for (double& v : a) v *= 1.5;
  const auto fixed = rms_ratio_interval(a, b, 7);
  EXPECT_NEAR(fixed[0], 1.5, 1e-12);
  EXPECT_NEAR(fixed[1], 1.5, 1e-12);
  Rng rng(3);
  std::vector<double> x12, y12, x100, y100;
  for (int k = 0; k < 100; ++k) {
    const double u = rng.uniform(5.0, 15.0), v = rng.uniform(5.0, 15.0);
    (k < 12 ? x12 : x100).push_back(u), (k < 12 ? y12 : y100).push_back(v);
  }
  x100.insert(x100.end(), x12.begin(), x12.end()), y100.insert(y100.end(), y12.begin(), y12.end());
  const auto rms_of = [](const std::vector<double>& v) {
    double s = 0.0;
    for (double e : v) s += e * e;
    return std::sqrt(s / static_cast<double>(v.size()));
  };
  const auto few = rms_ratio_interval(x12, y12, 7), many = rms_ratio_interval(x100, y100, 7);
  for (const auto& [ci, x, y] : {std::tuple{few, x12, y12}, std::tuple{many, x100, y100}}) {
    EXPECT_LT(ci[0], rms_of(x) / rms_of(y));
    EXPECT_GT(ci[1], rms_of(x) / rms_of(y));
    EXPECT_LT(ci[0], 1.0);  // the same spread of errors: 1 within
    EXPECT_GT(ci[1], 1.0);
  }
  EXPECT_LT(many[1] - many[0], 0.6 * (few[1] - few[0]));
  EXPECT_EQ(rms_ratio_interval(x12, y12, 7), few);  // seeded
  EXPECT_THROW(rms_ratio_interval(x12, y100, 7), InputError);
  EXPECT_THROW(rms_ratio_interval({}, {}, 7), InputError);
  EXPECT_THROW(rms_ratio_interval(x12, y12, 7, 10), InputError);
}

// The test poses are visited in a short tour from where the robot stands,
// their errors reported in the plan's order: the same poses listed in
// another order give the same error at each pose to the last bit.
TEST(Compensation, PosesAreVisitedInOneTourWhateverTheirOrder) {
  Robot actual;
  actual.geometry[kDth2] = 0.002;
  sim::TwinConfig twin;
  CompensationPlan plan;
  plan.poses = {{250, 280}, {190, 220}, {216.5, 250}, {240, 215}};
  plan.path = sim::CirclePath{{216.5, 250}, 10.0, 0.5, 0.25};
  CompensationPlan reversed = plan;
  std::reverse(reversed.poses.begin(), reversed.poses.end());
  const Accuracy a = measure_accuracy(actual, twin, Robot{}, plan, 7, "listed");
  const Accuracy b = measure_accuracy(actual, twin, Robot{}, reversed, 7, "reversed");
  ASSERT_EQ(a.static_error_um.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(a.static_error_um[k], b.static_error_um[3 - k]) << k;
  EXPECT_EQ(a.static_rms_um, b.static_rms_um);
  EXPECT_GT(a.static_rms_um, 100.0);  // the wrong offset shows at every pose
}

}  // namespace
}  // namespace gpm::scenario
