// Tests of render/mechanism_pose.cpp: re-posing MuJoCo from log rows.
#include <gtest/gtest.h>

#include "models/mjcf.hpp"
#include "render/mechanism_pose.hpp"
#include "render_test_util.hpp"
#include "sim/mujoco_util.hpp"

namespace gpm::render {
namespace {

TEST(MechanismPose, RowAtPicksTheLastRowNotAfterT) {
  sim::TrajectoryLog log;
  for (int k = 0; k < 5; ++k) {
    sim::LogRow r;
    r.t = 0.1 * k;
    log.rows.push_back(r);
  }
  EXPECT_EQ(row_at(log, -1.0).t, 0.0);
  EXPECT_EQ(row_at(log, 0.0).t, 0.0);
  EXPECT_DOUBLE_EQ(row_at(log, 0.25).t, 0.2);
  // The row logged at 0.1 * 3 = 0.30000000000000004 is at 0.3 (within kSameTime_s),
  // as the frame time of a part logged from elsewhere is summed otherwise.
  EXPECT_DOUBLE_EQ(row_at(log, 0.3).t, 0.1 * 3);
  EXPECT_DOUBLE_EQ(row_at(log, 0.3 - 2 * kSameTime_s).t, 0.2);
  EXPECT_DOUBLE_EQ(row_at(log, 9.0).t, 0.4);
}

// Re-posed from a logged row, MuJoCo's end-effector site sits at the logged
// true position and both loop closures are closed (independent of IK: the
// sites come from MuJoCo's forward kinematics of the bodies).
TEST(MechanismPose, ReposedModelPutsTheEndEffectorWhereTheLogSays) {
  const sim::SimulationResult& r = testing::run_of(testing::kLineScenario);
  const sim::ModelPtr m = sim::load_model_from_xml(r.model_xml);
  sim::DataPtr d(mj_makeData(m.get()));
  const JointAddresses adr = joint_addresses(m.get());
  const int ee = mj_name2id(m.get(), mjOBJ_SITE, "ee");
  const int tip2 = mj_name2id(m.get(), mjOBJ_SITE, "tip_b2");
  const int tip3 = mj_name2id(m.get(), mjOBJ_SITE, "tip_b3");
  ASSERT_GT(r.log.rows.size(), 100u);
  for (size_t k = 0; k < r.log.rows.size(); k += 37) {
    const sim::LogRow& row = r.log.rows[k];
    apply_pose(m.get(), d.get(), adr, pose_of(r.actual, row));
    const Eigen::Vector2d site(d->site_xpos[3 * ee] * 1e3, d->site_xpos[3 * ee + 1] * 1e3);
    EXPECT_LT((site - row.actual).norm(), 1e-6) << "row " << k;
    for (const int tip : {tip2, tip3}) {
      const Eigen::Vector2d t(d->site_xpos[3 * tip] * 1e3, d->site_xpos[3 * tip + 1] * 1e3);
      EXPECT_LT((t - site).norm(), 1e-6) << "row " << k;
    }
  }
}

// The active angles of the re-posed mechanism agree with the encoders (eq. 35)
// to within quantisation and noise.
TEST(MechanismPose, ActiveAnglesAgreeWithTheReadings) {
  const sim::SimulationResult& r = testing::run_of(testing::kLineScenario);
  for (size_t k = 0; k < r.log.rows.size(); k += 50) {
    const sim::LogRow& row = r.log.rows[k];
    const JointAngles q = pose_of(r.actual, row);
    const Eigen::Vector3d from_readings = active_from_readings(r.actual.geometry, row.readings);
    for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(wrap_pi(q.theta_a[i] - from_readings[i])), 2e-4);
  }
}

TEST(MechanismPose, UnreachableRowFallsBackToTheReadings) {
  const Robot robot;
  sim::LogRow row;
  const JointAngles home = inverse_kinematics(robot.geometry, robot.home);
  row.readings = readings_from_active(robot.geometry, home.theta_a);
  row.actual = {5000.0, 5000.0};
  const JointAngles q = pose_of(robot, row);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(wrap_pi(q.theta_a[i] - home.theta_a[i]), 0.0, 1e-12);
  const auto b = elbows(robot.geometry, q.theta_a);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d dir(std::cos(q.theta_b[i]), std::sin(q.theta_b[i]));
    EXPECT_NEAR(dir.dot((row.actual - b[i]).normalized()), 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace gpm::render
