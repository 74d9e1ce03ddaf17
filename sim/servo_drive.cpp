#include "sim/servo_drive.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gpm::sim {
namespace {

// Shortest signed angle from b to a (readings wrap at 2 pi).
double angle_diff(double a, double b) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  double d = std::fmod(a - b, two_pi);
  if (d > std::numbers::pi) d -= two_pi;
  if (d <= -std::numbers::pi) d += two_pi;
  return d;
}

}  // namespace

double preload_torque(const ServoDrive& drive, long updates) {
  const double tau = std::clamp(drive.torque_Nm, -drive.torque_limit, drive.torque_limit);
  if (drive.alternate_s <= 0.0) return tau;
  // The half-period index of the update's instant (a small epsilon so that an
  // instant on a multiple of alternate_s counts as the new half period).
  const double t = static_cast<double>(updates) * drive.period_s;
  const auto half = static_cast<long>(std::floor(t / drive.alternate_s + 1e-9));
  const double signed_tau = half % 2 == 0 ? tau : -tau;
  const double into = t - static_cast<double>(half) * drive.alternate_s;
  if (half == 0 || into >= drive.ramp_s) return signed_tau;
  return -signed_tau * std::cos(std::numbers::pi * into / drive.ramp_s);  // from -signed_tau to signed_tau
}

double servo_update(const ServoDrive& drive, ServoState& state, const ServoInput& in) {
  if (drive.mode == ServoMode::kTorqueOff) {
    state = ServoState{};
    return 0.0;
  }
  if (drive.mode == ServoMode::kTorque) {
    const long updates = state.updates;
    state = ServoState{};
    state.torque = preload_torque(drive, updates);
    state.updates = updates + 1;
    return state.torque;
  }
  const double e = angle_diff(in.position_command, in.position);
  const double w_cmd = std::clamp(drive.kp * e + drive.feedforward * in.velocity_command,
                                  -drive.velocity_limit, drive.velocity_limit);
  const double ew = w_cmd - in.velocity;
  state.integral = std::clamp(state.integral + drive.ki * ew * drive.period_s,
                              -drive.torque_limit, drive.torque_limit);
  state.torque = std::clamp(drive.kv * ew + state.integral, -drive.torque_limit, drive.torque_limit);
  return state.torque;
}

}  // namespace gpm::sim
