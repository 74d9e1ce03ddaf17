#include "hw/safety_supervisor.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

constexpr double kRel = 1e-9;  // relative slack for floating-point comparisons

int position_count(const std::array<JointMode, 3>& mode) {
  int n = 0;
  for (JointMode m : mode) n += m == JointMode::kPosition;
  return n;
}

// The two joints in position mode (mode holds exactly two).
std::pair<int, int> position_pair(const std::array<JointMode, 3>& mode) {
  int i = -1, j = -1;
  for (int k = 0; k < 3; ++k)
    if (mode[k] == JointMode::kPosition) (i < 0 ? i : j) = k;
  return {i, j};
}

// Where the position-mode joints of mode at readings q put the controller's
// end-effector: three, forward kinematics (eq. 32-34); two, their passive
// circles in the assembly mode at home. nullopt when they cannot (collinear
// elbows, circles that do not meet) or fewer than two are in position.
std::optional<Eigen::Vector2d> driven_point(const Geometry& g, const Eigen::Vector3d& q,
                                            const std::array<JointMode, 3>& mode,
                                            const std::array<std::array<int, 3>, 3>& pair_mode) {
  const int n = position_count(mode);
  const Eigen::Vector3d theta_a = active_from_readings(g, q);
  if (n == 3) {
    if (const auto fk = forward_kinematics(g, theta_a)) return fk->p;
    return std::nullopt;
  }
  if (n != 2) return std::nullopt;
  const auto [i, j] = position_pair(mode);
  return forward_kinematics_two(g, theta_a, i, j, pair_mode[i][j]);
}

// Why the readings have left the plan (empty when they have not): the
// end-effector from the three readings with the controller model (the
// radical centre, eq. 32-35: the torque-off joints' readings too, so a
// five-bar that changed assembly mode shows) against the point the command in
// force puts it at (its position-mode joints; two: in their assembly mode at
// home). Not watched with fewer than two joints in position mode.
struct TrackingPoints {
  Eigen::Vector2d here = Eigen::Vector2d::Zero();  // from the readings
  Eigen::Vector2d plan = Eigen::Vector2d::Zero();  // where the command puts it
};
std::optional<TrackingPoints> tracking_points(const Robot& controller, const HardwareCommand& command,
                                              const std::array<std::array<int, 3>, 3>& pair_mode,
                                              const Eigen::Vector3d& reading) {
  if (position_count(command.mode) < 2) return std::nullopt;
  const Geometry& g = controller.geometry;
  const auto here = forward_kinematics(g, active_from_readings(g, reading));
  if (!here) return std::nullopt;
  const std::optional<Eigen::Vector2d> plan = driven_point(g, command.theta_m, command.mode, pair_mode);
  if (!plan) return std::nullopt;
  return TrackingPoints{here->p, *plan};
}

std::string tracking_violation(const Robot& controller, const SafetyLimits& limits, const HardwareCommand& command,
                               const std::array<std::array<int, 3>, 3>& pair_mode, const Eigen::Vector3d& reading) {
  const std::optional<TrackingPoints> t = tracking_points(controller, command, pair_mode, reading);
  if (!t) return {};
  const double d = (t->here - t->plan).norm();
  if (!(d > limits.max_tracking_mm)) return {};
  return fmt::format("tracking: the end-effector from the readings ({:.3f}, {:.3f}) mm is {:.1f} mm from where the "
                     "command puts it ({:.3f}, {:.3f}) mm (max_tracking {} mm): drives disabled",
                     t->here.x(), t->here.y(), d, t->plan.x(), t->plan.y(), limits.max_tracking_mm);
}

}  // namespace

std::optional<double> SafetySupervisor::tracking_mm(const Eigen::Vector3d& reading) const {
  if (state() != LifecycleState::kActive) return std::nullopt;
  const std::optional<TrackingPoints> t = tracking_points(controller_, last_, pair_mode_, reading);
  if (!t) return std::nullopt;
  return (t->here - t->plan).norm();
}

std::optional<Eigen::Vector2d> SafetySupervisor::commanded_point() const {
  if (state() != LifecycleState::kActive) return std::nullopt;
  return driven_point(controller_.geometry, last_.theta_m, last_.mode, pair_mode_);
}

