// The controller's side of the twin: drive commands from inverse kinematics of
// the *controller's* model (nominal or calibrated), never of the actual one,
// so miscalibration shows as fighting servos, preload and end-effector error.
#pragma once

#include <Eigen/Core>

#include "models/kinematics.hpp"
#include "models/robot.hpp"
#include "sim/trajectory.hpp"

namespace gpm::sim {

// Position commands (encoder reading frame, rad in [0, 2 pi)) and velocity
// feed-forward (rad/s) for the three drives.
struct JointCommand {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
};

// Commands for a desired end-effector point: theta_a by IK of controller
// (eq. 31), reading = theta_a - dth (eq. 35), rate = J v with J the active
// Jacobian (eq. 11). Throws ReachError if the point is out of reach.
JointCommand command_for(const Robot& controller, const PathPoint& target);

// The same from the joint angles q that inverse kinematics of controller gave
// for target (a caller that needs q itself solves it once).
JointCommand command_at(const Robot& controller, const JointAngles& q, const PathPoint& target);

}  // namespace gpm::sim
