// Tests of sim/controller.cpp: commands are the controller's IK in the
// reading frame (eq. 35), the same from the solved angles, and the velocity
// feed-forward is d theta / dt.
#include "sim/controller.hpp"

#include <numbers>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"

namespace gpm::sim {
namespace {

TEST(Controller, PositionIsControllerIkMinusItsOffsets) {
  Robot ctrl;
  ctrl.geometry[kDth1] = 0.5;
  ctrl.geometry[kDth3] = -0.2;
  ctrl.geometry[kLa2] = 245.0;
  const Eigen::Vector2d p(230.0, 260.0);
  const JointCommand c = command_for(ctrl, {p, Eigen::Vector2d::Zero()});
  const JointAngles q = inverse_kinematics(ctrl.geometry, p, ctrl.branch);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(wrap_pi(c.position[i] + ctrl.geometry.dth_(i) - q.theta_a[i]), 0.0, 1e-14);
    EXPECT_GE(c.position[i], 0.0);
    EXPECT_LT(c.position[i], 2 * std::numbers::pi);
  }
  EXPECT_EQ(c.velocity.norm(), 0.0);
}

TEST(Controller, VelocityFeedForwardIsTheJointRate) {
  const Robot ctrl;
  const Eigen::Vector2d p(200.0, 240.0), v(30.0, -40.0);
  const double h = 1e-6;
  const auto qp = inverse_kinematics(ctrl.geometry, p + h * v, ctrl.branch);
  const auto qm = inverse_kinematics(ctrl.geometry, p - h * v, ctrl.branch);
  const Eigen::Vector3d fd = (qp.theta_a - qm.theta_a) / (2 * h);
  EXPECT_LT((command_for(ctrl, {p, v}).velocity - fd).norm(), 1e-6);
}

// From the joint angles inverse kinematics gave, the same commands, bit for bit.
TEST(Controller, CommandAtTheSolvedAnglesIsCommandFor) {
  Robot ctrl;
  ctrl.geometry[kDth2] = 0.3;
  const PathPoint target{{200.0, 240.0}, {30.0, -40.0}};
  const JointCommand a = command_for(ctrl, target);
  const JointCommand b = command_at(ctrl, inverse_kinematics(ctrl.geometry, target.p, ctrl.branch), target);
  EXPECT_EQ(a.position, b.position);
  EXPECT_EQ(a.velocity, b.velocity);
}

TEST(Controller, OutOfReachThrows) {
  EXPECT_THROW(command_for(Robot{}, {{216.5, 800.0}, {0, 0}}), ReachError);
}

}  // namespace
}  // namespace gpm::sim
