#include "hw/sampling_session.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "hw/cycle_clock.hpp"
#include "hw/hw_errors.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

// Encoder-space joint targets of the controller model at p, each taken
// within pi of near (readings wrap at 2 pi).
Eigen::Vector3d ik_readings(const Robot& c, const Eigen::Vector2d& p, const Eigen::Vector3d& near) {
  const JointAngles q = inverse_kinematics(c.geometry, p, c.branch);
  Eigen::Vector3d m = readings_from_active(c.geometry, q.theta_a);
  for (int i = 0; i < 3; ++i) m[i] = near[i] + wrap_pi(m[i] - near[i]);
  return m;
}

// Smooth 0..1 profile and its first two derivatives with respect to u = t / T.
double profile(double u) { return 0.5 * (1.0 - std::cos(std::numbers::pi * u)); }

class Runner {
 public:
  Runner(SafetySupervisor& hw, const SessionPlan& plan, const std::atomic<bool>* stop)
      : hw_(hw), plan_(plan), stop_(stop), c_(hw.controller()),
        clock_(hw.period_s(), hw.simulated_time()) {}

  void cycle(const Eigen::Vector3d& q) {
    if (stop_ && stop_->load()) {
      hw_.emergency_stop("stop requested (signal)");
      throw HardwareError("emergency stop requested: drives disabled");
    }
    state_ = hw_.read(clock_.now());
    HardwareCommand cmd;
    cmd.theta_m = q;
    cmd.mode = plan_.modes;
    hw_.write(cmd, clock_.now());
    command_ = q;
    clock_.wait_next();
  }

  // Duration of the straight move p0 -> p1 (blending out offset) that keeps
  // every joint within headroom of its velocity and acceleration limits and
  // the Cartesian peak speed at move_speed.
  double move_time(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, const Eigen::Vector3d& offset) {
    const int n = 40;
    std::vector<Eigen::Vector3d> q(n + 1);
    for (int k = 0; k <= n; ++k) {
      const double s = static_cast<double>(k) / n;
      q[k] = ik_readings(c_, p0 + s * (p1 - p0), command_) + (1.0 - s) * offset;
    }
    double T = std::numbers::pi / 2 * (p1 - p0).norm() / plan_.options.move_speed_mm_s;
    const SafetyLimits& L = hw_.limits();
    const double h = plan_.profile_headroom;
    for (int i = 0; i < 3; ++i) {
      double d1 = 0.0, d2 = 0.0;
      for (int k = 0; k <= n; ++k) {
        const int a = std::max(k - 1, 0), b = std::min(k + 1, n);
        d1 = std::max(d1, std::abs(q[b][i] - q[a][i]) * n / (b - a));
        if (k > 0 && k < n) d2 = std::max(d2, std::abs(q[k + 1][i] - 2 * q[k][i] + q[k - 1][i]) * n * n);
      }
      // s(t) = profile(t / T): ds/dt <= pi / (2T), d2s/dt2 <= pi^2 / (2T^2).
      T = std::max(T, std::numbers::pi / 2 * d1 / (h * L.max_velocity[i]));
      const double acc = d2 * std::numbers::pi * std::numbers::pi / 4 + d1 * std::numbers::pi * std::numbers::pi / 2;
      T = std::max(T, std::sqrt(acc / (h * L.max_acceleration[i])));
    }
    return std::max(T, 4 * hw_.period_s());
  }

  void move(const Eigen::Vector2d& p1) {
    const Eigen::Vector2d p0 = pose_;
    const Eigen::Vector3d offset = command_ - ik_readings(c_, p0, command_);
    const double T = move_time(p0, p1, offset);
    const long steps = static_cast<long>(std::ceil(T / hw_.period_s()));
    for (long k = 1; k <= steps; ++k) {
      const double s = profile(static_cast<double>(k) / steps);
      cycle(ik_readings(c_, p0 + s * (p1 - p0), command_) + (1.0 - s) * offset);
    }
    pose_ = p1;
  }

