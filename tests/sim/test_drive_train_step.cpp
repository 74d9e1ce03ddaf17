// Tests of sim/drive_train_step.cpp: the drive train inside the twin, each
// against an independent expectation.
// - off (every amplitude 0) is the twin without a drive train, bit for bit;
// - the mesh law applied through qfrc_applied with a linear stiffness (and a
//   vanishing dead band) reproduces MuJoCo's own tendon spring step for step,
//   rotor friction included (signs and wiring);
// - static deflection: a drive in torque mode pushing T on its chain twists
//   its transmission by b/2 + f^-1((1 + delta) T) (the catalogue's torsion
//   formula on top of the dead band; the applied torque, not the reported
//   one, loads the mesh); between +T and -T the lost motion is b + 2 f^-1;
// - cogging and torque constant: a drive holding an unloaded axis reports
//   -cogging / (1 + delta) (it cancels its motor's ripple through its own
//   torque constant);
// - transmission error: at rest the link stands at theta_m - (TE(theta_m) -
//   TE(theta_m0)) - tau / K (the gear's kinematic error plus Hooke's law);
// - load-dependent and Stribeck friction: by power balance over a circle,
//   the drives' extra mean power is mean(mu |tau_t| |omega_m|), and
//   mean(F_x exp(-(omega_m / v_s)^2) |omega_m|);
// - the twin refuses a mesh without a rotor, or bands too stiff for the timestep;
// - drawn (randomized) drive trains on the realistic twin run stable at 0.25 ms.
#include "sim/drive_train_step.hpp"

#include <cmath>
#include <functional>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "sim/sampling.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

// 4 kHz drive loop and 0.25 ms steps (stable with compliance), ideal encoders.
TwinConfig fast_config() {
  TwinConfig c;
  c.mjcf.timestep_s = 0.00025;
  c.mjcf.solref_timeconst_s = 0.0005;
  c.servo_rate_hz = 4000.0;
  c.encoder.bits = 0;
  return c;
}

void run_for(const TwinModel& m, TwinState& s, double seconds) {
  const long n = std::lround(seconds / m.timestep_s());
  for (long k = 0; k < n; ++k) twin_step(m, s);
}

// Drive readings that put the end-effector at p (mm) by the actual inverse kinematics.
Eigen::Vector3d readings_at(const Robot& r, const Eigen::Vector2d& p) {
  const JointAngles q = inverse_kinematics(r.geometry, p, r.branch);
  Eigen::Vector3d c;
  for (int i = 0; i < 3; ++i) c[i] = q.theta_a[i] - r.geometry.dth_(i);
  return c;
}

// Off is off: a drive train whose every amplitude is 0 (phases, orders and
// Stribeck speed set, as the scenario parser leaves them) builds no drive
// train and steps bit for bit as the twin without one.
TEST(DriveTrainStep, OffIsTheIdealTwinBitForBit) {
  const Robot robot;
  const TwinConfig ideal = fast_config();
  TwinConfig off = ideal;
  off.effects.drive.te_motor_order = 3, off.effects.drive.cogging_periods_per_motor_rev = 36;
  for (DriveChain& d : off.effects.drive.chain)
    d.te_joint_phase_rad = 1.0, d.te_motor_phase_rad = 2.0, d.cogging_phase_rad = 3.0, d.stribeck_speed_rad_s = 0.2;
  const TwinModel mi(robot, ideal), mo(robot, off);
  EXPECT_FALSE(off.effects.any());
  EXPECT_FALSE(mo.drive_train.on);
  EXPECT_EQ(mi.xml(), mo.xml());
  TwinState si(mi, 1), so(mo, 1);
  const Eigen::Vector3d theta_m0 = si.last.theta_motor;
  const Eigen::Vector3d target = readings_at(robot, robot.home + Eigen::Vector2d(15.0, 25.0));
  twin_command(si, target, Eigen::Vector3d::Zero());
  twin_command(so, target, Eigen::Vector3d::Zero());
  for (int k = 0; k < 1000; ++k) twin_step(mi, si), twin_step(mo, so);
  for (int j = 0; j < mi.mj()->nq; ++j) EXPECT_EQ(si.data->qpos[j], so.data->qpos[j]) << j;
  EXPECT_GT((si.last.theta_motor - theta_m0).cwiseAbs().maxCoeff(), 0.01) << "the drives should have moved";
}

