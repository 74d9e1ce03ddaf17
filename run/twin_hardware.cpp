// The in-process twin as hardware (run/twin_hardware.hpp).
#include "run/twin_hardware.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/rng.hpp"
#include "hw/safety_limits.hpp"

namespace gpm::scenario {

std::array<hw::JointMode, 3> twin_joint_modes(const sim::Scenario& s) {
  std::array<hw::JointMode, 3> modes{};
  for (std::size_t i = 0; i < 3; ++i)
    modes[i] = s.twin.drives[i].mode == sim::ServoMode::kPosition ? hw::JointMode::kPosition
                                                                   : hw::JointMode::kTorqueOff;
  return modes;
}

hw::SafetyLimits twin_safety_limits(const sim::Scenario& s, const Robot& controller) {
  hw::SafetyLimits l;
  l.joint_min.fill(-hw::kJointBoundRad);
  l.joint_max.fill(hw::kJointBoundRad);
  l.max_velocity.fill(hw::kMaxVelocityRadS);
  l.max_acceleration.fill(hw::kMaxAccelerationRadS2);
  l.workspace_centre = controller.home;
  l.workspace_radius_mm = hw::kMaxWorkspaceRadiusMm;
  l.max_inconsistency_rad = 1.0;
  l.watchdog_hold_s = 0.1;
  l.watchdog_disable_s = 0.5;
  l.comms_timeout_s = 10.0;
  l.max_tracking_mm = s.max_tracking_mm > 0.0 ? s.max_tracking_mm : hw::kMaxWorkspaceRadiusMm;
  return l;
}

TwinHardware make_twin_hardware(const sim::Scenario& s, const Robot& actual, const Robot& controller) {
  hw::TwinBackendConfig c;
  c.actual = actual;
  c.twin = s.twin;
  c.seed = derive_seed(s.seed, Stream::kTwinNoise);
  c.period_s = 1.0 / s.twin.servo_rate_hz;
  auto backend = std::make_unique<hw::TwinBackend>(std::move(c));
  TwinHardware th;
  th.twin = backend.get();
  th.robot = std::make_unique<hw::SafetySupervisor>(std::move(backend), controller,
                                                    twin_safety_limits(s, controller));
  return th;
}

TwinTruth::TwinTruth(TwinHardware& th, sim::TrajectoryLog* log, gpm::Progress* progress)
    : th_(th), log_(log), progress_(progress) {
  th_.twin->observe([this](const sim::TwinSnapshot& snap) { on_read(snap); });
}

TwinTruth::~TwinTruth() { th_.twin->observe({}); }

hw::SampleHook TwinTruth::hook() {
  return [this](long id, long cycles) { on_sample(id, cycles); };
}

void TwinTruth::on_read(const sim::TwinSnapshot& snap) {
  time_s_ = snap.time_s;
  recent_.push_back(snap);
  if (const auto p = th_.robot->commanded_point()) desired_ = *p;
  if (!desired_.allFinite()) desired_ = snap.ee_mm;  // before the first command: where it stands
  if (log_ && reads_ % log_->every == 0)
    log_->add(sim::LogRow{snap.time_s, desired_, snap.ee_mm, snap.readings, snap.torque, snap.violation_m,
                          snap.growth, snap.growth_base});
  if (progress_ && reads_ % 400 == 0) progress_->update(snap.time_s);
  ++reads_;
}

void TwinTruth::on_sample(long id, long cycles) {
  const long n = std::min<long>(std::max(1L, cycles), static_cast<long>(recent_.size()));
  if (n == 0) return;  // no read yet: nothing to stand for
  SampleTruth t;
  for (auto it = recent_.end() - n; it != recent_.end(); ++it) {
    t.theta_a += it->theta_a;
    t.xy_mm += it->ee_mm;
    t.omega += it->velocity;
    t.tau += it->torque;
    t.t_s += it->time_s;
  }
  const double k = 1.0 / static_cast<double>(n);
  t.theta_a *= k, t.xy_mm *= k, t.omega *= k, t.tau *= k, t.t_s *= k;
  samples_[id] = t;
  recent_.clear();
}

}  // namespace gpm::scenario
