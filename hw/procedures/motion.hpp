// The one motion primitive of the procedures (sampling session, zero-offset
// search, section-3 offsets): control cycles through the SafetySupervisor at
// its period (read, write, wait), smooth moves along a joint-space path
// timed within a fraction of the velocity and acceleration limits, settling,
// and averaging of the readings. Every cycle first looks at the stop flag
// (StopOnSignal): a request disables the drives and throws Interrupted.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "hw/hardware_types.hpp"
#include "hw/procedures/cycle_clock.hpp"
#include "hw/safety_supervisor.hpp"
#include "sim/sampling.hpp"

namespace gpm::hw {

// Smooth 0..1 time law s(u), u = t / T (cosine): peak ds/du = pi / 2, peak
// d2s/du2 = pi^2 / 2.
double motion_profile(double u);

// Smallest commanded joint move (rad) that check_followed judges: 0.01 rad
// is 2.4 mm at a 244 mm link, far beyond servo lag and the fight of drives
// over a wrong model after settling.
inline constexpr double kFollowMinRad = 0.01;

class Motion {
 public:
  // Moves hw with the joints in modes (position or torque off), using
  // headroom (0, 1] of the velocity and acceleration limits; stop (optional)
  // is polled every cycle.
  Motion(SafetySupervisor& hw, const std::array<JointMode, 3>& modes, double headroom,
         const std::atomic<bool>* stop = nullptr);

  // Configures hw if needed, reads, activates: the command starts at the reading.
  void start();
  // Deactivates hw if it is active (a normal stop, drives disabled).
  void finish();

  // One control cycle: read, command q (encoder space), wait for the next.
  // Throws Interrupted (after an emergency stop) when a stop was requested.
  void cycle(const Eigen::Vector3d& q);
  // Duration of the path q(s), s in [0, 1] sampled at q.size() points,
  // run with motion_profile within headroom of the limits of the commanded
  // joints; at least min_T and four periods.
  double path_time(const std::vector<Eigen::Vector3d>& q, double min_T) const;
  // Runs path(s) from s = profile(1 / steps) to 1 in ceil(T / period) cycles.
  void follow(const std::function<Eigen::Vector3d(double)>& path, double T);
  // Straight line in joint space to q1 at a tip speed of at most speed_mm_s
  // (joint motion times the longest proximal link of the robot's model).
  void move_joints(const Eigen::Vector3d& q1, double speed_mm_s);
  // Holds the command until every joint is slower than c.velocity_rad_s for
  // c.hold_s and returns true; after c.timeout_s HardwareError (what,
  // speeds), or false when required is false (the wait given up).
  bool settle(const sim::SettleCriterion& c, const std::string& what, bool required = true);
  // Throws HardwareError unless every position-mode joint whose command moved
  // more than kFollowMinRad since command0 saw its reading move at least
  // half as far since reading0: a drive that does not move, or readings that
  // do not change, must not pass for samples. what prefixes the message.
  void check_followed(const Eigen::Vector3d& reading0, const Eigen::Vector3d& command0,
                      const std::string& what) const;
  // Holds the command for seconds and returns the mean reading (in [0, 2 pi)).
  Eigen::Vector3d average(double seconds);
  // Commands path(u), u = k / n for k = 1..n (n = seconds / period, at least
  // one) and returns path(1) plus the mean gap between each reading and the
  // command of the cycle before it (in [0, 2 pi)): the reading the joints
  // would give held at path(1). With a closed path around the current
  // command the encoders cross many counts, so the rounding errors of the
  // readings average out; the path's own shape (its curvature too) is
  // subtracted exactly; the joint speeds average to zero over the loop, so
  // lags (servo lag, readings not taken at one instant) cancel to first order.
  Eigen::Vector3d average_along(const std::function<Eigen::Vector3d(double)>& path, double seconds);

  // q with each component taken within pi of the current command.
  Eigen::Vector3d wrap_near(const Eigen::Vector3d& q) const;
  const Eigen::Vector3d& command() const { return command_; }
  const HardwareState& state() const { return state_; }
  double now() const { return clock_.now(); }
  double period_s() const { return hw_.period_s(); }
  SafetySupervisor& hardware() { return hw_; }

 private:
  SafetySupervisor& hw_;
  std::array<JointMode, 3> modes_;
  double headroom_;
  const std::atomic<bool>* stop_;
  CycleClock clock_;
  HardwareState state_;
  Eigen::Vector3d command_ = Eigen::Vector3d::Zero();
};

}  // namespace gpm::hw