TEST(DriveTrainStep, LinearMeshReproducesMuJoCosSpring) {
  const Robot robot;
  TwinConfig spring = fast_config();
  spring.effects.mjcf.compliance_rad_per_Nm = {1e-4, 1.5e-4, 0.8e-4};
  spring.effects.mjcf.coulomb_Nm.fill(0.3);
  TwinConfig mesh = spring;
  for (DriveChain& c : mesh.effects.drive.chain) c.backlash_rad = 1e-300;  // turns the mesh on, changes nothing
  const TwinModel ms(robot, spring), mm(robot, mesh);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(mm.drive_train.mesh[static_cast<size_t>(i)]);
    EXPECT_EQ(mm.rotor_friction[static_cast<size_t>(i)].dof, -1) << "the drive train solves the rotor's friction";
  }
  TwinState ss(ms, 1), sm(mm, 1);
  const Eigen::Vector3d target = readings_at(robot, robot.home + Eigen::Vector2d(25.0, -10.0));
  twin_command(ss, target, Eigen::Vector3d::Zero());
  twin_command(sm, target, Eigen::Vector3d::Zero());
  double worst = 0.0, moved = 0.0;
  for (int k = 0; k < 2000; ++k) {
    twin_step(ms, ss), twin_step(mm, sm);
    worst = std::max(worst, (ss.last.theta_a - sm.last.theta_a).cwiseAbs().maxCoeff());
    worst = std::max(worst, (ss.last.theta_motor - sm.last.theta_motor).cwiseAbs().maxCoeff());
    moved = std::max(moved, (ss.last.theta_a - ss.last.theta_motor).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(moved, 1e-4) << "the transmission should have twisted";
  EXPECT_LT(worst, 1e-10);
}

// Twist theta_m - theta_a of chain 1 at rest while it pushes T in torque mode.
double twist_under_torque(const TwinConfig& base, double T) {
  TwinConfig c = base;
  c.drives[0].mode = ServoMode::kTorque;
  c.drives[0].torque_Nm = T;
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  run_for(m, s, 1.5);
  twin_sense(m, s);
  EXPECT_NEAR(s.last.torque[0], T, 1e-12) << "the drive reports the torque it was told";
  EXPECT_LT(s.last.motor_velocity.cwiseAbs().maxCoeff(), 1e-5) << "not at rest";
  return s.last.theta_motor[0] - s.last.theta_a[0];
}

TEST(DriveTrainStep, StaticDeflectionFollowsDeadBandAndBands) {
  TwinConfig c = fast_config();
  DriveChain& d = c.effects.drive.chain[0];
  d.stiffness_Nm_per_rad = {1.3e4, 1.8e4, 2.3e4};  // CSF-20 class
  d.band_Nm = {7.0, 25.0};
  d.backlash_rad = 6e-4;
  d.torque_constant_delta = 0.1;
  const double T = 12.0, applied = 1.1 * T;
  const double expected = 3e-4 + 7.0 / 1.3e4 + (applied - 7.0) / 1.8e4;  // b/2 + T1/K1 + (T - T1)/K2
  const double plus = twist_under_torque(c, T), minus = twist_under_torque(c, -T);
  EXPECT_NEAR(plus, expected, 1e-5 * expected);
  EXPECT_NEAR(minus, -expected, 1e-5 * expected);
  EXPECT_NEAR(plus - minus, 6e-4 + 2 * (7.0 / 1.3e4 + (applied - 7.0) / 1.8e4), 2e-5 * expected) << "lost motion";
}

// The alternating preload (sim::preload_torque) takes the lost motion up on
// one flank, then on the other: the twist at rest flips with the torque.
TEST(DriveTrainStep, AlternatingPreloadTakesUpEachFlankInTurn) {
  TwinConfig c = fast_config();
  DriveChain& d = c.effects.drive.chain[0];
  d.stiffness_Nm_per_rad = {1.3e4, 1.3e4, 1.3e4};
  d.band_Nm = {7.0, 25.0};
  d.backlash_rad = 6e-4;
  c.drives[0].mode = ServoMode::kTorque;
  c.drives[0].torque_Nm = 4.0;
  c.drives[0].alternate_s = 1.5;
  const double expected = 3e-4 + 4.0 / 1.3e4;  // b/2 + T/K
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  for (const double sign : {1.0, -1.0, 1.0}) {
    run_for(m, s, 1.5);  // to just before the next change of sign (the drive's updates start at 0)
    twin_sense(m, s);
    EXPECT_EQ(s.last.torque[0], sign * 4.0);
    EXPECT_NEAR(s.last.theta_motor[0] - s.last.theta_a[0], sign * expected, 1e-3 * expected);
  }
}

TEST(DriveTrainStep, LinkStandsOffByTheTransmissionError) {
  const Robot robot;
  TwinConfig c = fast_config();
  c.effects.gear_ratio = 10.0;
  c.effects.mjcf.compliance_rad_per_Nm.fill(1e-4);
  for (DriveChain& d : c.effects.drive.chain) {
    d.te_joint_rad = 1e-3, d.te_joint_phase_rad = 0.4;
    d.te_motor_rad = 2e-4, d.te_motor_phase_rad = 2.0;
  }
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  const Eigen::Vector3d theta_m0 = s.last.theta_motor;
  twin_command(s, readings_at(robot, robot.home + Eigen::Vector2d(-30.0, 20.0)), Eigen::Vector3d::Zero());
  run_for(m, s, 1.5);
  twin_sense(m, s);
  for (size_t k = 0; k < 3; ++k) {
    const DriveChain& d = c.effects.drive.chain[k];
    const double th = s.last.theta_motor[static_cast<long>(k)];
    // TE written out (not the library's function): A_j sin(th + phi_j) + A_m sin(2 N th + phi_m).
    const auto te = [&](double x) { return 1e-3 * std::sin(x + 0.4) + 2e-4 * std::sin(2 * 10.0 * x + 2.0); };
    const double gear = te(th) - te(theta_m0[static_cast<long>(k)]);
    const double hooke = 1e-4 * s.last.torque[static_cast<long>(k)];
    EXPECT_GT(std::abs(gear), 1e-4) << "chain " << k + 1 << ": the move should change the TE";
    EXPECT_NEAR(th - s.last.theta_a[static_cast<long>(k)], gear + hooke, 1e-9) << "chain " << k + 1 << " " << d.te_joint_rad;
  }
}

// Two drives hold position and the third is off, so at rest the mechanism
// carries no torque (J^T tau = 0 with tau_3 = 0 and J's 2 x 2 block
// regular): each holding drive applies nothing, and reports the torque that
// cancels its motor's cogging through its own torque constant,
// tau_reported = -A_c sin(P N theta_m + phi_c) / (1 + delta).
TEST(DriveTrainStep, HoldingDrivesReportTheTorqueThatCancelsCogging) {
  TwinConfig c = fast_config();
  c.drives[2].mode = ServoMode::kTorqueOff;
  c.effects.gear_ratio = 10.0;
  c.effects.drive.cogging_periods_per_motor_rev = 24;
  const double delta[2] = {0.05, -0.08}, phase[2] = {0.3, 2.2};
  for (size_t k = 0; k < 2; ++k) {
    DriveChain& d = c.effects.drive.chain[k];
    d.cogging_Nm = 0.2, d.cogging_phase_rad = phase[k], d.torque_constant_delta = delta[k];
  }
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  run_for(m, s, 1.0);
  twin_sense(m, s);
  double largest = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double cog = 0.2 * std::sin(24 * 10.0 * s.last.theta_motor[i] + phase[i]);
    EXPECT_NEAR(s.last.torque[i], -cog / (1.0 + delta[i]), 1e-4) << "drive " << i + 1;
    largest = std::max(largest, std::abs(cog));
  }
  EXPECT_GT(largest, 0.02) << "the test should see some cogging";
  EXPECT_LT(s.last.motor_velocity.cwiseAbs().maxCoeff(), 1e-6) << "not at rest";
}

