// Tests of run/compensation.cpp: the internal-preload projection by
// hand, the twin's accuracy with the true model against a wrong one, and
// the test poses visited in a short tour whatever their order.
#include "run/compensation.hpp"

#include <algorithm>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "models/kinematics.hpp"

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
