// One robot interface for every backend, in the manner of ros2_control's
// SystemInterface: a lifecycle (configure, activate, deactivate, shutdown and
// an error state) and a read()/write() cycle at a fixed rate. The public
// methods enforce the lifecycle; backends implement the protected hooks.
// Hardware has one owner: not copyable, not movable (own it by unique_ptr).
#pragma once

#include <string>

#include "hw/hardware_types.hpp"

namespace gpm::hw {

// Lifecycle states (ros2_control: unconfigured, inactive, active, finalized;
// kError is entered on any backend failure or emergency stop, drives disabled).
enum class LifecycleState { kUnconfigured, kInactive, kActive, kFinalized, kError };

// Text name of a lifecycle state.
const char* lifecycle_state_name(LifecycleState s);

class RobotHardware {
 public:
  RobotHardware() = default;
  virtual ~RobotHardware() = default;
  RobotHardware(const RobotHardware&) = delete;
  RobotHardware& operator=(const RobotHardware&) = delete;
  RobotHardware(RobotHardware&&) = delete;
  RobotHardware& operator=(RobotHardware&&) = delete;

  // Unconfigured -> Inactive: connect and check the drives (left disabled).
  // Throws LifecycleError from another state, HardwareError on failure (-> kError).
  void configure();
  // Inactive -> Active: enable the drives, holding the current position.
  void activate();
  // Active -> Inactive: disable the drives (no torque).
  void deactivate();
  // Any state -> Finalized: disable the drives and disconnect; never throws.
  void shutdown() noexcept;
  // Error -> Unconfigured, once the cause has been cleared.
  void reset();
  // Disables every drive at once and enters kError; callable from any state;
  // never throws. Call it from the control thread (a signal handler sets a
  // flag that the loop polls).
  void emergency_stop(const std::string& reason) noexcept;

  // Reads the state at time_s (Inactive or Active; each joint's read time is
  // time_s unless the backend stamps its own). A backend failure enters
  // kError (drives disabled) and rethrows.
  const HardwareState& read(double time_s);
  // Writes a command at time_s (Active only; LifecycleError otherwise). A
  // backend failure enters kError and rethrows; CommandRejected (one refused
  // command) is rethrown with the hardware still active.
  void write(const HardwareCommand& command, double time_s);

  // Current lifecycle state.
  LifecycleState state() const { return state_; }
  // Why the hardware entered kError (empty otherwise).
  const std::string& error_message() const { return error_; }
  // Last state read.
  const HardwareState& last_state() const { return state_data_; }
  // Fixed cycle period of the read/write loop (s).
  virtual double period_s() const = 0;
  // True when time only advances with the cycle (a simulation may run faster
  // than real time); false for real drives (the loop paces itself on the wall clock).
  virtual bool simulated_time() const { return false; }
  // One line naming the backend and where it is ("modbus 127.0.0.1:1502").
  virtual std::string describe() const = 0;

 protected:
  // Connect and check; fill initial with a first reading (drives disabled).
  virtual void on_configure(HardwareState& initial) = 0;
  // Called with the last state read; enable the drives holding there.
  virtual void on_activate(const HardwareState& current) = 0;
  virtual void on_deactivate() = 0;
  virtual void on_shutdown() noexcept = 0;
  // Make safe after a failure or an emergency stop: disable every drive,
  // best effort; must not throw.
  virtual void on_error() noexcept = 0;
  // Clear the error so configure() may run again.
  virtual void on_reset() {}
  virtual void on_read(double time_s, HardwareState& state) = 0;
  virtual void on_write(const HardwareCommand& command, double time_s) = 0;

 private:
  void require(LifecycleState s, const char* what) const;
  void fail(const std::string& message) noexcept;

  LifecycleState state_ = LifecycleState::kUnconfigured;
  std::string error_;
  HardwareState state_data_;
  bool estop_ = false;
};

}  // namespace gpm::hw
