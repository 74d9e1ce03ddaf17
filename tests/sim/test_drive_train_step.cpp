// Tests of sim/drive_train_step.cpp: the drive train inside the twin, each
// against an independent expectation.
// - the mesh law applied through qfrc_applied with a linear stiffness (and a
//   vanishing dead band) reproduces MuJoCo's own tendon spring step for step,
//   rotor friction included (signs and wiring);
// - static deflection: a drive in torque mode pushing T on its chain twists
//   its transmission by b/2 + f^-1((1 + delta) T) (the catalogue's torsion
//   formula on top of the dead band; the applied torque, not the reported
//   one, loads the mesh); between +T and -T the lost motion is b + 2 f^-1;
// - transmission error: at rest the link stands at theta_m - (TE(theta_m) -
//   TE(theta_m0)) - tau / K (the gear's kinematic error plus Hooke's law);
// - load-dependent friction: by power balance over a circle, the drives'
//   extra mean power is mu mean(|tau_t| |omega_m|);
// - the twin refuses a mesh without a rotor, or bands too stiff for the timestep;
// - drawn (randomized) drive trains on the realistic twin run stable at 0.25 ms.
#include "sim/drive_train_step.hpp"

#include <cmath>

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
  EXPECT_NEAR(plus, expected, 1e-3 * expected);
  EXPECT_NEAR(minus, -expected, 1e-3 * expected);
  EXPECT_NEAR(plus - minus, 6e-4 + 2 * (7.0 / 1.3e4 + (applied - 7.0) / 1.8e4), 2e-3 * expected) << "lost motion";
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
    EXPECT_NEAR(th - s.last.theta_a[static_cast<long>(k)], gear + hooke, 1e-7) << "chain " << k + 1 << " " << d.te_joint_rad;
  }
}

// Mean power the drives put in, and mu mean(|tau_t| |omega_m|), over two circles.
struct Power {
  double tau_w = 0, load = 0;
};

Power circle_power(const TwinConfig& config, double mu) {
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
    const TwinSnapshot snap = advance(session, path_at(circle, t));
    p.tau_w += snap.torque.dot(snap.motor_velocity);
    for (int i = 0; i < 3; ++i) p.load += mu * std::abs(s.drive_train.tau_t[static_cast<size_t>(i)] * snap.motor_velocity[i]);
  }
  p.tau_w /= n, p.load /= n;
  return p;
}

TEST(DriveTrainStep, LoadFrictionCostsItsPower) {
  TwinConfig base = fast_config();
  base.effects.mjcf.compliance_rad_per_Nm.fill(1e-4);
  base.effects.mjcf.coulomb_Nm.fill(0.3);
  TwinConfig loaded = base;
  for (DriveChain& d : loaded.effects.drive.chain) d.load_friction = 0.2;
  const Power p0 = circle_power(base, 0.0), p1 = circle_power(loaded, 0.2);
  ASSERT_GT(p1.load, 0.01);
  EXPECT_NEAR((p1.tau_w - p0.tau_w) / p1.load, 1.0, 0.05);
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
