#include "hw/procedures/trajectory_session.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "hw/procedures/motion.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

constexpr double kSyncEvery_s = 0.1;  // samples reach the disk at least this often (path time)

long cycle_count(const TrajectoryPlan& plan, double period_s) {
  return std::max(1L, std::lround(sim::waypoint_duration(plan.path) / period_s));
}

// The last cycle sampled: the path's end, or plan.end_s's cycle before it.
long last_sampled_cycle(const TrajectoryPlan& plan, double period_s) {
  const long n = cycle_count(plan, period_s);
  return plan.end_s > 0.0 ? std::min(n, std::max(1L, std::lround(plan.end_s / period_s))) : n;
}

// Why a pose of the joint-space line q0 -> q1 (the move to the path's start,
// timed within the limits by Motion) is not allowed; empty when every one is.
std::string line_violation(const SafetySupervisor& hw, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1,
                           const std::array<JointMode, 3>& modes) {
  for (int k = 0; k <= 16; ++k) {
    const std::string why = hw.check_pose(q0 + (q1 - q0) * (k / 16.0), modes);
    if (!why.empty()) return why;
  }
  return {};
}

// Throws InputError unless a log that holds samples holds this plan's, all of them.
void check_resumed(const TrajectoryPlan& plan, double period_s, const SampleLog& log) {
  const long n = trajectory_sample_count(plan, period_s);
  if (log.size() == 0) return;
  if (static_cast<long>(log.size()) != n) {
    throw InputError(fmt::format("{}: holds {} of the {} samples of this path: a path sampled on the fly is one "
                                 "motion and cannot be continued; choose another output file",
                                 log.path(), log.size(), n));
  }
  for (const auto& [id, row] : log.recorded()) {
    Eigen::Vector2d p, v;
    sim::waypoint_at(plan.path, static_cast<double>(id * plan.every) * period_s, p, v);
    if (id < 0 || id >= n || !row.has_target || (row.target - p).norm() > 1e-9 * (1.0 + p.norm()))
      throw InputError(fmt::format("{}: sample {} is not where this path puts it: the file was recorded with "
                                   "another plan; choose another output file",
                                   log.path(), id));
  }
}

// Where the path ended early: its cycle and what the tracking watch measured
// (planned: at plan.end_s, not by the watch).
struct EarlyEnd {
  std::size_t cycle = 0;
  double tracking_mm = 0.0;
  bool planned = false;
};

// Follows the path from its start (the robot stands there), appending the
// samples to log; stops following (nullopt: it did not) at the first sample
// whose tracking passes plan.retreat_fraction of the watch's bound, or
// (planned) at the last sample before plan.end_s when it is set.
std::optional<EarlyEnd> follow_and_sample(Motion& motion, const TrajectoryPlan& plan,
                                          const std::vector<Eigen::Vector3d>& q, SampleLog& log,
                                          const SampleHook& on_sample) {
  const double period = motion.period_s();
  const double retreat_mm = plan.retreat_fraction * motion.hardware().limits().max_tracking_mm;
  const long sync_every = std::max(1L, std::lround(kSyncEvery_s / (plan.every * period)));
  const double t0 = motion.now();
  Eigen::Vector3d sum_between = Eigen::Vector3d::Zero(), last_torque = Eigen::Vector3d::Zero();
  long periods_between = 0, id = 0;
  const long every = std::max(1, plan.every);
  const std::size_t last = static_cast<std::size_t>(last_sampled_cycle(plan, period) / every * every);
  for (std::size_t k = 0; k < q.size(); ++k) {
    const double t = motion.now() - t0;
    motion.cycle(q[k]);
    const HardwareState& st = motion.state();  // read at t, the command before in force
    if (static_cast<long>(k) % plan.every != 0) {
      sum_between += st.torque;
      last_torque = st.torque;
      ++periods_between;
      continue;
    }
    SampleMotion m;
    m.t_s = t;
    m.t_read = st.read_time_s - Eigen::Vector3d::Constant(t0);
    m.tau = st.torque;
    m.tau_last = periods_between > 0 ? last_torque : st.torque;
    m.tau_between = periods_between > 0 ? Eigen::Vector3d(sum_between / static_cast<double>(periods_between))
                                        : st.torque;
    Eigen::Vector2d p, v;
    sim::waypoint_at(plan.path, static_cast<double>(k) * period, p, v);
    log.append(id, st.theta_m, p, m);
    if (on_sample) on_sample(id, 1);
    if (++id % sync_every == 0) log.sync();
    sum_between = st.torque;  // the sample's own cycle is the first of the next interval
    last_torque = st.torque;
    periods_between = 1;
    if (retreat_mm > 0.0) {
      const std::optional<double> d = motion.hardware().tracking_mm(st.theta_m);
      if (d && *d > retreat_mm) {
        log.sync();
        return EarlyEnd{k, *d, false};
      }
    }
    if (plan.end_s > 0.0 && k == last && k + 1 < q.size()) {
      log.sync();
      return EarlyEnd{k, 0.0, true};
    }
  }
  log.sync();
  return std::nullopt;
}

