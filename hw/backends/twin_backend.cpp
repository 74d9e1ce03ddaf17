#include "hw/backends/twin_backend.hpp"

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/kinematics.hpp"
#include "sim/mujoco_util.hpp"

namespace gpm::hw {

TwinBackend::TwinBackend(TwinBackendConfig config) : config_(std::move(config)) {}

TwinBackend::~TwinBackend() = default;

const sim::TwinSnapshot& TwinBackend::snapshot() const {
  if (!state_) throw LifecycleError("twin snapshot: the twin is not configured");
  return state_->last;
}

const sim::TwinModel& TwinBackend::model(const std::array<JointMode, 3>& modes) {
  unsigned mask = 0;
  for (int i = 0; i < 3; ++i)
    if (modes[static_cast<std::size_t>(i)] == JointMode::kPosition) mask |= 1u << i;
  return model_for(mask);
}

const sim::TwinModel& TwinBackend::model_for(unsigned mask, bool enabled) {
  // A joint out of position mode is torque-off, or pulls with the scenario's
  // preload torque while the drives are enabled (the twin's preload, constant or
  // alternating: sim::preload_torque).
  unsigned key = mask;
  for (int i = 0; i < 3; ++i)
    if (enabled && !((mask >> i) & 1u) && config_.twin.drives[i].mode == sim::ServoMode::kTorque) key |= 8u << i;
  auto it = models_.find(key);
  if (it == models_.end()) {
    sim::TwinConfig c = config_.twin;
    for (int i = 0; i < 3; ++i) {
      c.drives[i].mode = (mask >> i) & 1u     ? sim::ServoMode::kPosition
                         : (key >> (3 + i)) & 1u ? sim::ServoMode::kTorque
                                                 : sim::ServoMode::kTorqueOff;
    }
    try {
      it = models_.emplace(key, std::make_unique<sim::TwinModel>(config_.actual, c)).first;
    } catch (const sim::SimError& e) {
      throw HardwareError(fmt::format("twin: {}", e.what()));
    }
  }
  return *it->second;
}

void TwinBackend::fill(HardwareState& s) const {
  const sim::TwinSnapshot& last = state_->last;
  s.time_s = last.time_s;
  s.theta_m = last.readings;
  s.velocity = last.velocity;
  s.torque = last.torque;
  s.torque_reported = true;
  s.read_time_s.setConstant(last.time_s);  // the twin's encoders latch one instant
  for (int i = 0; i < 3; ++i) {
    s.drive[i] = DriveStatus{};
    s.drive[i].enabled = (mask_ >> i) & 1u;
    s.drive[i].status_word = s.drive[i].enabled ? 0x0001 : 0x0000;
  }
}

void TwinBackend::on_configure(HardwareState& initial) {
  mask_ = 0;
  enabled_ = false;
  state_ = std::make_unique<sim::TwinState>(model_for(0b111), config_.seed);
  model_for(0, false);
  latched_ = state_->last;
  last_command_ = state_->last.readings;
  fill(initial);
}

void TwinBackend::on_activate(const HardwareState&) {
  last_command_ = state_->last.readings;
  sim::twin_command(*state_, last_command_, Eigen::Vector3d::Zero());
  mask_ = 0b111;
  enabled_ = true;
}

void TwinBackend::on_deactivate() { mask_ = 0, enabled_ = false; }

void TwinBackend::on_shutdown() noexcept {
  mask_ = 0;
  enabled_ = false;
  state_.reset();
}

void TwinBackend::on_error() noexcept { mask_ = 0, enabled_ = false; }

void TwinBackend::on_reset() { state_.reset(); }

void TwinBackend::on_read(double time_s, HardwareState& s) {
  const sim::TwinModel& model = model_for(mask_, enabled_);
  const double h = model.timestep_s();
  try {
    while (state_->data->time + 0.5 * h < time_s) {
      const bool tick = state_->steps % model.steps_per_tick() == 0;  // the drives' loop: encoders latch
      sim::twin_step(model, *state_);
      if (tick) latched_ = state_->last;
    }
  } catch (const sim::SimError& e) {
    throw HardwareError(fmt::format("twin: {}", e.what()));
  }
  fill(s);
  if (observer_) observer_(latched_);
}

void TwinBackend::on_write(const HardwareCommand& cmd, double) {
  unsigned mask = 0;
  Eigen::Vector3d position = cmd.theta_m;
  Eigen::Vector3d reference = position;  // what the drives servo to this cycle
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (cmd.mode[i] == JointMode::kPosition) {
      mask |= 1u << i;
      // The drive interpolates linearly between its last two setpoints and
      // servoes to the ramp's middle with its slope as velocity feed-forward:
      // a position and a speed of one instant, half a period behind the setpoint.
      const double step = wrap_pi(position[i] - last_command_[i]);
      velocity[i] = step / config_.period_s;
      reference[i] = last_command_[i] + 0.5 * step;
    } else {
      position[i] = reference[i] = state_->last.readings[i];
    }
  }
  model_for(mask, true);
  sim::twin_command(*state_, reference, velocity);
  last_command_ = position;
  mask_ = mask;
  enabled_ = true;
}

}  // namespace gpm::hw
