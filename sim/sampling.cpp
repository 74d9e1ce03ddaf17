#include "sim/sampling.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/kinematics.hpp"
#include "sim/oracle_command.hpp"

namespace gpm::sim {
namespace {

// Servo ticks in a duration (at least one).
long ticks_in(const TwinModel& model, double seconds) {
  const double period = model.timestep_s() * model.steps_per_tick();
  return std::max(1L, std::lround(seconds / period));
}

}  // namespace

void TrajectoryLog::add(const LogRow& row) {
  ++count;
  max_violation_m = std::max(max_violation_m, row.violation_m);
  max_torque = std::max(max_torque, row.torque.cwiseAbs().maxCoeff());
  if (sink) sink(row);
  if (keep_rows) rows.push_back(row);
}

Session make_session(const TwinModel& model, TwinState& state, const Robot& controller,
                     TrajectoryLog* log) {
  return Session{model, state, controller, log, controller.home};
}

TwinSnapshot advance(Session& s, const PathPoint& desired) {
  const Geometry& g = s.controller.geometry;
  const JointAngles q = inverse_kinematics(g, desired.p, s.controller.branch);
  JointCommand c = command_at(s.controller, q, desired);
  const Eigen::Vector3d dth(g.dth_(0), g.dth_(1), g.dth_(2));
  if (s.oracle) c.position = oracle_readings(s.model, q.theta_a, dth);
  else if (s.readings_for) c.position = s.readings_for(q.theta_a, dth);
  twin_command(s.state, c.position, c.velocity);
  s.desired = desired.p;
  // Align to the drive loop so the first step below is a tick.
  while (s.state.steps % s.model.steps_per_tick() != 0) twin_step(s.model, s.state);
  twin_step(s.model, s.state);
  const TwinSnapshot snap = s.state.last;
  for (int k = 1; k < s.model.steps_per_tick(); ++k) twin_step(s.model, s.state);
  if (s.log) {
    const long tick = s.state.steps / s.model.steps_per_tick() - 1;
    if (tick % s.log->every == 0) {
      s.log->add(LogRow{snap.time_s, desired.p, snap.ee_mm, snap.readings, snap.torque, snap.violation_m,
                        snap.growth, snap.growth_base});
    }
  }
  if (s.max_tracking_mm > 0.0) {
    const Geometry& g = s.controller.geometry;
    const auto fk = forward_kinematics(g, active_from_readings(g, snap.readings));  // eq. 32-35
    if (fk && (fk->p - desired.p).norm() > s.max_tracking_mm) {
      throw TrackingStop(fmt::format(
          "tracking: at t = {:.3f} s the end-effector from the readings (controller's model) is at ({:.3f}, {:.3f}) mm, "
          "{:.1f} mm from the plan ({:.3f}, {:.3f}), beyond servo.max_tracking_mm {:.4g} mm: drives stopped",
          snap.time_s, fk->p.x(), fk->p.y(), (fk->p - desired.p).norm(), desired.p.x(), desired.p.y(),
          s.max_tracking_mm));
    }
  }
  return snap;
}

void follow_path(Session& s, const Path& path) {
  const double period = s.model.timestep_s() * s.model.steps_per_tick();
  const long n = ticks_in(s.model, path_duration(path));
  for (long k = 0; k <= n; ++k) advance(s, path_at(path, k * period));
}

SampleRecord take_sample(Session& s, const Eigen::Vector2d& target, long id,
                         const SamplingOptions& o) {
  const double period = s.model.timestep_s() * s.model.steps_per_tick();
  follow_path(s, make_move(s.desired, target, o.move_speed_mm_s));
  const PathPoint hold{target, Eigen::Vector2d::Zero()};
  SampleRecord rec;
  rec.id = id;
  rec.target = target;
  // Settle: every joint slower than the threshold for hold_s.
  const long need = ticks_in(s.model, o.settle.hold_s);
  const long limit = ticks_in(s.model, o.settle.timeout_s);
  long calm = 0, k = 0;
  for (; k < limit && calm < need; ++k) {
    const TwinSnapshot snap = advance(s, hold);
    calm = snap.velocity.cwiseAbs().maxCoeff() < o.settle.velocity_rad_s ? calm + 1 : 0;
  }
  rec.settled = calm >= need;
  rec.settle_time_s = k * period;
  // Average over the window; readings unwrapped around the first one.
  const long n = ticks_in(s.model, o.average_s);
  rec.t_s = s.state.data->time + 0.5 * static_cast<double>(n) * period;
  Eigen::Vector3d first = Eigen::Vector3d::Zero(), sum_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_a = Eigen::Vector3d::Zero(), sum_tau = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_w = Eigen::Vector3d::Zero();
  Eigen::Vector2d sum_xy = Eigen::Vector2d::Zero();
  for (long j = 0; j < n; ++j) {
    const TwinSnapshot snap = advance(s, hold);
    if (j == 0) first = snap.readings;
    for (int i = 0; i < 3; ++i) sum_m[i] += wrap_pi(snap.readings[i] - first[i]);
    sum_a += snap.theta_a;
    sum_tau += snap.torque;
    sum_w += snap.velocity;
    sum_xy += snap.ee_mm;
  }
  for (int i = 0; i < 3; ++i) rec.theta_m[i] = wrap_2pi(first[i] + sum_m[i] / n);
  rec.theta_a = sum_a / n;
  rec.tau = sum_tau / n;
  rec.tau_last = rec.tau;
  rec.tau_between = rec.tau;
  rec.omega = sum_w / n;
  rec.xy_mm = sum_xy / n;
  return rec;
}

}  // namespace gpm::sim