  // Holds the target until every joint is slower than the settle velocity for hold_s.
  void settle(long id) {
    const sim::SettleCriterion& c = plan_.options.settle;
    const double t0 = clock_.now();
    double still_since = -1.0;
    const Eigen::Vector3d q = command_;
    for (;;) {
      cycle(q);
      const bool still = state_.velocity.cwiseAbs().maxCoeff() < c.velocity_rad_s;
      if (!still) still_since = -1.0;
      else if (still_since < 0) still_since = clock_.now();
      if (still_since >= 0 && clock_.now() - still_since >= c.hold_s) return;
      if (clock_.now() - t0 > c.timeout_s) {
        throw HardwareError(fmt::format("sample {}: the joints did not settle within {} s (speeds "
                                        "{:.4f} {:.4f} {:.4f} rad/s)",
                                        id, c.timeout_s, state_.velocity[0], state_.velocity[1],
                                        state_.velocity[2]));
      }
    }
  }

  Eigen::Vector3d average() {
    const long n = std::max(1L, std::lround(plan_.options.average_s / hw_.period_s()));
    const Eigen::Vector3d q = command_;
    Eigen::Vector3d first = Eigen::Vector3d::Zero(), sum = Eigen::Vector3d::Zero();
    for (long k = 0; k < n; ++k) {
      cycle(q);
      if (k == 0) first = state_.theta_m;
      for (int i = 0; i < 3; ++i) sum[i] += first[i] + wrap_pi(state_.theta_m[i] - first[i]);
    }
    Eigen::Vector3d mean = sum / static_cast<double>(n);
    for (int i = 0; i < 3; ++i) mean[i] = wrap_2pi(mean[i]);
    return mean;
  }

  SessionResult run(SampleLog& log) {
    SessionResult r;
    if (hw_.state() == LifecycleState::kUnconfigured) hw_.configure();
    state_ = hw_.read(clock_.now());
    hw_.activate();
    command_ = state_.theta_m;
    const auto fk = forward_kinematics(c_.geometry, active_from_readings(c_.geometry, command_));
    if (!fk) throw HardwareError("the controller model has no forward kinematics at the current readings");
    pose_ = fk->p;
    for (size_t k = 0; k < plan_.poses.size(); ++k) {
      const long id = static_cast<long>(k);
      if (log.has(id)) {
        ++r.skipped;
        continue;
      }
      move(plan_.poses[k]);
      settle(id);
      log.append(id, average(), plan_.poses[k]);
      ++r.taken;
    }
    hw_.deactivate();
    r.duration_s = clock_.now();
    return r;
  }

 private:
  SafetySupervisor& hw_;
  const SessionPlan& plan_;
  const std::atomic<bool>* stop_;
  const Robot& c_;
  CycleClock clock_;
  HardwareState state_;
  Eigen::Vector3d command_ = Eigen::Vector3d::Zero();
  Eigen::Vector2d pose_ = Eigen::Vector2d::Zero();
};

}  // namespace

SessionResult run_sampling_session(SafetySupervisor& hw, const SessionPlan& plan, SampleLog& log,
                                   const std::atomic<bool>* stop) {
  // Every pose must be allowed before anything moves.
  for (size_t k = 0; k < plan.poses.size(); ++k) {
    const Robot& c = hw.controller();
    const Reach reach = check_reach(c, plan.poses[k]);
    std::string why = reach.ok ? "" : reach.reason;
    if (why.empty()) why = hw.check_pose(readings_from_active(c.geometry, reach.q.theta_a));
    if (!why.empty()) {
      throw InputError(fmt::format("pose {} ({}, {}) mm is outside the safety limits: {}", k,
                                   plan.poses[k].x(), plan.poses[k].y(), why));
    }
  }
  Runner runner(hw, plan, stop);
  try {
    SessionResult r = runner.run(log);
    hw.shutdown();
    return r;
  } catch (const CommandRejected& e) {
    hw.emergency_stop(e.what());
    hw.shutdown();
    throw HardwareError(fmt::format("{} ({} samples kept in {})", e.what(), log.size(), log.path()));
  } catch (const HardwareError& e) {
    hw.emergency_stop(e.what());
    hw.shutdown();
    throw HardwareError(fmt::format("{}: drives disabled; {} samples kept in {} (rerun with --resume "
                                    "to continue)",
                                    e.what(), log.size(), log.path()));
  } catch (const LifecycleError& e) {
    hw.emergency_stop(e.what());
    hw.shutdown();
    throw HardwareError(fmt::format("{}: drives disabled; {} samples kept in {}", e.what(),
                                    log.size(), log.path()));
  }
}

}  // namespace gpm::hw