// From cycle k of q (the robot in motion along it) to rest at q's start: the
// path parameter slows linearly to rest over plan.stop_s, then the path is
// retraced at rest-to-rest timing within the limits' headroom (Motion::follow).
void retreat(Motion& motion, const TrajectoryPlan& plan, const std::vector<Eigen::Vector3d>& q, std::size_t k) {
  if (q.size() < 2) return;  // a path of one point: the robot is at its start
  const double last = static_cast<double>(q.size() - 1);
  const auto at = [&](double s) {  // q at a real cycle index, linear between cycles
    s = std::clamp(s, 0.0, last);
    const std::size_t i = std::min(static_cast<std::size_t>(s), q.size() - 2);
    return Eigen::Vector3d(q[i] + (s - static_cast<double>(i)) * (q[i + 1] - q[i]));
  };
  const long n = std::max(1L, std::lround(plan.stop_s / motion.period_s()));
  double s = static_cast<double>(k);
  for (long j = 1; j <= n; ++j) {
    const double jd = static_cast<double>(j);
    s = static_cast<double>(k) + jd - 0.5 * jd * jd / static_cast<double>(n);  // speed 1 - j / n
    motion.cycle(at(s));
  }
  const double s_end = s;
  const auto back = [&](double u) { return at(s_end * (1.0 - u)); };
  // The retraced path's shape, fine enough for its curvature (one point every 10 cycles).
  const long points = std::max(64L, std::lround(s_end / 10.0));
  std::vector<Eigen::Vector3d> shape;
  for (long i = 0; i <= points; ++i) shape.push_back(back(static_cast<double>(i) / static_cast<double>(points)));
  motion.follow(back, motion.path_time(shape, 0.0));
}

}  // namespace

long trajectory_sample_count(const TrajectoryPlan& plan, double period_s) {
  return last_sampled_cycle(plan, period_s) / std::max(1, plan.every) + 1;
}

std::vector<Eigen::Vector3d> trajectory_commands(const Robot& c, const TrajectoryPlan& plan, double period_s) {
  const long n = cycle_count(plan, period_s);
  std::vector<Eigen::Vector3d> q;
  q.reserve(static_cast<std::size_t>(n + 1));
  for (long k = 0; k <= n; ++k) {
    Eigen::Vector2d p, v;
    sim::waypoint_at(plan.path, static_cast<double>(k) * period_s, p, v);
    const Reach reach = check_reach(c, p);
    if (!reach.ok)
      throw InputError(fmt::format("the excitation path at {:.3f} s ({:.3f}, {:.3f}) mm: {}", k * period_s, p.x(),
                                   p.y(), reach.reason));
    Eigen::Vector3d m = readings_from_active(c.geometry, reach.q.theta_a);
    if (!q.empty())
      for (int i = 0; i < 3; ++i) m[i] = q.back()[i] + wrap_pi(m[i] - q.back()[i]);
    q.push_back(m);
  }
  return q;
}

void check_trajectory_plan(const SafetySupervisor& hw, const TrajectoryPlan& plan) {
  if (plan.every < 1) throw InputError(fmt::format("sample every {} cycles: expected 1 or more", plan.every));
  const double period = hw.period_s();
  const std::string why = hw.check_path(trajectory_commands(hw.controller(), plan, period), plan.modes);
  if (!why.empty())
    throw InputError(fmt::format("the excitation path at the hardware's {:g} Hz is outside the safety limits: {}",
                                 1.0 / period, why));
}

SessionResult run_trajectory_session(SafetySupervisor& hw, const TrajectoryPlan& plan, SampleLog& log,
                                     const std::atomic<bool>* stop, const SampleHook& on_sample) {
  check_trajectory_plan(hw, plan);
  const double period = hw.period_s();
  check_resumed(plan, period, log);
  SessionResult r;
  if (log.size() > 0) {  // a finished session: nothing to move
    r.skipped = static_cast<long>(log.size());
    return r;
  }
  std::vector<Eigen::Vector3d> q = trajectory_commands(hw.controller(), plan, period);
  Motion motion(hw, plan.modes, plan.profile_headroom, stop);
  std::optional<EarlyEnd> early;
  try {
    if (hw.state() == LifecycleState::kUnconfigured) hw.configure();
    const HardwareState& first = hw.read(0.0);
    if (!first.torque_reported)
      throw InputError(fmt::format("{}: the drives do not report their torque, which the calibration of samples on "
                                   "the fly needs (a register map's actual_torque); sample stop-and-go instead "
                                   "(sampling.pattern: designed)",
                                   hw.describe()));
    // The path in the turns the encoders read now, and the move to its start checked before it is made.
    const Eigen::Vector3d here = first.theta_m;
    Eigen::Vector3d turns = Eigen::Vector3d::Zero();
    for (int i = 0; i < 3; ++i) turns[i] = here[i] + wrap_pi(q[0][i] - here[i]) - q[0][i];
    for (Eigen::Vector3d& qk : q) qk += turns;
    const std::string why = line_violation(hw, here, q[0], plan.modes);
    if (!why.empty()) throw InputError(fmt::format("the move to the excitation path's start: {}", why));
    motion.start();
    motion.move_joints(q[0], plan.move_speed_mm_s);
    motion.settle(plan.settle, "the excitation path's start: ");
    const Eigen::Vector3d reading0 = motion.state().theta_m, command0 = motion.command();
    early = follow_and_sample(motion, plan, q, log, on_sample);
    motion.check_followed(reading0, command0, "the excitation path: ");
    if (early) retreat(motion, plan, q, early->cycle);
    motion.finish();
    r.taken = static_cast<long>(log.size());
    r.duration_s = motion.now();
    hw.shutdown();
    if (!early || early->planned) return r;
  } catch (const InputError&) {  // refused before moving (the torque, the move to the start)
    hw.shutdown();
    throw;
  } catch (...) {
    rethrow_session_error(hw, log);
  }
  throw PathEndedEarly(fmt::format(
      "tracking: the end-effector from the readings left its plan by {:.1f} mm at t = {:.3f} s of the path (beyond "
      "{:g} of max_tracking {:g} mm): sampling ended there and the robot retraced its path to the start, drives "
      "disabled; {} samples kept in {}",
      early->tracking_mm, static_cast<double>(early->cycle) * period, plan.retreat_fraction,
      hw.limits().max_tracking_mm, log.size(), log.path()), r.duration_s);
}

}  // namespace gpm::hw
