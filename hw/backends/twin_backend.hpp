// Backend `twin`: the MuJoCo twin (sim/) in process. Time is simulated: read(t)
// steps the physics up to t, so a session runs as fast as the CPU allows.
// Drives are disabled (torque off) until activate(); per-joint modes follow
// the commands. A position drive interpolates linearly between its last two
// setpoints, as a drive in cyclic synchronous position mode, and servoes to
// the ramp's middle with its slope as velocity feed-forward (a position and
// a speed of one instant). A joint the scenario gives a constant torque keeps
// it while enabled and not in position mode (the twin's preload). What only
// a twin knows (true angles, end-effector, geometry) is for an observer and
// snapshot(), never in the HardwareState a real drive gives.
#pragma once

#include <functional>
#include <map>
#include <memory>

#include "hw/robot_hardware.hpp"
#include "models/robot.hpp"
#include "sim/twin.hpp"

namespace gpm::hw {

// Settings of the twin backend (constant).
struct TwinBackendConfig {
  Robot actual;               // the twin's actual parameters (never the controller's)
  sim::TwinConfig twin;       // servo, encoder, MJCF settings
  unsigned long long seed = 1;
  double period_s = 0.004;    // read/write cycle period
};

class TwinBackend final : public RobotHardware {
 public:
  // A twin backend; the MuJoCo model is built in configure().
  explicit TwinBackend(TwinBackendConfig config);
  ~TwinBackend() override;

  // The twin's last snapshot (true angles and end-effector; for tests and logs).
  const sim::TwinSnapshot& snapshot() const;
  // Called after every read with the twin's snapshot of the instant the
  // readings were latched (the truth of a simulation: trajectory log, true
  // poses of the samples); empty: none.
  void observe(std::function<void(const sim::TwinSnapshot&)> observer) { observer_ = std::move(observer); }
  // The twin's compiled model with the joints of modes in position mode
  // (built if needed; its MJCF text is model.xml, its events and growth the truth).
  const sim::TwinModel& model(const std::array<JointMode, 3>& modes);

  double period_s() const override { return config_.period_s; }
  bool simulated_time() const override { return true; }
  std::string describe() const override { return "twin (MuJoCo, in process)"; }

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
  const sim::TwinModel& model_for(unsigned mask, bool enabled = true);
  void fill(HardwareState& state) const;

  TwinBackendConfig config_;
  // One compiled model per mode combination (bit i set: joint i in position
  // mode). sim::TwinModel fixes the drive modes at construction; the models
  // are identical otherwise, so one TwinState steps with any of them.
  std::map<unsigned, std::unique_ptr<sim::TwinModel>> models_;
  std::unique_ptr<sim::TwinState> state_;
  unsigned mask_ = 0;
  bool enabled_ = false;  // drives enabled (a preload joint pulls only then)
  std::function<void(const sim::TwinSnapshot&)> observer_;
  sim::TwinSnapshot latched_;  // the snapshot of the last drive loop tick (readings latched)
  Eigen::Vector3d last_command_ = Eigen::Vector3d::Zero();
};

}  // namespace gpm::hw
