// Tests of the physical effects in sim/twin.cpp and sim/effects.cpp (models/mjcf.cpp
// builds the MuJoCo part), each against an independent physical expectation:
// - compliance: at rest the transmission is a spring, so link - motor = -c tau
//   (the spring carries the drive torque; Hooke's law), per joint;
// - thermal: a link measured in the running model has length
//   L0 (1 + alpha rise (1 - exp(-t / tau))) and the loops stay closed;
// - clearance: a force reversed on the end-effector moves it through a dead
//   band of about the clearance only when every chain is loose (the redundant
//   closure pins a single loose chain), and each passive link, a two-force
//   member, gives axially by the play of its two pins, 2c, under a preload;
//   the tips of chains 2 and 3 (closed by their play) stay within 2c of the hub;
//   at home the centring springs exert nothing, and the hub stays on each
//   passive link's line (the play is axial);
// - friction: by power balance over whole revolutions of a circle, the
//   drives' extra mean power is c sum |w_i| (Coulomb) and b sum w_i^2 (viscous),
//   on rigid drives (MuJoCo's frictionloss rows) and on compliant ones (the
//   rotor's friction solved by the twin, sim/rotor_friction.cpp);
// - cyclic error: the reading error fitted over many angles is A sin(theta + phase);
// - skew: the reading of encoder i equals the true motor angle skew_i earlier.
#include "sim/effects.hpp"

#include <cmath>
#include <deque>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "sim/sampling.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

Robot perturbed() {
  Robot r;
  const double d[kNumParams] = {0, 0, 0, 0, 0.2, -0.3, 0.25, -0.2, 0.15, -0.1, 0.3, 0.2, 0.004, -0.006, 0.003};
  for (int i = 0; i < kNumParams; ++i) r.geometry[i] += d[i];
  return r;
}

// A config with a 4 kHz drive loop and 0.25 ms steps (stable with compliance), ideal encoders.
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

TEST(Effects, CompliantTransmissionTwistsByComplianceTimesTorque) {
  const Robot actual = perturbed();
  TwinConfig c = fast_config();
  const std::array<double, 3> comp = {1e-4, 2e-4, 1.5e-4};
  c.effects.mjcf.compliance_rad_per_Nm = comp;
  const TwinModel m(actual, c);
  TwinState s(m, 1);
  // Commands inconsistent with the closed chain (as a miscalibrated
  // controller gives): the three drives fight with a preload.
  twin_command(s, s.last.readings + Eigen::Vector3d(0.01, -0.008, 0.006), Eigen::Vector3d::Zero());
  run_for(m, s, 1.0);
  twin_sense(m, s);
  int loaded = 0;
  for (int i = 0; i < 3; ++i) {
    const double tau = s.last.torque[i];
    const double twist = wrap_pi(s.last.theta_a[i] - (s.last.readings[i] + actual.geometry.dth_(i)));
    if (std::abs(tau) < 1.0) continue;
    ++loaded;
    EXPECT_NEAR(twist / (-comp[static_cast<size_t>(i)] * tau), 1.0, 0.01) << "joint " << i + 1 << " tau " << tau;
  }
  EXPECT_GE(loaded, 2) << "the drives should fight with a preload of several N m";
  EXPECT_LT(s.last.violation_m, 1e-6);
}