// Mean powers over two circles: the drives' input, the rotors' friction
// (qfrc_applied on the rotor less the mesh's -tau_t: the friction torque f,
// power -f omega_m), and mean(F(tau_t, omega_m) |omega_m|) of a friction law F.
struct Power {
  double tau_w = 0, friction = 0, law = 0;
};

Power circle_power(const TwinConfig& config, const std::function<double(double, double)>& F) {
  const Robot robot;
  const TwinModel m(robot, config);
  TwinState s(m, 1);
  Session session = make_session(m, s, robot, nullptr);
  const CirclePath circle{robot.home, 30.0, 1.0, 3.0};
  follow_path(session, make_move(session.desired, path_at(circle, 0.0).p, 100.0));
  follow_path(session, CirclePath{robot.home, 30.0, 1.0, 1.0});
  Power p;
  long n = 0;
  const double period = m.timestep_s() * m.steps_per_tick();
  for (double t = 0.0; t < 2.0 - 1e-9; t += period, ++n) {
    const TwinSnapshot snap = advance(session, path_at(circle, t));  // the last step's start
    p.tau_w += snap.torque.dot(snap.motor_velocity);
    for (int i = 0; i < 3; ++i) {
      const double omega = snap.motor_velocity[i], tau_t = s.drive_train.tau_t[static_cast<size_t>(i)];
      p.friction -= (s.data->qfrc_applied[m.dof_m[i]] + tau_t) * omega;
      p.law += F(tau_t, omega) * std::abs(omega);
    }
  }
  p.tau_w /= n, p.friction /= n, p.law /= n;
  return p;
}