SafetySupervisor::SafetySupervisor(std::unique_ptr<RobotHardware> backend, const Robot& controller,
                                   const SafetyLimits& limits, Clock& clock)
    : backend_(std::move(backend)), clock_(clock), controller_(controller), limits_(limits) {
  controller_.limits.reach_margin = limits.reach_margin_mm;
  controller_.limits.min_transmission = limits.min_transmission;
  controller_.limits.min_direct = limits.min_direct;
  dt_ = backend_->period_s();
  const JointAngles home = inverse_kinematics(controller_.geometry, controller_.home,
                                              controller_.branch);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != j)
        pair_mode_[i][j] = assembly_mode(controller_.geometry, home.theta_a, controller_.home, i, j);
}

std::string SafetySupervisor::check_joint_positions(const Eigen::Vector3d& q,
                                                    const std::array<JointMode, 3>& mode,
                                                    const char* what) const {
  return joint_limit_violation(limits_, q, mode, what);
}

std::string SafetySupervisor::check_workspace(const Eigen::Vector3d& q,
                                              const std::array<JointMode, 3>& mode,
                                              const char* what) const {
  const int n = position_count(mode);
  if (n < 2) return {};
  const Geometry& g = controller_.geometry;
  const Eigen::Vector3d theta_a = active_from_readings(g, q);
  const std::optional<Eigen::Vector2d> driven = driven_point(g, q, mode, pair_mode_);
  if (!driven) {
    if (n == 3) return fmt::format("{}: the elbows are collinear (no forward kinematics)", what);
    const auto [i, j] = position_pair(mode);
    return fmt::format("{}: passive links {} and {} cannot meet", what, i + 1, j + 1);
  }
  const Eigen::Vector2d p = *driven;
  JointAngles ik;  // the controller model's IK of p (check_reach's)
  const std::string why = workspace_violation(limits_, controller_, p, what, &ik);
  if (!why.empty()) return why;
  for (int k = 0; k < 3; ++k) {
    if (mode[k] != JointMode::kPosition) continue;
    const double d = std::abs(wrap_pi(ik.theta_a[k] - theta_a[k]));
    if (d > limits_.max_inconsistency_rad) {
      return fmt::format("{}: joint {} is {:.6f} rad from the controller model's IK of ({:.3f}, "
                         "{:.3f}) mm (max_inconsistency {} rad): the servos would fight",
                         what, k + 1, d, p.x(), p.y(), limits_.max_inconsistency_rad);
    }
  }
  return {};
}

std::string SafetySupervisor::check_pose(const Eigen::Vector3d& theta_m) const {
  return check_pose(theta_m, {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition});
}

std::string SafetySupervisor::check_pose(const Eigen::Vector3d& theta_m,
                                         const std::array<JointMode, 3>& mode) const {
  std::string why = check_joint_positions(theta_m, mode, "position");
  if (why.empty()) why = check_workspace(theta_m, mode, "end-effector");
  return why;
}

std::string SafetySupervisor::check_path(const std::vector<Eigen::Vector3d>& q,
                                         const std::array<JointMode, 3>& mode) const {
  const double dt = period_s();
  Eigen::Vector3d v_prev = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < q.size(); ++k) {
    const std::string why = check_pose(q[k], mode);
    if (!why.empty()) return fmt::format("point {} of the path: {}", k, why);
    if (k == 0) continue;
    const Eigen::Vector3d v = (q[k] - q[k - 1]) / dt;
    for (int i = 0; i < 3; ++i) {
      if (mode[i] != JointMode::kPosition) continue;
      if (std::abs(v[i]) > limits_.max_velocity[i] * (1 + kRel))
        return fmt::format("point {} of the path: joint {} at {:.4f} rad/s, above max_velocity {} rad/s", k, i + 1,
                           v[i], limits_.max_velocity[i]);
      const double a = (v[i] - v_prev[i]) / dt;
      if (k >= 2 && std::abs(a) > limits_.max_acceleration[i] * (1 + kRel) + 1e-9)
        return fmt::format("point {} of the path: joint {} at {:.4f} rad/s^2, above max_acceleration {} rad/s^2", k,
                           i + 1, a, limits_.max_acceleration[i]);
    }
    v_prev = v;
  }
  return {};
}

