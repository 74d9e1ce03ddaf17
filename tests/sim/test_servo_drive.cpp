// Tests of sim/servo_drive.cpp against hand-computed loop outputs.
#include "sim/servo_drive.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace gpm::sim {
namespace {

TEST(ServoDrive, PreloadIsConstantWithoutAlternation) {
  ServoDrive d;
  d.mode = ServoMode::kTorque;
  d.torque_Nm = -2.0;
  ServoState s;
  for (int k = 0; k < 5000; ++k) EXPECT_EQ(servo_update(d, s, {0.0, 0.0, 0.3, 1.0}), -2.0);
  d.torque_Nm = -50.0;  // clamped to the drive's limit
  EXPECT_EQ(servo_update(d, s, {0.0, 0.0, 0.3, 1.0}), -38.0);
}

// A 1 kHz drive preloading 2 N m, its sign changed every 0.01 s over ramp_s.
ServoDrive alternating_drive(double ramp_s) {
  ServoDrive d;
  d.mode = ServoMode::kTorque;
  d.torque_Nm = 2.0;
  d.alternate_s = 0.01;
  d.ramp_s = ramp_s;
  d.period_s = 0.001;
  return d;
}

// Hand-worked: a 1 kHz loop alternating every 0.01 s without a ramp applies
// +tau on updates 0-9, -tau on 10-19, +tau on 20-29; torque-off starts the
// count again.
TEST(ServoDrive, PreloadChangesSignEveryAlternation) {
  const ServoDrive d = alternating_drive(0.0);
  ServoState s;
  for (int k = 0; k < 30; ++k) {
    const double expected = (k / 10) % 2 == 0 ? 2.0 : -2.0;
    EXPECT_EQ(servo_update(d, s, {0.0, 0.0, 0.0, 0.0}), expected) << "update " << k;
    EXPECT_EQ(s.torque, expected);
  }
  EXPECT_EQ(preload_torque(d, 10), -2.0);
  EXPECT_EQ(preload_torque(d, 9), 2.0);
  ServoDrive off = d;
  off.mode = ServoMode::kTorqueOff;
  EXPECT_EQ(servo_update(off, s, {0.0, 0.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(servo_update(d, s, {0.0, 0.0, 0.0, 0.0}), 2.0);  // update 0 again
}

// Hand-worked: with a ramp of 0.004 s each change of sign is -tau_new cos(pi u / 0.004):
// +2 at the change (u = 0), 2 cos(pi / 4) one update later, 0 halfway, -2 from u = 0.004.
TEST(ServoDrive, PreloadRampsThroughZeroAtEachChange) {
  const ServoDrive d = alternating_drive(0.004);
  EXPECT_EQ(preload_torque(d, 0), 2.0) << "no ramp at the start";
  EXPECT_NEAR(preload_torque(d, 10), 2.0, 1e-12);
  EXPECT_NEAR(preload_torque(d, 11), 2.0 * std::cos(std::numbers::pi / 4.0), 1e-12);
  EXPECT_NEAR(preload_torque(d, 12), 0.0, 1e-12);
  EXPECT_NEAR(preload_torque(d, 13), -2.0 * std::cos(std::numbers::pi / 4.0), 1e-12);
  EXPECT_EQ(preload_torque(d, 14), -2.0);
  EXPECT_NEAR(preload_torque(d, 22), 0.0, 1e-12);
  EXPECT_EQ(preload_torque(d, 24), 2.0);
}

TEST(ServoDrive, AtRestActsAsSpringOfStiffnessKpKv) {
  ServoDrive d;  // kp 100 1/s, kv 10 N m s/rad
  ServoState s;
  const double tau = servo_update(d, s, {1.0 + 0.002, 0.0, 1.0, 0.0});
  EXPECT_NEAR(tau, 100.0 * 10.0 * 0.002, 1e-12);
  EXPECT_DOUBLE_EQ(d.stiffness(), 1000.0);
  EXPECT_DOUBLE_EQ(s.torque, tau);
}

TEST(ServoDrive, VelocityFeedForwardAndDamping) {
  ServoDrive d;
  d.feedforward = 0.5;
  ServoState s;
  // w* = 0.5 * 2 = 1 rad/s, measured 0.4 rad/s: tau = 10 * 0.6.
  EXPECT_NEAR(servo_update(d, s, {1.0, 2.0, 1.0, 0.4}), 6.0, 1e-12);
}

TEST(ServoDrive, ErrorWrapsAcrossZero) {
  ServoDrive d;
  ServoState s;
  // Command just above 0, reading just below 2 pi: the error is +0.002, not -2 pi.
  const double tau = servo_update(d, s, {0.001, 0.0, 2.0 * std::numbers::pi - 0.001, 0.0});
  EXPECT_NEAR(tau, 1000.0 * 0.002, 1e-9);
}

TEST(ServoDrive, SaturatesTorqueAndVelocityCommand) {
  ServoDrive d;
  d.velocity_limit = 1.0;
  d.torque_limit = 5.0;
  ServoState s;
  // kp * e = 100 rad/s -> clamped to 1; tau = 10 * 1 = 10 -> clamped to 5.
  EXPECT_DOUBLE_EQ(servo_update(d, s, {2.0, 0.0, 1.0, 0.0}), 5.0);
  d.torque_limit = 50.0;
  EXPECT_DOUBLE_EQ(servo_update(d, s, {2.0, 0.0, 1.0, 0.0}), 10.0);
  EXPECT_DOUBLE_EQ(servo_update(d, s, {0.0, 0.0, 1.0, 0.0}), -10.0);
}

TEST(ServoDrive, IntegralAccumulatesAndIsClamped) {
  ServoDrive d;
  d.ki = 1000.0;
  d.period_s = 0.001;
  d.torque_limit = 3.0;
  ServoState s;
  // e_w = 0.1 rad/s: each update adds 1000 * 0.1 * 0.001 = 0.1 N m.
  servo_update(d, s, {0.0, 0.1, 0.0, 0.0});
  EXPECT_NEAR(s.integral, 0.1, 1e-12);
  EXPECT_NEAR(s.torque, 10.0 * 0.1 + 0.1, 1e-12);
  for (int k = 0; k < 1000; ++k) servo_update(d, s, {0.0, 0.1, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(s.integral, 3.0);
  EXPECT_DOUBLE_EQ(s.torque, 3.0);
}

TEST(ServoDrive, TorqueOffGivesNoTorqueAndClearsState) {
  ServoDrive d;
  d.mode = ServoMode::kTorqueOff;
  ServoState s{2.0, 4.0};
  EXPECT_EQ(servo_update(d, s, {3.0, 1.0, 0.0, 0.0}), 0.0);
  EXPECT_EQ(s.integral, 0.0);
  EXPECT_EQ(s.torque, 0.0);
}

TEST(ServoDrive, TorqueModeHoldsItsConstantTorqueWithinTheLimitWhateverTheError) {
  ServoDrive d;
  d.mode = ServoMode::kTorque;
  d.torque_Nm = -1.5;
  ServoState s{2.0, 4.0};
  EXPECT_EQ(servo_update(d, s, {3.0, 1.0, 0.0, 0.0}), -1.5);
  EXPECT_EQ(servo_update(d, s, {-3.0, -1.0, 0.5, 2.0}), -1.5);
  EXPECT_EQ(s.integral, 0.0);
  EXPECT_EQ(s.torque, -1.5);
  d.torque_Nm = 100.0;  // clamped to the drive's limit
  EXPECT_EQ(servo_update(d, s, {0.0, 0.0, 0.0, 0.0}), d.torque_limit);
}

}  // namespace
}  // namespace gpm::sim