TEST(Effects, RigidTransmissionReadsTheLink) {
  const Robot actual = perturbed();
  const TwinModel m(actual, fast_config());
  EXPECT_FALSE(m.compliant[0]);
  TwinState s(m, 1);
  twin_command(s, s.last.readings + Eigen::Vector3d(0.01, 0.0, 0.0), Eigen::Vector3d::Zero());
  run_for(m, s, 0.3);
  twin_sense(m, s);
  ASSERT_GT(s.last.torque.cwiseAbs().maxCoeff(), 1.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(std::abs(wrap_pi(s.last.theta_a[i] - s.last.readings[i] - actual.geometry.dth_(i))), 1e-12);
}

TEST(Effects, TooStiffTransmissionIsRefusedWithTheKey) {
  TwinConfig c = fast_config();
  c.effects.mjcf.compliance_rad_per_Nm.fill(1e-7);
  try {
    TwinModel m(Robot{}, c);
    FAIL() << "a stiffness beyond the explicit stability limit was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("transmission_compliance_rad_per_Nm"), std::string::npos);
  }
  TwinConfig slow;  // 2 kHz velocity loop on the rotor alone: kv T / armature = 1.9
  slow.effects.mjcf.compliance_rad_per_Nm.fill(1e-4);
  EXPECT_THROW(TwinModel(Robot{}, slow), InputError);
}

double distance(const mjData* d, const double* a, const double* b) {
  (void)d;
  return std::hypot(a[0] - b[0], a[1] - b[1]);
}

TEST(Effects, ThermalGrowthLengthensLinksAsAFirstOrderRise) {
  const Robot actual = perturbed();
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.thermal = ThermalEffect{1e-4, 10.0, 0.2};  // 1e-3 final growth (0.24 mm), fast for the test
  const TwinModel m(actual, c);
  TwinState s(m, 1);
  const mjModel* mm = state_model(m, s);
  ASSERT_NE(mm, m.mj()) << "the shared model must stay constant";
  const int base1 = mj_name2id(mm, mjOBJ_SITE, "base_a1");
  const int elbow1 = mj_name2id(mm, mjOBJ_BODY, "link_b1");
  const int tip2 = mj_name2id(mm, mjOBJ_SITE, "tip_b2");
  const int elbow2 = mj_name2id(mm, mjOBJ_BODY, "link_b2");
  for (double t_end : {0.1, 0.3, 0.6}) {
    run_for(m, s, t_end - s.data->time);
    mj_forward(mm, s.data.get());
    // The geometry in effect is the one set at the start of the last step.
    const double t = s.data->time - m.timestep_s();
    const double g = 1e-4 * 10.0 * (1.0 - std::exp(-t / 0.2));
    const mjData* d = s.data.get();
    const double la1 = distance(d, d->site_xpos + 3 * base1, d->xpos + 3 * elbow1);
    const double lb2 = distance(d, d->xpos + 3 * elbow2, d->site_xpos + 3 * tip2);
    EXPECT_NEAR(la1, actual.geometry.la_(0) * 1e-3 * (1.0 + g), 2e-9) << "t " << t;
    EXPECT_NEAR(lb2, actual.geometry.lb_(1) * 1e-3 * (1.0 + g), 2e-9) << "t " << t;
    EXPECT_LT(constraint_violation_m(m, d), 1e-7) << "the loops stay closed at t " << t;
  }
  // The base plate grows too: A3 - A1 scaled by the same factor.
  const Geometry g0 = actual.geometry;
  const Geometry g1 = thermal_geometry(g0, 1e-3);
  EXPECT_NEAR((g1.A(2) - g1.A(0)).norm(), (g0.A(2) - g0.A(0)).norm() * 1.001, 1e-9);
  EXPECT_DOUBLE_EQ(g1.dth_(1), g0.dth_(1));
}

// Displacement of the end-effector between a force +F and -F along x while the drives hold.
double dead_band_mm(const std::array<double, 3>& clearance_m) {
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.mjcf.clearance_m = clearance_m;
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  const int ee = mj_name2id(m.mj(), mjOBJ_BODY, "ee");
  double x[2];
  for (int k = 0; k < 2; ++k) {
    s.data->xfrc_applied[6 * ee + 0] = k == 0 ? 0.2 : -0.2;  // N
    run_for(m, s, 0.4);
    x[k] = s.last.ee_mm.x();
  }
  return x[0] - x[1];
}

TEST(Effects, ClearanceGivesADeadBandOnlyWhenEveryChainIsLoose) {
  const double c = 0.05e-3;  // 50 um, large against the drives' own give under 2 N
  const double rigid = dead_band_mm({0, 0, 0});
  const double all = dead_band_mm({c, c, c}) - rigid;
  const double one = dead_band_mm({c, 0, 0}) - rigid;
  EXPECT_GT(rigid, 0.0);
  EXPECT_GT(all, 1.0 * c * 1e3) << "all chains loose: a dead band of at least the clearance";
  EXPECT_LT(all, 8.0 * c * 1e3);
  EXPECT_LT(std::abs(one), 0.2 * c * 1e3) << "one loose chain is pinned by the other two";
}

// A passive link pinned at both ends carries only an axial force (a two-force
// member), so the play of its two loose pins shows as a change of its
// effective length |C - B_i| of up to 2c, and the fighting drives' preload,
// which stretches or compresses every passive link, takes that play up.
TEST(Effects, ClearanceLetsEachPassiveLinkGiveTwiceTheClearanceAxially) {
  const double c_mm = 0.05;  // large against the limits' own give
  const auto length_change_mm = [](const TwinModel& m, const TwinState& s, int i) {
    const Geometry& g = m.actual().geometry;
    const Eigen::Vector2d b = g.A(i) + g.la_(i) * Eigen::Vector2d(std::cos(s.last.theta_a[i]), std::sin(s.last.theta_a[i]));
    return (s.last.ee_mm - b).norm() - g.lb_(i);
  };
  for (const double c : {0.0, c_mm}) {
    TwinConfig config;
    config.encoder.bits = 0;
    config.effects.mjcf.clearance_m.fill(c * kMetresPerMm);
    const TwinModel m(Robot{}, config);
    TwinState s(m, 1);
    // Commands 5 mm apart at the link tips, far more than the play absorbs.
    twin_command(s, s.last.readings + Eigen::Vector3d(0.02, -0.02, 0.01), Eigen::Vector3d::Zero());
    run_for(m, s, 0.5);
    for (int i = 0; i < 3; ++i) {
      const double d = std::abs(length_change_mm(m, s, i));
      // Never more than the two pins' play (1 um for the limits' own give) ...
      EXPECT_LT(d, 2.0 * c + 1e-3) << "chain " << i + 1 << ", clearance " << c << " mm";
      // ... and under the preload all of it (both pins at their limits).
      if (c > 0.0) {
        EXPECT_GT(d, 1.9 * c) << "chain " << i + 1 << ", clearance " << c << " mm";
      }
    }
  }
}

// Chains 2 and 3 close with clearance through the play itself: their tips
// keep within 2c of the hub (the two pins' play summed) and, under the
// fighting drives' preload, take all of it; the loop-closure gap counts only
// what lies beyond the play, so it stays at the limits' own give.
TEST(Effects, ClearanceKeepsTheHubWithinTwiceTheClearanceOfEachTip) {
  const double c = 0.05e-3;  // m
  TwinConfig config;
  config.encoder.bits = 0;
  config.effects.mjcf.clearance_m.fill(c);
  const TwinModel m(Robot{}, config);
  TwinState s(m, 1);
  twin_command(s, s.last.readings + Eigen::Vector3d(0.02, -0.02, 0.01), Eigen::Vector3d::Zero());
  run_for(m, s, 0.5);
  const mjData* d = s.data.get();
  const Eigen::Vector3d ee(d->site_xpos + 3 * m.site_ee);
  for (int i = 1; i < 3; ++i) {
    const double gap = (Eigen::Vector3d(d->site_xpos + 3 * m.site_tip[i]) - ee).norm();
    EXPECT_LT(gap, 2.0 * c + 1e-6) << "chain " << i + 1;
    EXPECT_GT(gap, 1.9 * c) << "chain " << i + 1;
  }
  EXPECT_LT(s.last.violation_m, 1e-6);
}

// The pins' centring springs rest with the hub centred: at the assembled home,
// at rest, the clearance exerts no force on any joint (a tendon's default
// rest length is taken at qpos_spring, not at home: 0.72 m away, 70 N).
// Under the preload each passive link stays a two-force member: the hub
// sits on its link's line, not round the rim of the play.
TEST(Effects, ClearanceRestsCentredAndGivesOnlyAlongTheLink) {
  const double c = 0.05e-3;  // m
  TwinConfig config;
  config.encoder.bits = 0;
  config.effects.mjcf.clearance_m.fill(c);
  const TwinModel m(Robot{}, config);
  TwinState s(m, 1);
  const mjData* d = s.data.get();
  for (int k = 0; k < m.mj()->nv; ++k) EXPECT_NEAR(d->qfrc_passive[k], 0.0, 1e-9) << "dof " << k;
  twin_command(s, s.last.readings + Eigen::Vector3d(0.02, -0.02, 0.01), Eigen::Vector3d::Zero());
  run_for(m, s, 0.5);
  const Eigen::Vector3d ee(d->site_xpos + 3 * m.site_ee);
  for (int i = 1; i < 3; ++i) {
    const Eigen::Vector3d tip(d->site_xpos + 3 * m.site_tip[i]);
    const Eigen::Vector3d across(d->xmat[9 * m.body_elbow[i] + 1], d->xmat[9 * m.body_elbow[i] + 4], 0.0);
    EXPECT_LT(std::abs((ee - tip).dot(across)), 0.01 * c) << "chain " << i + 1;
  }
}

// Mean drive power sum tau_i w_i and mean sum |w_i|, sum w_i^2 over whole revolutions of a circle.
struct Power {
  double tau_w = 0, abs_w = 0, w2 = 0;
};

Power circle_power(const MjcfEffects& fx, TwinConfig c = {}) {
  c.encoder.bits = 0;
  c.effects.mjcf = fx;
  const Robot robot;
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  Session session = make_session(m, s, robot, nullptr);
  const CirclePath circle{robot.home, 30.0, 1.0, 3.0};
  follow_path(session, make_move(session.desired, path_at(circle, 0.0).p, 100.0));
  follow_path(session, CirclePath{robot.home, 30.0, 1.0, 1.0});  // reach the steady state
  Power p;
  long n = 0;
  const double period = m.timestep_s() * m.steps_per_tick();
  for (double t = 0.0; t < 2.0 - 1e-9; t += period, ++n) {
    const TwinSnapshot snap = advance(session, path_at(circle, t));
    p.tau_w += snap.torque.dot(snap.motor_velocity);
    p.abs_w += snap.motor_velocity.cwiseAbs().sum();
    p.w2 += snap.motor_velocity.squaredNorm();
  }
  p.tau_w /= n, p.abs_w /= n, p.w2 /= n;
  return p;
}

TEST(Effects, CoulombAndViscousFrictionCostTheirPower) {
  const Power base = circle_power({});
  MjcfEffects coulomb;
  coulomb.coulomb_Nm.fill(0.5);
  const Power pc = circle_power(coulomb);
  EXPECT_NEAR((pc.tau_w - base.tau_w) / (0.5 * base.abs_w), 1.0, 0.05);
  MjcfEffects viscous;
  viscous.viscous_Nm_s.fill(0.5);
  const Power pv = circle_power(viscous);
  EXPECT_NEAR((pv.tau_w - base.tau_w) / (0.5 * base.w2), 1.0, 0.05);
}

// On a compliant drive the rotor's friction is solved by the twin in closed
// form (sim/rotor_friction.hpp) instead of by MuJoCo's frictionloss row: the
// same power balance holds, measured on the rotors' velocities.
TEST(Effects, CoulombFrictionOnCompliantDrivesCostsItsPower) {
  MjcfEffects compliant;
  compliant.compliance_rad_per_Nm.fill(1e-4);
  MjcfEffects coulomb = compliant;
  coulomb.coulomb_Nm.fill(0.5);
  {
    TwinConfig c = fast_config();
    c.effects.mjcf = coulomb;
    const TwinModel m(Robot{}, c);
    for (int i = 0; i < 3; ++i) {
      ASSERT_TRUE(m.compliant[i]);
      EXPECT_EQ(m.rotor_friction[i].dof, m.dof_m[i]);
      EXPECT_EQ(m.rotor_friction[i].coulomb_Nm, 0.5);
      EXPECT_EQ(m.mj()->dof_frictionloss[m.dof_m[i]], 0.0) << "MuJoCo's row would act twice";
    }
    c.effects.mjcf.compliance_rad_per_Nm.fill(0.0);
    const TwinModel rigid(Robot{}, c);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(rigid.rotor_friction[i].dof, -1);
      EXPECT_EQ(rigid.mj()->dof_frictionloss[rigid.dof_a[i]], 0.5);
    }
  }
  const Power base = circle_power(compliant, fast_config());
  const Power pc = circle_power(coulomb, fast_config());
  EXPECT_NEAR((pc.tau_w - base.tau_w) / (0.5 * base.abs_w), 1.0, 0.05);
}