std::string SafetySupervisor::check(const HardwareCommand& cmd) const {
  const int n = position_count(cmd.mode);
  if (n == 1) {
    return "exactly one joint in position mode leaves the mechanism free to move; command 0, 2 "
           "or 3 joints in position mode";
  }
  std::string why = check_joint_positions(cmd.theta_m, cmd.mode, "command");
  if (!why.empty()) return why;
  const Eigen::Vector3d& reading = last_state().theta_m;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  double stop_time = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (cmd.mode[i] != JointMode::kPosition) continue;
    const bool was_position = last_.mode[i] == JointMode::kPosition;
    const double prev = was_position ? last_.theta_m[i] : reading[i];
    const double v_prev = was_position ? last_velocity_[i] : 0.0;
    v[i] = (cmd.theta_m[i] - prev) / dt_;
    if (std::abs(v[i]) > limits_.max_velocity[i] * (1 + kRel)) {
      return fmt::format("joint {}: command step {:.6f} rad in {} s is {:.4f} rad/s, above "
                         "max_velocity {} rad/s{}",
                         i + 1, cmd.theta_m[i] - prev, dt_, v[i], limits_.max_velocity[i],
                         was_position ? "" : " (a joint enters position mode at its reading)");
    }
    const double a = (v[i] - v_prev) / dt_;
    if (std::abs(a) > limits_.max_acceleration[i] * (1 + kRel) + 1e-9) {
      return fmt::format("joint {}: command acceleration {:.4f} rad/s^2 is above "
                         "max_acceleration {} rad/s^2",
                         i + 1, a, limits_.max_acceleration[i]);
    }
    stop_time = std::max(stop_time, std::abs(v[i]) / limits_.max_acceleration[i]);
  }
  why = check_workspace(cmd.theta_m, cmd.mode, "commanded end-effector");
  if (!why.empty()) return why;
  if (stop_time > 0.0) {
    // Braking decelerates every joint along the same straight line in joint
    // space: its stopping point and midpoint must be allowed as well.
    const Eigen::Vector3d stop = cmd.theta_m + v * (stop_time / 2);
    why = check_joint_positions(stop, cmd.mode, "stopping point");
    if (why.empty()) why = check_workspace(stop, cmd.mode, "stopping point");
    if (why.empty()) why = check_workspace(cmd.theta_m + v * (stop_time / 4), cmd.mode,
                                           "braking path");
  }
  return why;
}

HardwareCommand SafetySupervisor::brake_command() const {
  HardwareCommand c = last_;
  double stop_time = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (c.mode[i] == JointMode::kPosition)
      stop_time = std::max(stop_time, std::abs(last_velocity_[i]) / limits_.max_acceleration[i]);
  }
  const double scale = stop_time > dt_ ? 1.0 - dt_ / stop_time : 0.0;
  for (int i = 0; i < 3; ++i) {
    if (c.mode[i] == JointMode::kPosition) c.theta_m[i] += last_velocity_[i] * scale * dt_;
  }
  return c;
}

template <class F>
void SafetySupervisor::timed(const char* what, F&& f) {
  const double t0 = clock_.now();
  f();
  if (backend_->simulated_time()) return;
  const double s = clock_.now() - t0;
  if (s > limits_.comms_timeout_s) {
    throw SafetyError(fmt::format("comms timeout: {} of {} took {:.1f} ms (comms_timeout {} ms)",
                                  what, backend_->describe(), s * 1e3,
                                  limits_.comms_timeout_s * 1e3));
  }
}

void SafetySupervisor::forward(const HardwareCommand& cmd, double time_s) {
  HardwareCommand sent = cmd;
  const Eigen::Vector3d& reading = last_state().theta_m;
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (sent.mode[i] == JointMode::kPosition) {
      const double prev =
          last_.mode[i] == JointMode::kPosition ? last_.theta_m[i] : reading[i];
      v[i] = (sent.theta_m[i] - prev) / dt_;
    } else {
      sent.theta_m[i] = reading[i];  // a disabled joint's target follows its reading
    }
  }
  timed("write", [&] { backend_->write(sent, time_s); });
  last_ = sent;
  last_velocity_ = v;
}

