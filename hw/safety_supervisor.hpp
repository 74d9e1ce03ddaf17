// The safety supervisor: sits between every caller and every backend and is
// itself a RobotHardware. No command that breaks a limit reaches the backend:
// joint limits, workspace disc with a margin, chain reach and singularity
// margins of the controller model, velocity and acceleration limits (also for
// the stopping point of every accepted command), command consistency, a
// command watchdog (hold, then disable), comms timeouts, emergency stop, and
// a tracking watch (the end-effector from the readings within max_tracking of
// where the command in force puts it, else the drives are disabled).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hw/clock.hpp"
#include "hw/robot_hardware.hpp"
#include "hw/safety_limits.hpp"
#include "models/robot.hpp"

namespace gpm::hw {

class SafetySupervisor final : public RobotHardware {
 public:
  // Supervises backend (owned) with limits; controller is the robot model the
  // caller commands with (nominal or calibrated), used for FK/IK checks.
  // clock measures backend calls against comms_timeout and paces the
  // procedures' cycles on real time (the wall clock unless tests inject one).
  SafetySupervisor(std::unique_ptr<RobotHardware> backend, const Robot& controller,
                   const SafetyLimits& limits, Clock& clock = steady_clock());

  // Why cmd would be refused now (empty when it is allowed).
  std::string check(const HardwareCommand& cmd) const;
  // Why the static position theta_m (encoder space) is not allowed (empty when it is).
  std::string check_pose(const Eigen::Vector3d& theta_m) const;
  // The same for the joints of mode in position mode (two: the end-effector
  // they put it at; the others are free). The one pose check of every
  // procedure (sampling poses, zero-search points and circles).
  std::string check_pose(const Eigen::Vector3d& theta_m, const std::array<JointMode, 3>& mode) const;
  // Why the joint path q (encoder space, one command per period_s()) would
  // be refused, naming the first bad point (empty when every command is
  // allowed): each point by check_pose for mode, the steps and their changes
  // by the velocity and acceleration limits of the position joints. For a
  // procedure that knows its path before the robot moves (gpm monitor).
  std::string check_path(const std::vector<Eigen::Vector3d>& q, const std::array<JointMode, 3>& mode) const;
  // Where the command in force puts the controller model's end-effector (mm;
  // two position joints: in their assembly mode at home); nullopt before a
  // command or where it cannot (fewer than two joints in position mode).
  std::optional<Eigen::Vector2d> commanded_point() const;
  // What the tracking watch measures for reading against the command in
  // force (mm); nullopt where it does not watch (before a command, fewer
  // than two joints in position mode, no assembly).
  std::optional<double> tracking_mm(const Eigen::Vector3d& reading) const;
  // Number of commands refused so far.
  long rejected_count() const { return rejected_; }
  // True while the robot brakes or holds because no valid command came.
  bool holding() const { return holding_; }
  // The supervised backend (for status only: never command it directly).
  const RobotHardware& backend() const { return *backend_; }
  // The limits and the controller model in force.
  const SafetyLimits& limits() const { return limits_; }
  const Robot& controller() const { return controller_; }
  // The clock of real time for this robot.
  Clock& clock() const { return clock_; }

  double period_s() const override { return backend_->period_s(); }
  bool simulated_time() const override { return backend_->simulated_time(); }
  std::string describe() const override { return "supervised " + backend_->describe(); }

 protected:
  void on_configure(HardwareState& initial) override;
  void on_activate(const HardwareState& current) override;
  void on_deactivate() override;
  void on_shutdown() noexcept override;
  void on_error() noexcept override;
  void on_reset() override;
  void on_read(double time_s, HardwareState& state) override;
  void on_write(const HardwareCommand& command, double time_s) override;

 private:
  std::string check_joint_positions(const Eigen::Vector3d& q,
                                    const std::array<JointMode, 3>& mode,
                                    const char* what) const;
  std::string check_workspace(const Eigen::Vector3d& q, const std::array<JointMode, 3>& mode,
                              const char* what) const;
  HardwareCommand brake_command() const;
  void forward(const HardwareCommand& cmd, double time_s);
  template <class F> void timed(const char* what, F&& f);

  std::unique_ptr<RobotHardware> backend_;
  Clock& clock_;
  Robot controller_;
  SafetyLimits limits_;
  double dt_ = 0.0;
  std::array<std::array<int, 3>, 3> pair_mode_{};  // assembly mode of chain pairs at home

  // Last command forwarded to the backend and its velocity (rad, rad/s).
  HardwareCommand last_;
  Eigen::Vector3d last_velocity_ = Eigen::Vector3d::Zero();
  double last_fresh_time_ = 0.0;  // time of the last accepted caller command
  bool have_reading_ = false;
  HardwareState previous_reading_;
  bool holding_ = false;
  long rejected_ = 0;
};

}  // namespace gpm::hw