TEST(Effects, CyclicErrorIsASineOfTheReadingWithItsPhase) {
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.encoder_cyclic_rad = {1e-3, 2e-3, 5e-4};
  c.effects.encoder_phase_rad = {0.3, 2.0, 4.5};
  const Robot robot = perturbed();
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  // Sweep the joints over a range of angles, fit e = a sin(x) + b cos(x) per encoder.
  Eigen::Matrix2d AtA[3];
  Eigen::Vector2d Atb[3];
  for (int i = 0; i < 3; ++i) AtA[i].setZero(), Atb[i].setZero();
  Session session = make_session(m, s, robot, nullptr);
  const CirclePath circle{robot.home, 60.0, 1.0, 1.0};
  follow_path(session, make_move(session.desired, path_at(circle, 0.0).p, 100.0));
  const double period = m.timestep_s() * m.steps_per_tick();
  for (double t = 0.0; t < 1.0; t += period) {
    const TwinSnapshot snap = advance(session, path_at(circle, t));
    for (int i = 0; i < 3; ++i) {
      const double x = snap.theta_motor[i] - robot.geometry.dth_(i);
      const double e = wrap_pi(snap.readings[i] - x);
      const Eigen::Vector2d row(std::sin(x), std::cos(x));
      AtA[i] += row * row.transpose();
      Atb[i] += row * e;
    }
  }
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d ab = AtA[i].ldlt().solve(Atb[i]);  // A cos(ph), A sin(ph)
    EXPECT_NEAR(std::hypot(ab[0], ab[1]), c.effects.encoder_cyclic_rad[i], 1e-3 * c.effects.encoder_cyclic_rad[i]);
    EXPECT_NEAR(wrap_pi(std::atan2(ab[1], ab[0]) - c.effects.encoder_phase_rad[i]), 0.0, 1e-3);
  }
}

