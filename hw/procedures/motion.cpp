#include "hw/procedures/motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {

double motion_profile(double u) { return 0.5 * (1.0 - std::cos(std::numbers::pi * u)); }

Motion::Motion(SafetySupervisor& hw, const std::array<JointMode, 3>& modes, double headroom,
               const std::atomic<bool>* stop)
    : hw_(hw), modes_(modes), headroom_(headroom), stop_(stop),
      clock_(hw.period_s(), hw.simulated_time(), hw.clock()) {}

void Motion::start() {
  if (hw_.state() == LifecycleState::kUnconfigured) hw_.configure();
  state_ = hw_.read(clock_.now());
  hw_.activate();
  command_ = state_.theta_m;
}

void Motion::finish() {
  if (hw_.state() == LifecycleState::kActive) hw_.deactivate();
}

void Motion::cycle(const Eigen::Vector3d& q) {
  if (stop_ && stop_->load()) {
    const std::string why = fmt::format("interrupted by {}", StopOnSignal::signal_name());
    hw_.emergency_stop(why);
    throw Interrupted(why + ": drives disabled");
  }
  state_ = hw_.read(clock_.now());
  HardwareCommand cmd;
  cmd.theta_m = q;
  cmd.mode = modes_;
  hw_.write(cmd, clock_.now());
  command_ = q;
  clock_.wait_next();
}

double Motion::path_time(const std::vector<Eigen::Vector3d>& q, double min_T) const {
  constexpr double kPi = std::numbers::pi;
  const int n = static_cast<int>(q.size()) - 1;
  const SafetyLimits& L = hw_.limits();
  double T = min_T;
  for (int i = 0; i < 3; ++i) {
    if (modes_[i] != JointMode::kPosition) continue;
    double d1 = 0.0, d2 = 0.0;
    for (int k = 0; k <= n; ++k) {
      const int a = std::max(k - 1, 0), b = std::min(k + 1, n);
      d1 = std::max(d1, std::abs(q[b][i] - q[a][i]) * n / (b - a));
      if (k > 0 && k < n) d2 = std::max(d2, std::abs(q[k + 1][i] - 2 * q[k][i] + q[k - 1][i]) * n * n);
    }
    // s(t) = profile(t / T): ds/dt <= pi / (2T), d2s/dt2 <= pi^2 / (2T^2).
    T = std::max(T, kPi / 2 * d1 / (headroom_ * L.max_velocity[i]));
    const double acc = d2 * kPi * kPi / 4 + d1 * kPi * kPi / 2;
    T = std::max(T, std::sqrt(acc / (headroom_ * L.max_acceleration[i])));
  }
  return std::max(T, 4 * hw_.period_s());
}

void Motion::follow(const std::function<Eigen::Vector3d(double)>& path, double T) {
  const long steps = static_cast<long>(std::ceil(T / hw_.period_s()));
  for (long k = 1; k <= steps; ++k) cycle(path(motion_profile(static_cast<double>(k) / steps)));
}

void Motion::move_joints(const Eigen::Vector3d& q1, double speed_mm_s) {
  const Eigen::Vector3d q0 = command_;
  std::vector<Eigen::Vector3d> path;
  for (int k = 0; k <= 8; ++k) path.push_back(q0 + (q1 - q0) * (k / 8.0));
  // The tip of a proximal link moves its length times the joint motion.
  const Geometry& g = hw_.controller().geometry;
  double link = 0.0;
  for (int i = 0; i < 3; ++i)
    if (modes_[i] == JointMode::kPosition) link = std::max(link, g[la(i)]);
  const double dist_mm = (q1 - q0).cwiseAbs().maxCoeff() * link;
  const double T = path_time(path, std::numbers::pi / 2 * dist_mm / speed_mm_s);
  follow([&](double s) { return Eigen::Vector3d(q0 + (q1 - q0) * s); }, T);
}

bool Motion::settle(const sim::SettleCriterion& c, const std::string& what, bool required) {
  const double t0 = clock_.now();
  double still_since = -1.0;
  const Eigen::Vector3d q = command_;
  for (;;) {
    cycle(q);
    const bool still = state_.velocity.cwiseAbs().maxCoeff() < c.velocity_rad_s;
    if (!still) still_since = -1.0;
    else if (still_since < 0) still_since = clock_.now();
    if (still_since >= 0 && clock_.now() - still_since >= c.hold_s) return true;
    if (clock_.now() - t0 > c.timeout_s) {
      if (!required) return false;
      throw HardwareError(fmt::format("{}the joints did not settle within {} s (speeds {:.4f} {:.4f} "
                                      "{:.4f} rad/s)",
                                      what, c.timeout_s, state_.velocity[0], state_.velocity[1],
                                      state_.velocity[2]));
    }
  }
}

void Motion::check_followed(const Eigen::Vector3d& reading0, const Eigen::Vector3d& command0,
                            const std::string& what) const {
  for (int i = 0; i < 3; ++i) {
    if (modes_[i] != JointMode::kPosition) continue;
    const double commanded = std::abs(wrap_pi(command_[i] - command0[i]));
    const double moved = std::abs(wrap_pi(state_.theta_m[i] - reading0[i]));
    if (commanded > kFollowMinRad && !(moved >= 0.5 * commanded)) {
      throw HardwareError(fmt::format("{}joint {} did not follow its command: commanded {:.4f} rad, its reading "
                                      "moved {:.4f} rad (a drive that does not move, or readings that do not change)",
                                      what, i + 1, commanded, moved));
    }
  }
}

Eigen::Vector3d Motion::average(double seconds) {
  const Eigen::Vector3d q = command_;
  return average_along([&q](double) { return q; }, seconds);
}

Eigen::Vector3d Motion::average_along(const std::function<Eigen::Vector3d(double)>& path, double seconds) {
  const long n = std::max(1L, std::lround(seconds / hw_.period_s()));
  Eigen::Vector3d gap = Eigen::Vector3d::Zero();
  for (long k = 0; k < n; ++k) {
    const Eigen::Vector3d before = command_;  // what the joints followed when they were read
    cycle(path(static_cast<double>(k + 1) / n));
    for (int i = 0; i < 3; ++i) gap[i] += wrap_pi(state_.theta_m[i] - before[i]);
  }
  Eigen::Vector3d mean = path(1.0) + gap / static_cast<double>(n);
  for (int i = 0; i < 3; ++i) mean[i] = wrap_2pi(mean[i]);
  return mean;
}

Eigen::Vector3d Motion::wrap_near(const Eigen::Vector3d& q) const {
  Eigen::Vector3d m = q;
  for (int i = 0; i < 3; ++i) m[i] = command_[i] + wrap_pi(q[i] - command_[i]);
  return m;
}

}  // namespace gpm::hw