TwinConfig coulomb_base() {
  TwinConfig c = fast_config();
  c.effects.mjcf.compliance_rad_per_Nm.fill(1e-4);
  c.effects.mjcf.coulomb_Nm.fill(0.3);
  return c;
}

TEST(DriveTrainStep, LoadFrictionCostsItsPower) {
  TwinConfig loaded = coulomb_base();
  for (DriveChain& d : loaded.effects.drive.chain) d.load_friction = 0.2;
  const Power p0 = circle_power(coulomb_base(), [](double, double) { return 0.0; });
  const Power p1 = circle_power(loaded, [](double tau_t, double) { return 0.2 * std::abs(tau_t); });
  ASSERT_GT(p1.law, 0.01);
  EXPECT_NEAR((p1.tau_w - p0.tau_w) / p1.law, 1.0, 0.05);
}

// The Stribeck term at a speed scale v_s of the circle's own joint speeds
// (0.3 rad/s), so that its shape, not only its level, sets the power. The
// drives pay the friction's extra power (energy balance), and the friction
// reaches the Stribeck law's power F |omega| but for MuJoCo's soft creep
// through each reversal (sim/rotor_friction.hpp: below the bound the rotor
// creeps at R / b = 0.4 rad/s per N m with the default solref and solimp),
// measured 97 %.
TEST(DriveTrainStep, StribeckFrictionCostsItsPower) {
  TwinConfig sticky = coulomb_base();
  for (DriveChain& d : sticky.effects.drive.chain) d.stiction_excess_Nm = 0.4, d.stribeck_speed_rad_s = 0.3;
  const auto stribeck = [](double, double w) { return 0.3 + 0.4 * std::exp(-(w / 0.3) * (w / 0.3)); };
  const Power p0 = circle_power(coulomb_base(), [](double, double) { return 0.3; });
  const Power p1 = circle_power(sticky, stribeck);
  EXPECT_NEAR((p1.tau_w - p0.tau_w) / (p1.friction - p0.friction), 1.0, 0.05);
  EXPECT_GT(p1.friction - p0.friction, 0.5 * (p1.law - p0.law)) << "the stiction should cost power";
  EXPECT_NEAR(p1.friction / p1.law, 0.985, 0.015);
  const Power flat = circle_power(sticky, [](double, double) { return 0.7; });
  EXPECT_LT(p1.law, 0.9 * flat.law) << "the circle's speeds should reach the Stribeck fall";
}

TEST(DriveTrainStep, RefusesAMeshWithoutRotorOrTooStiff) {
  TwinConfig c = fast_config();
  c.effects.drive.chain[1].backlash_rad = 1e-3;
  try {
    TwinModel m(Robot{}, c);
    FAIL() << "backlash without a rotor was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("chain 2"), std::string::npos) << e.what();
  }
  TwinConfig stiff;  // 0.5 ms steps: omega dt = 1.7 for 2.3e4 N m/rad
  stiff.effects.drive.chain[0].stiffness_Nm_per_rad = {1.3e4, 1.8e4, 2.3e4};
  stiff.effects.drive.chain[0].band_Nm = {7.0, 25.0};
  try {
    TwinModel m(Robot{}, stiff);
    FAIL() << "a band beyond the explicit stability limit was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("drive_stiffness_Nm_per_rad"), std::string::npos) << e.what();
  }
}

TEST(DriveTrainStep, DrawnDriveTrainsRunStableOnTheRealisticTwin) {
  const Robot robot;
  Rng rng(7);
  for (int trial = 0; trial < 3; ++trial) {
    TwinConfig c = fast_config();
    c.effects = realistic_effects();
    c.effects.gear_ratio = 10.0;
    draw_drive_train(rng, c.effects);
    const TwinModel m(robot, c);
    TwinState s(m, 1);
    twin_command(s, readings_at(robot, robot.home + Eigen::Vector2d(20.0, 20.0)), Eigen::Vector3d::Zero());
    run_for(m, s, 0.5);
    twin_sense(m, s);
    EXPECT_LT(s.last.violation_m, 1e-6);
    EXPECT_LT((s.last.ee_mm - (robot.home + Eigen::Vector2d(20.0, 20.0))).norm(), 0.5) << "trial " << trial;
  }
}

}  // namespace
}  // namespace gpm::sim
