#include "hw/safety_limits.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/yaml_util.hpp"

namespace gpm::hw {
namespace {

constexpr const char* kKeys =
    "joint_min, joint_max, max_velocity, max_acceleration, workspace_centre, workspace_radius, "
    "workspace_margin, reach_margin, min_transmission, min_direct, max_inconsistency, "
    "watchdog_hold, watchdog_disable, comms_timeout (and optionally max_tracking)";

YAML::Node required(const YAML::Node& node, const char* key, const std::string& file,
                    const std::string& kp) {
  const YAML::Node v = node[key];
  if (!v) {
    throw InputError(yaml_where(file, node, kp) +
                     fmt::format("missing key '{}' (every safety limit is required before "
                                 "anything moves; keys: {})",
                                 key, kKeys));
  }
  return v;
}

std::array<double, kNumChains> triple(const YAML::Node& node, const char* key,
                                      const std::string& file, const std::string& kp,
                                      bool positive) {
  const std::string path = kp + "." + key;
  const YAML::Node v = required(node, key, file, kp);
  if (!v.IsSequence() || v.size() != 3) {
    throw InputError(yaml_where(file, v, path) + "expected a list of three numbers, one per joint");
  }
  std::array<double, kNumChains> out{};
  for (size_t i = 0; i < 3; ++i) {
    const std::string p = fmt::format("{}[{}]", path, i);
    out[i] = positive ? yaml_positive(v[i], file, p) : yaml_number(v[i], file, p);
  }
  return out;
}

double scalar(const YAML::Node& node, const char* key, const std::string& file,
              const std::string& kp, double lo, double hi, const char* valid) {
  const std::string path = kp + "." + key;
  const YAML::Node v = required(node, key, file, kp);
  const double x = yaml_number(v, file, path);
  if (!(x >= lo && x <= hi)) {
    throw InputError(yaml_where(file, v, path) + fmt::format("must be {}, got {}", valid, x));
  }
  return x;
}

// The per-joint limits of node (keypath kp) into s: joint range, speed and
// acceleration, each within what this robot's servo joints can mean.
void parse_joint_limits(const YAML::Node& node, const std::string& file, const std::string& kp, SafetyLimits& s) {
  s.joint_min = triple(node, "joint_min", file, kp, false);
  s.joint_max = triple(node, "joint_max", file, kp, false);
  for (size_t i = 0; i < 3; ++i) {
    if (!(s.joint_max[i] > s.joint_min[i])) {
      throw InputError(yaml_where(file, node["joint_max"], kp + ".joint_max") +
                       fmt::format("joint {}: max {} must be above min {}", i + 1, s.joint_max[i],
                                   s.joint_min[i]));
    }
  }
  s.max_velocity = triple(node, "max_velocity", file, kp, true);
  s.max_acceleration = triple(node, "max_acceleration", file, kp, true);
  // Physically meaningful ranges (hw/README.md): the GPM2002's proximal links
  // are 244 mm, so 20 rad/s is about 5 m/s at the elbow.
  for (size_t i = 0; i < 3; ++i) {
    if (s.joint_min[i] < -kJointBoundRad || s.joint_max[i] > kJointBoundRad) {
      throw InputError(yaml_where(file, node[s.joint_min[i] < -kJointBoundRad ? "joint_min" : "joint_max"],
                                  kp + (s.joint_min[i] < -kJointBoundRad ? ".joint_min" : ".joint_max")) +
                       fmt::format("joint {}: limits must lie within [-{}, {}] rad (encoder angles "
                                   "are in [0, 2 pi))",
                                   i + 1, kJointBoundRad, kJointBoundRad));
    }
    if (s.max_velocity[i] > kMaxVelocityRadS) {
      throw InputError(yaml_where(file, node["max_velocity"], fmt::format("{}.max_velocity[{}]", kp, i)) +
                       fmt::format("{} rad/s is above {} rad/s (a servo joint of this robot; "
                                   "first runs use ~0.2)",
                                   s.max_velocity[i], kMaxVelocityRadS));
    }
    if (s.max_acceleration[i] > kMaxAccelerationRadS2) {
      throw InputError(yaml_where(file, node["max_acceleration"], fmt::format("{}.max_acceleration[{}]", kp, i)) +
                       fmt::format("{} rad/s^2 is above {} rad/s^2 (first runs use ~1)",
                                   s.max_acceleration[i], kMaxAccelerationRadS2));
    }
  }
}

// The workspace disc of node (keypath kp) into s: centre, radius and the margin inside it.
void parse_workspace(const YAML::Node& node, const std::string& file, const std::string& kp, SafetyLimits& s) {
  const YAML::Node c = required(node, "workspace_centre", file, kp);
  if (!c.IsSequence() || c.size() != 2) {
    throw InputError(yaml_where(file, c, kp + ".workspace_centre") +
                     "expected [x, y] in mm, e.g. [216.5, 250]");
  }
  s.workspace_centre = {yaml_number(c[0], file, kp + ".workspace_centre[0]"),
                        yaml_number(c[1], file, kp + ".workspace_centre[1]")};
  if (s.workspace_centre.cwiseAbs().maxCoeff() > kMaxLengthMm) {
    throw InputError(yaml_where(file, c, kp + ".workspace_centre") +
                     fmt::format("each coordinate must be within +-{} mm", kMaxLengthMm));
  }
  s.workspace_radius_mm = scalar(node, "workspace_radius", file, kp, 1e-9, kMaxWorkspaceRadiusMm,
                                 "a radius in (0, 500] mm (the base triangle is 433 x 500 mm)");
  s.workspace_margin_mm = scalar(node, "workspace_margin", file, kp, 0.0, kMaxWorkspaceRadiusMm, "in [0, 500] mm");
  if (s.workspace_margin_mm >= s.workspace_radius_mm) {
    throw InputError(yaml_where(file, node["workspace_margin"], kp + ".workspace_margin") +
                     fmt::format("must be below workspace_radius ({} mm)", s.workspace_radius_mm));
  }
}

// The watchdog, comms timeout and tracking bound of node (keypath kp) into s.
void parse_timing(const YAML::Node& node, const std::string& file, const std::string& kp, SafetyLimits& s) {
  s.watchdog_hold_s = scalar(node, "watchdog_hold", file, kp, 1e-6, 60.0, "in (0, 60] s");
  s.watchdog_disable_s = scalar(node, "watchdog_disable", file, kp, 1e-6, 600.0, "in (0, 600] s");
  if (s.watchdog_disable_s <= s.watchdog_hold_s) {
    throw InputError(yaml_where(file, node["watchdog_disable"], kp + ".watchdog_disable") +
                     fmt::format("must be longer than watchdog_hold ({} s)", s.watchdog_hold_s));
  }
  s.comms_timeout_s = scalar(node, "comms_timeout", file, kp, 1e-4, 10.0, "in [0.0001, 10] s");
  // The one optional key: its default is itself a limit (hw/README.md).
  if (node["max_tracking"])
    s.max_tracking_mm = scalar(node, "max_tracking", file, kp, 0.01, kMaxWorkspaceRadiusMm, "in [0.01, 500] mm");
}

}  // namespace

SafetyLimits safety_limits_from_yaml(const YAML::Node& node, const std::string& file,
                                     const std::string& keypath) {
  if (!node || node.IsNull()) {
    throw InputError(fmt::format("{}: missing section '{}' (a hardware config must give every "
                                 "safety limit before anything moves; keys: {})",
                                 file, keypath, kKeys));
  }
  yaml_check_keys(node, file, keypath,
                  {"joint_min", "joint_max", "max_velocity", "max_acceleration",
                   "workspace_centre", "workspace_radius", "workspace_margin", "reach_margin",
                   "min_transmission", "min_direct", "max_inconsistency", "watchdog_hold",
                   "watchdog_disable", "comms_timeout", "max_tracking"});
  const std::string& kp = keypath;
  SafetyLimits s;
  parse_joint_limits(node, file, kp, s);
  parse_workspace(node, file, kp, s);
  s.reach_margin_mm = scalar(node, "reach_margin", file, kp, 0.0, kMaxWorkspaceRadiusMm, "in [0, 500] mm");
  s.min_transmission = scalar(node, "min_transmission", file, kp, 0.0, 0.999, "in [0, 1)");
  s.min_direct = scalar(node, "min_direct", file, kp, 0.0, 0.999, "in [0, 1)");
  s.max_inconsistency_rad =
      scalar(node, "max_inconsistency", file, kp, 1e-12, 1.0, "in (0, 1] rad");
  parse_timing(node, file, kp, s);
  return s;
}

std::string safety_limits_to_yaml(const SafetyLimits& s, int indent) {
  const std::string pad(static_cast<size_t>(indent), ' ');
  auto t = [](const std::array<double, 3>& a) {
    return fmt::format("[{}, {}, {}]", format_exact(a[0]), format_exact(a[1]), format_exact(a[2]));
  };
  std::string out;
  out += fmt::format("{}joint_min: {}\n", pad, t(s.joint_min));
  out += fmt::format("{}joint_max: {}\n", pad, t(s.joint_max));
  out += fmt::format("{}max_velocity: {}\n", pad, t(s.max_velocity));
  out += fmt::format("{}max_acceleration: {}\n", pad, t(s.max_acceleration));
  out += fmt::format("{}workspace_centre: [{}, {}]\n", pad, format_exact(s.workspace_centre.x()),
                     format_exact(s.workspace_centre.y()));
  out += fmt::format("{}workspace_radius: {}\n", pad, format_exact(s.workspace_radius_mm));
  out += fmt::format("{}workspace_margin: {}\n", pad, format_exact(s.workspace_margin_mm));
  out += fmt::format("{}reach_margin: {}\n", pad, format_exact(s.reach_margin_mm));
  out += fmt::format("{}min_transmission: {}\n", pad, format_exact(s.min_transmission));
  out += fmt::format("{}min_direct: {}\n", pad, format_exact(s.min_direct));
  out += fmt::format("{}max_inconsistency: {}\n", pad, format_exact(s.max_inconsistency_rad));
  out += fmt::format("{}watchdog_hold: {}\n", pad, format_exact(s.watchdog_hold_s));
  out += fmt::format("{}watchdog_disable: {}\n", pad, format_exact(s.watchdog_disable_s));
  out += fmt::format("{}comms_timeout: {}\n", pad, format_exact(s.comms_timeout_s));
  out += fmt::format("{}max_tracking: {}\n", pad, format_exact(s.max_tracking_mm));
  return out;
}

std::string joint_limit_violation(const SafetyLimits& limits, const Eigen::Vector3d& q,
                                  const std::array<JointMode, 3>& mode, const char* what) {
  for (int i = 0; i < 3; ++i) {
    if (mode[i] != JointMode::kPosition) continue;
    if (!std::isfinite(q[i])) return fmt::format("joint {}: {} is not a finite number", i + 1, what);
    if (q[i] < limits.joint_min[i] || q[i] > limits.joint_max[i]) {
      return fmt::format("joint {}: {} {:.6f} rad is outside the joint limits [{}, {}]", i + 1, what, q[i],
                         limits.joint_min[i], limits.joint_max[i]);
    }
  }
  return {};
}

bool clears_reach(const Robot& robot, const Eigen::Vector2d& p, JointAngles& q) {
  const Geometry& g = robot.geometry;
  const double m = robot.limits.reach_margin;
  if (!p.allFinite()) return false;
  for (int i = 0; i < kNumChains; ++i) {  // the annulus of each chain, as check_reach
    const double d = (p - g.A(i)).norm();
    if (d > g.la_(i) + g.lb_(i) - m || d < std::abs(g.la_(i) - g.lb_(i)) + m) return false;
  }
  q = inverse_kinematics(g, p, robot.branch);
  if (!q.theta_a.allFinite() || !q.theta_b.allFinite()) return false;
  for (int i = 0; i < kNumChains; ++i)  // type 1: the expression of conditioning(), compared as check_reach does
    if (!(std::abs(std::sin(q.theta_a[i] - q.theta_b[i])) >= robot.limits.min_transmission)) return false;
  // Type 2: the smaller singular value of U (rows: the passive links' unit
  // directions) in closed form. U'U has trace 3 and, by Cauchy-Binet,
  // determinant sum_{i<j} sin^2(theta_b_i - theta_b_j), so sigma_min^2 =
  // det / lambda_max with no cancellation; it agrees with the SVD of
  // conditioning() to rounding, far inside the relative margin 1e-6.
  double a = 0.0, b = 0.0, c = 0.0, det = 0.0;
  for (int i = 0; i < kNumChains; ++i) {
    const double ci = std::cos(q.theta_b[i]), si = std::sin(q.theta_b[i]);
    a += ci * ci, b += ci * si, c += si * si;
    for (int j = i + 1; j < kNumChains; ++j) det += std::pow(std::sin(q.theta_b[i] - q.theta_b[j]), 2);
  }
  const double lambda_max = 0.5 * (a + c) + std::hypot(0.5 * (a - c), b);
  const double direct = std::sqrt(det / lambda_max) / std::sqrt(1.5);
  return direct > robot.limits.min_direct * (1.0 + 1e-6);
}

std::string workspace_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                                const char* what) {
  JointAngles ik;
  return workspace_violation(limits, controller, p, what, &ik);
}

std::string workspace_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                                const char* what, JointAngles* ik) {
  const double r = (p - limits.workspace_centre).norm();
  const double rmax = limits.workspace_radius_mm - limits.workspace_margin_mm;
  if (r > rmax) {
    return fmt::format("{} ({:.3f}, {:.3f}) mm is {:.3f} mm from the workspace centre, beyond "
                       "{:.3f} mm (radius minus margin)",
                       what, p.x(), p.y(), r, rmax);
  }
  if (clears_reach(controller, p, *ik)) return {};
  const Reach reach = check_reach(controller, p);
  if (!reach.ok) return fmt::format("{} ({:.3f}, {:.3f}) mm: {}", what, p.x(), p.y(), reach.reason);
  *ik = reach.q;
  return {};
}

std::string target_violation(const SafetyLimits& limits, const Robot& controller, const Eigen::Vector2d& p,
                             const std::array<JointMode, 3>& mode) {
  std::string why = workspace_violation(limits, controller, p, "target");
  if (!why.empty()) return why;
  const JointAngles q = inverse_kinematics(controller.geometry, p, controller.branch);
  return joint_limit_violation(limits, readings_from_active(controller.geometry, q.theta_a), mode, "target");
}

}  // namespace gpm::hw
