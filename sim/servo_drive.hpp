// AC servo drive of one active joint: a cascaded position/velocity loop as in
// industrial drives, sampled at the drive's loop rate.
//   velocity command  w* = clamp(kp * wrap(pos_cmd - pos) + ff * vel_cmd, +-velocity_limit)
//   torque            tau = clamp(kv * (w* - w) + ki * integral(w* - w), +-torque_limit)
// Position feedback is the drive's encoder reading; velocity feedback is the
// motor speed. At rest the joint behaves as a spring of stiffness kp * kv
// (N m/rad) towards its command, which is what makes inconsistent commands
// through the closed chain hold an internal preload (docs/ARCHITECTURE.md).
// With ki > 0 fighting servos wind their integrators up to the torque limit,
// as real drives do; ki therefore defaults to 0 (a P/P cascade).
// No MuJoCo dependency: a pure function of constants and a small state.
#pragma once

namespace gpm::sim {

// Per-joint operating mode.
enum class ServoMode {
  kPosition,   // closes the position loop on its command
  kTorqueOff,  // no torque; the encoder is still read (redundant joint as sensor)
  kTorque,     // a torque (ServoDrive::torque_Nm): the redundant joint preloads the chain one way,
               // so every joint clearance is taken up along the same direction; with
               // ServoDrive::alternate_s > 0 the preload changes sign every alternate_s seconds
};

// Constant settings of one drive (defaults: 400 W servo behind a 10:1 reducer,
// see models/mjcf.cpp; output-side units).
struct ServoDrive {
  ServoMode mode = ServoMode::kPosition;
  double kp = 100.0;             // position loop gain, 1/s
  double kv = 10.0;              // velocity loop gain, N m s/rad
  double ki = 0.0;               // velocity loop integral gain, N m/rad
  double feedforward = 1.0;      // velocity feed-forward fraction, 0..1
  double torque_limit = 38.0;    // N m (peak torque at the reducer output)
  double velocity_limit = 6.0;   // rad/s
  double period_s = 0.0005;      // loop period (1 / loop rate)
  double torque_Nm = 0.0;        // kTorque: the torque applied (clamped to +-torque_limit)
  double alternate_s = 0.0;      // kTorque: seconds between changes of its sign (0: constant)
  double ramp_s = 0.2;           // kTorque alternating: seconds each change of sign takes (a cosine)

  // Holding stiffness at rest, kp * kv (N m/rad).
  double stiffness() const { return kp * kv; }
};

// Mutable state of one drive.
struct ServoState {
  double integral = 0.0;  // integral term, N m (clamped to +-torque_limit)
  double torque = 0.0;    // last torque output, held until the next update
  long updates = 0;       // kTorque: loop updates since the drive last left torque-off
};

// kTorque's torque after `updates` loop updates: torque_Nm, its sign changed
// at every whole multiple of alternate_s (when > 0) of updates * period_s,
// from -tau to tau as -tau cos(pi u / ramp_s) over the ramp_s after it.
double preload_torque(const ServoDrive& drive, long updates);

// Inputs of one loop update (angles in the drive's own reading frame).
struct ServoInput {
  double position_command = 0.0;  // rad, an encoder reading value
  double velocity_command = 0.0;  // rad/s, feed-forward
  double position = 0.0;          // rad, encoder reading
  double velocity = 0.0;          // rad/s, motor speed
};

// One loop update: returns the torque to apply until the next update and
// stores it in state.torque.
double servo_update(const ServoDrive& drive, ServoState& state, const ServoInput& in);

}  // namespace gpm::sim
