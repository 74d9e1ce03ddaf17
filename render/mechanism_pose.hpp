// Re-posing the MuJoCo mechanism from a trajectory log row: the joint angles
// of the actual (true) robot whose end-effector is at the logged true
// position, so the drawn chains close exactly on the drawn end-effector.
#pragma once

#include <array>

#include <mujoco/mujoco.h>

#include "models/kinematics.hpp"
#include "models/robot.hpp"
#include "sim/sampling.hpp"

namespace gpm::render {

// Times within this are the same instant (rows are at least a servo period apart).
inline constexpr double kSameTime_s = 1e-9;

// The log row shown at time t: the last row with row.t <= t + kSameTime_s
// (the first row before the log starts). The log must not be empty.
const sim::LogRow& row_at(const sim::TrajectoryLog& log, double t);

// Joint angles of the actual robot with the end-effector at row.actual (IK on
// the actual robot's branches). If that point is out of the actual robot's
// reach (it never is for a twin run), the active angles come from the
// readings (theta_a = theta_m + dth) and the passive ones point at row.actual.
JointAngles pose_of(const Robot& actual, const sim::LogRow& row);

// qpos addresses of joint_a1..3 and joint_b1..3 in a model built by
// mjcf_from_robot; throws sim::SimError if a joint is missing.
struct JointAddresses {
  std::array<int, 3> a{}, b{};
};
JointAddresses joint_addresses(const mjModel* m);

// Writes q into d->qpos (joint_a absolute, joint_b relative to its active
// link, as mjcf.hpp lays them out) and runs the kinematics (mj_kinematics,
// mj_camlight); velocities are zeroed.
void apply_pose(const mjModel* m, mjData* d, const JointAddresses& adr, const JointAngles& q);

}  // namespace gpm::render
