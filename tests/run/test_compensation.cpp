// Tests of run/compensation.cpp: the internal-preload projection by
// hand, the twin's accuracy with the true model against a wrong one, and
// the test poses visited in a short tour whatever their order, the oracle's
// floor below the true geometry's alone on a twin with encoder errors, the
// calibrated controller's compensation of its reading model's reducer error
// (as the oracle's) and the bootstrap interval of an RMS ratio against hand-worked cases.
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

// The calibrated controller compensates the drive-train harmonics of its
// reading model (calib::reading_at), in the calibration's convention: a
// harmonic of the reading twice per motor revolution referenced to 0 at the
// home readings. Given the twin's own reducer error in that convention
// (TE(theta_m) = A sin(2 N theta_m + phi), theta_m = r + dth, less its value
// at the motors' home: a = A cos(2 N dth + phi), b = A sin(2 N dth + phi),
// reducer_home_rad the home readings) it stands where the oracle does; the
// geometry alone stands off by the error, and so does the harmonic given
// with a mean of 0 (no home reading).
TEST(Compensation, TheCalibratedControllerCompensatesItsDriveTrainHarmonics) {
  const Robot actual;
  sim::TwinConfig twin;
  twin.encoder.bits = 0;
  twin.effects.gear_ratio = 10.0;
  twin.effects.mjcf.compliance_rad_per_Nm = {1e-4, 1e-4, 1e-4};  // the rotor a body of its own: a mesh between
  twin.servo_rate_hz = 4000.0;  // the main job's drive loop, fast enough for the rotor alone
  twin.mjcf.timestep_s = 0.00025;
  const std::array<double, 3> A{1.2e-4, 0.8e-4, 1.0e-4}, phi{0.3, 2.0, 4.1};
  calib::ReadingModel model;
  model.gear_ratio = 10.0;
  const JointAngles home = inverse_kinematics(actual.geometry, actual.home, actual.branch);
  const Eigen::Vector3d r_home = readings_from_active(actual.geometry, home.theta_a);
  for (std::size_t k = 0; k < 3; ++k) {
    twin.effects.drive.chain[k].te_motor_rad = A[k];
    twin.effects.drive.chain[k].te_motor_phase_rad = phi[k];
    const double psi = 2.0 * 10.0 * actual.geometry.dth_(static_cast<int>(k)) + phi[k];
    model.harmonic[calib::kReducerHarmonic][k] = A[k] * std::cos(psi);
    model.harmonic[calib::kReducerHarmonic][k + 3] = A[k] * std::sin(psi);
    model.reducer_home_rad[k] = wrap_2pi(r_home[static_cast<Eigen::Index>(k)]);
  }
  CompensationPlan plan;
  plan.poses = {{216.5, 250}, {250, 280}, {190, 220}, {230, 215}};
  plan.path = sim::CirclePath{{216.5, 250}, 30.0, 3.0, 0.25};
  const Accuracy geometry = measure_accuracy(actual, twin, actual, plan, 1, "true");
  const Accuracy oracle = measure_accuracy(actual, twin, actual, plan, 1, "oracle", nullptr, 0.0, true);
  const Accuracy compensated = measure_accuracy(actual, twin, actual, plan, 1, "calibrated", nullptr, 0.0, false, &model);
  calib::ReadingModel mean_zero = model;
  mean_zero.reducer_home_rad.fill(calib::kNotReferenced);
  const Accuracy unreferenced = measure_accuracy(actual, twin, actual, plan, 1, "mean 0", nullptr, 0.0, false, &mean_zero);
  EXPECT_GT(geometry.static_rms_um, 5.0);
  EXPECT_GT(unreferenced.static_rms_um, 5.0);
  EXPECT_LT(std::abs(compensated.static_rms_um - oracle.static_rms_um), 0.2);
  EXPECT_LT(compensated.static_rms_um, 0.1 * geometry.static_rms_um);
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