TEST(Effects, SkewedEncodersReadTheAngleOfAnEarlierInstant) {
  TwinConfig c;
  c.encoder.bits = 0;
  c.effects.encoder_skew_s = {0.0, 0.001, 0.002};  // 2 and 4 drive loop periods
  const Robot robot;
  const TwinModel m(robot, c);
  TwinState s(m, 1);
  Session session = make_session(m, s, robot, nullptr);
  const CirclePath circle{robot.home, 40.0, 0.5, 1.0};
  follow_path(session, make_move(session.desired, path_at(circle, 0.0).p, 100.0));
  const double period = m.timestep_s() * m.steps_per_tick();
  std::deque<Eigen::Vector3d> history;  // true motor angles, one per drive loop
  double worst[3] = {0, 0, 0}, moved[3] = {0, 0, 0};
  for (double t = 0.0; t < 0.5; t += period) {
    const TwinSnapshot snap = advance(session, path_at(circle, t));
    history.push_back(snap.theta_motor);
    if (history.size() > 5) history.pop_front();
    if (history.size() < 5 || t < 0.1) continue;
    for (int i = 0; i < 3; ++i) {
      const size_t back = static_cast<size_t>(std::lround(c.effects.encoder_skew_s[i] / period));
      const double then = history[history.size() - 1 - back][i] - robot.geometry.dth_(i);
      worst[i] = std::max(worst[i], std::abs(wrap_pi(snap.readings[i] - then)));
      moved[i] = std::max(moved[i], std::abs(snap.motor_velocity[i]) * c.effects.encoder_skew_s[i]);
    }
  }
  EXPECT_LT(worst[0], 1e-12) << "encoder 1 is the reference";
  for (int i = 1; i < 3; ++i) {
    ASSERT_GT(moved[i], 1e-4) << "the joints should move enough for the skew to matter";
    EXPECT_LT(worst[i], 0.02 * moved[i]) << "encoder " << i + 1;
  }
}

}  // namespace
}  // namespace gpm::sim