void SafetySupervisor::on_configure(HardwareState& initial) {
  backend_->configure();
  initial = backend_->last_state();
  previous_reading_ = initial;
  have_reading_ = true;
  last_ = HardwareCommand{};
  last_.theta_m = initial.theta_m;
}

void SafetySupervisor::on_activate(const HardwareState& current) {
  const std::string why = check_pose(current.theta_m);
  if (!why.empty()) {
    throw SafetyError("refusing to enable the drives: the robot is outside its safety limits: " +
                      why);
  }
  backend_->activate();
  last_ = hold_command(backend_->last_state().theta_m);
  last_velocity_.setZero();
  last_fresh_time_ = current.time_s;
  holding_ = false;
}

void SafetySupervisor::on_deactivate() {
  backend_->deactivate();
  last_.mode = {JointMode::kTorqueOff, JointMode::kTorqueOff, JointMode::kTorqueOff};
  last_velocity_.setZero();
}

void SafetySupervisor::on_shutdown() noexcept { backend_->shutdown(); }

void SafetySupervisor::on_error() noexcept {
  backend_->emergency_stop("safety supervisor stopped the robot");
}

void SafetySupervisor::on_reset() {
  if (backend_->state() == LifecycleState::kError) backend_->reset();
  have_reading_ = false;
}

void SafetySupervisor::on_read(double time_s, HardwareState& state) {
  timed("read", [&] { state = backend_->read(time_s); });
  for (int i = 0; i < 3; ++i) {
    const DriveStatus& d = state.drive[i];
    if (d.fault) {
      throw HardwareError(fmt::format("drive {} reports a fault (fault code 0x{:04x}, status "
                                      "word 0x{:04x})",
                                      i + 1, d.fault_code, d.status_word));
    }
    if (!std::isfinite(state.theta_m[i])) {
      throw HardwareError(fmt::format("drive {}: encoder reading is not a number", i + 1));
    }
  }
  if (have_reading_) {
    const double elapsed = std::max(state.time_s - previous_reading_.time_s, dt_);
    for (int i = 0; i < 3; ++i) {
      const double jump = std::abs(wrap_pi(state.theta_m[i] - previous_reading_.theta_m[i]));  // encoders wrap at 2 pi
      const double plausible = 4.0 * limits_.max_velocity[i] * elapsed + 0.05;
      if (jump > plausible) {
        throw HardwareError(fmt::format("drive {}: implausible encoder reading {:.6f} rad after "
                                        "{:.6f} rad {:.1f} ms earlier (garbage register value?)",
                                        i + 1, state.theta_m[i], previous_reading_.theta_m[i],
                                        elapsed * 1e3));
      }
    }
  }
  previous_reading_ = state;
  have_reading_ = true;
  if (this->state() != LifecycleState::kActive) return;
  for (int i = 0; i < 3; ++i) {
    if (last_.mode[i] == JointMode::kPosition && !state.drive[i].enabled) {
      throw HardwareError(fmt::format("drive {} disabled itself while commanded (status word "
                                      "0x{:04x})",
                                      i + 1, state.drive[i].status_word));
    }
  }
  const double since = time_s - last_fresh_time_;
  if (since > limits_.watchdog_disable_s) {
    throw SafetyError(fmt::format("command watchdog: no valid command for {:.3f} s "
                                  "(watchdog_disable {} s): drives disabled",
                                  since, limits_.watchdog_disable_s));
  }
  if (const std::string why = tracking_violation(controller_, limits_, last_, pair_mode_, state.theta_m);
      !why.empty())
    throw SafetyError(why);
  if (since > limits_.watchdog_hold_s) {
    holding_ = true;
    forward(brake_command(), time_s);
  }
}

void SafetySupervisor::on_write(const HardwareCommand& command, double time_s) {
  const std::string why = check(command);
  if (!why.empty()) {
    ++rejected_;
    holding_ = true;
    forward(brake_command(), time_s);
    throw CommandRejected("safety: command refused: " + why);
  }
  forward(command, time_s);
  last_fresh_time_ = time_s;
  holding_ = false;
}

}  // namespace gpm::hw
