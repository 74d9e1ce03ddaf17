// Safety limits (constant model) enforced by the SafetySupervisor, read from
// the `safety:` section of a hardware file. Every key is required (but
// max_tracking, whose default is itself a limit): a config that would command
// motion without its limits is refused (InputError, exit 2).
#pragma once

#include <array>
#include <string>

#include <Eigen/Core>
#include <yaml-cpp/yaml.h>

#include "hw/hardware_types.hpp"
#include "models/kinematics.hpp"
#include "models/parameters.hpp"
#include "models/robot.hpp"

namespace gpm::hw {

// Physically meaningful ranges of the limits (hw/README.md; a hardware file
// outside them is refused): joint limits within +-kJointBoundRad, speeds up
// to kMaxVelocityRadS, accelerations up to kMaxAccelerationRadS2, workspace
// radius and margins up to kMaxWorkspaceRadiusMm, centre within +-kMaxLengthMm.
inline constexpr double kJointBoundRad = 4 * 3.14159265358979323846;
inline constexpr double kMaxVelocityRadS = 20.0;
inline constexpr double kMaxAccelerationRadS2 = 500.0;
inline constexpr double kMaxWorkspaceRadiusMm = 500.0;
inline constexpr double kMaxLengthMm = 2000.0;

struct SafetyLimits {
  // Joint limits on the encoder readings theta_m (rad), per joint.
  std::array<double, kNumChains> joint_min{};
  std::array<double, kNumChains> joint_max{};
  // Commanded joint speed and acceleration limits (rad/s, rad/s^2), per joint.
  std::array<double, kNumChains> max_velocity{};
  std::array<double, kNumChains> max_acceleration{};
  // End-effector workspace: a disc (mm) the commanded position stays inside,
  // shrunk by workspace_margin_mm.
  Eigen::Vector2d workspace_centre = Eigen::Vector2d::Zero();
  double workspace_radius_mm = 0.0;
  double workspace_margin_mm = 0.0;
  // Chain annulus margin and singularity margins (models/robot.hpp Limits),
  // applied to the controller model.
  double reach_margin_mm = 0.0;
  double min_transmission = 0.0;
  double min_direct = 0.0;
  // Position-mode commands must agree with the controller model's IK of the
  // point they reach within this (rad): no servo fighting by command.
  double max_inconsistency_rad = 0.0;
  // Command watchdog: no fresh command for hold_s -> ramp to a stop and hold;
  // for disable_s -> disable the drives (error state).
  double watchdog_hold_s = 0.0;
  double watchdog_disable_s = 0.0;
  // A backend read or write taking longer than this is a comms failure (s).
  double comms_timeout_s = 0.0;
  // Tracking watch (optional key `max_tracking`, default 20 mm): while active,
  // the end-effector computed from the three readings with the controller
  // model (the radical centre, eq. 32-35) must stay within this of the one
  // the command in force puts it at; beyond it the drives are disabled.
  double max_tracking_mm = 20.0;

  bool operator==(const SafetyLimits&) const = default;
};

// Reads and validates a `safety:` map; every key is required. Throws
// InputError naming file, key path, what is wrong and what is valid.
SafetyLimits safety_limits_from_yaml(const YAML::Node& node, const std::string& file,
                                     const std::string& keypath);

// YAML text of the limits (a `safety:` body indented by indent).
std::string safety_limits_to_yaml(const SafetyLimits& limits, int indent);

// The pose checks of the supervisor (SafetySupervisor::check_pose and its
// command checks call these), as sentences naming `what`; empty when fine.
// The first joint in position mode whose reading q lies outside its limits.
std::string joint_limit_violation(const SafetyLimits& limits, const Eigen::Vector3d& q,
                                  const std::array<JointMode, 3>& mode, const char* what);
// End-effector point p outside the workspace disc (less its margin) or the
// controller's reach and singularity margins.
std::string workspace_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                                const char* what);
// workspace_violation that also gives the controller's IK of p when p passes
// (in *ik; the angles check_reach computes). Same verdict and sentence: a
// point the reach measures clear by a margin is passed without
// check_reach's singular value decompositions, any other is decided by it.
std::string workspace_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                                const char* what, JointAngles* ik);
// True if check_reach(robot, p).ok holds by a margin the measures' rounding
// cannot cross (then q is its IK); false when unsure or failing (ask check_reach).
bool clears_reach(const Robot& robot, const Eigen::Vector2d& p, JointAngles& q);
// A target p for the controller (its IK readings checked against the joint
// limits of the position-mode joints, p against the workspace): what a
// sampling pose must pass before the robot moves (run-time pose design uses it).
std::string target_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                             const std::array<JointMode, 3>& mode);

}  // namespace gpm::hw
