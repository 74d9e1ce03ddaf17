#include "hw/robot_hardware.hpp"

#include <fmt/format.h>

#include "hw/hw_errors.hpp"

namespace gpm::hw {

const char* lifecycle_state_name(LifecycleState s) {
  switch (s) {
    case LifecycleState::kUnconfigured: return "unconfigured";
    case LifecycleState::kInactive: return "inactive";
    case LifecycleState::kActive: return "active";
    case LifecycleState::kFinalized: return "finalized";
    case LifecycleState::kError: return "error";
  }
  return "?";
}

const char* joint_mode_name(JointMode mode) {
  return mode == JointMode::kPosition ? "position" : "torque_off";
}

HardwareCommand hold_command(const Eigen::Vector3d& theta_m) {
  HardwareCommand c;
  c.theta_m = theta_m;
  c.mode = {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  return c;
}

void RobotHardware::require(LifecycleState s, const char* what) const {
  if (state_ != s) {
    throw LifecycleError(fmt::format("{}: refused in state '{}' (needs '{}'){}", what,
                                     lifecycle_state_name(state_), lifecycle_state_name(s),
                                     state_ == LifecycleState::kError ? ": " + error_ : ""));
  }
}

void RobotHardware::fail(const std::string& message) noexcept {
  on_error();
  if (state_ != LifecycleState::kError) error_ = message;
  state_ = LifecycleState::kError;
}

void RobotHardware::configure() {
  require(LifecycleState::kUnconfigured, "configure");
  try {
    HardwareState initial = state_data_;
    on_configure(initial);
    state_data_ = initial;
  } catch (const HardwareError& e) {
    fail(e.what());
    throw;
  }
  state_ = LifecycleState::kInactive;
}

void RobotHardware::activate() {
  require(LifecycleState::kInactive, "activate");
  try {
    on_activate(state_data_);
  } catch (const HardwareError& e) {
    fail(e.what());
    throw;
  }
  if (estop_) return;  // stopped while activating
  state_ = LifecycleState::kActive;
}

void RobotHardware::deactivate() {
  require(LifecycleState::kActive, "deactivate");
  try {
    on_deactivate();
  } catch (const HardwareError& e) {
    fail(e.what());
    throw;
  }
  state_ = LifecycleState::kInactive;
}

void RobotHardware::shutdown() noexcept {
  if (state_ == LifecycleState::kFinalized) return;
  on_shutdown();
  state_ = LifecycleState::kFinalized;
}

void RobotHardware::reset() {
  require(LifecycleState::kError, "reset");
  on_reset();
  estop_ = false;
  error_.clear();
  state_ = LifecycleState::kUnconfigured;
}

void RobotHardware::emergency_stop(const std::string& reason) noexcept {
  estop_ = true;
  fail("emergency stop: " + reason);
}

const HardwareState& RobotHardware::read(double time_s) {
  if (state_ != LifecycleState::kActive && state_ != LifecycleState::kInactive) {
    require(LifecycleState::kActive, "read");
  }
  try {
    HardwareState s = state_data_;
    s.read_time_s.setConstant(time_s);  // a backend that knows better sets each joint's
    on_read(time_s, s);
    state_data_ = s;
  } catch (const HardwareError& e) {
    fail(e.what());
    throw;
  }
  return state_data_;
}

void RobotHardware::write(const HardwareCommand& command, double time_s) {
  require(LifecycleState::kActive, "write");
  try {
    on_write(command, time_s);
  } catch (const CommandRejected&) {
    throw;  // one refused command: the hardware stays active (the supervisor holds)
  } catch (const HardwareError& e) {
    fail(e.what());
    throw;
  }
}

}  // namespace gpm::hw
