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

double servo_update(const ServoDrive& drive, ServoState& state, const ServoInput& in) {
  if (drive.mode == ServoMode::kTorqueOff) {
    state = ServoState{};
    return 0.0;
  }
  if (drive.mode == ServoMode::kTorque) {
    state = ServoState{};
    state.torque = std::clamp(drive.torque_Nm, -drive.torque_limit, drive.torque_limit);
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
