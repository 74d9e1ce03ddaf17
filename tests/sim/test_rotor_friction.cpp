// Tests of sim/rotor_friction.cpp: the closed-form friction of a rotor that is
// a one-dof tree of its own reproduces MuJoCo's frictionloss row. Two copies
// of one model (a rotor with armature, damping and Coulomb friction, driven by
// a motor and joined to a link by a stiff torsional spring, as in the twin's
// compliant transmission) are stepped side by side: one with MuJoCo's
// frictionloss, one with that row taken over by take_rotor_friction. The
// motor torque sweeps through +-1.5 F, so the rotor sticks (creeps, in MuJoCo's
// soft friction) and slips in both directions; the two trajectories agree to
// round-off (about 1e-14 rad). A hard Coulomb clamp (regulariser 0)
// gives a trajectory visibly different under the same sweep, so the
// agreement is a property of the soft model, not of a loose tolerance. The
// soft friction as a law of the motion, on MuJoCo's own solver:
// -F sat((omega + alpha / b) / (F R / b)), the speed 1 / b ahead. And the
// friction time constant (effects friction_timeconst_s) against a coasting
// rotor worked by hand: hard Coulomb at two steps, MuJoCo's soft law at 0.02 s.
#include "sim/rotor_friction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "sim/mujoco_util.hpp"

namespace gpm::sim {
namespace {

constexpr double kFriction_Nm = 0.3;

// Rotor (world child, hinge "joint_m") and link (world child, hinge
// "joint_a"), joined by a fixed tendon of stiffness 2e4 N m/rad; the link
// carries a soft spring to zero so the chain has somewhere to rest.
const char* kRotorAndLink = R"(<mujoco>
  <option timestep="0.00025"><flag contact="disable"/></option>
  <worldbody>
    <body name="rotor">
      <joint name="joint_m" type="hinge" axis="0 0 1" damping="0.05" armature="0.0026" frictionloss="0.3"/>
      <inertial pos="0 0 0" mass="0.5" diaginertia="1e-6 1e-6 1e-6"/>
    </body>
    <body name="link">
      <joint name="joint_a" type="hinge" axis="0 0 1" stiffness="2" damping="0.01"/>
      <inertial pos="0.1 0 0" mass="0.8" diaginertia="1e-4 3e-3 3e-3"/>
      <body name="tip" pos="0.2 0 0">
        <joint name="joint_b" type="hinge" axis="0 0 1"/>
        <inertial pos="0.1 0 0" mass="0.3" diaginertia="1e-5 1e-3 1e-3"/>
      </body>
    </body>
  </worldbody>
  <tendon>
    <fixed name="twist" stiffness="2e4">
      <joint joint="joint_m" coef="1"/>
      <joint joint="joint_a" coef="-1"/>
    </fixed>
  </tendon>
  <actuator><motor name="motor" joint="joint_m" gear="1"/></actuator>
</mujoco>)";

struct Sweep {
  double max_dq_rad = 0.0;     // largest |q_ref - q_closed| over all dofs and steps
  double max_dv_rad_s = 0.0;   // largest |v_ref - v_closed|
  double travel_rad = 0.0;     // largest |q_m| of the reference (how far the rotor went)
  double stick_fraction = 0.0; // share of steps the friction stayed inside +-F (the row's quadratic zone)
};

// Steps the MuJoCo-frictionloss model and the closed-form copy for seconds
// under ctrl = 1.5 F sin(2 pi t / 0.5 s); hard_clamp replaces the closed form
// by a rigid Coulomb clamp (the counter-check).
Sweep sweep(double seconds, bool hard_clamp = false) {
  const ModelPtr m_ref = load_model_from_xml(kRotorAndLink);
  const ModelPtr m_cf = load_model_from_xml(kRotorAndLink);
  const int dof = m_cf->jnt_dofadr[require_id(m_cf.get(), mjOBJ_JOINT, "joint_m")];
  RotorFriction r = take_rotor_friction(m_cf.get(), dof, require_id(m_cf.get(), mjOBJ_ACTUATOR, "motor"));
  if (hard_clamp) r.regulariser = 0.0, r.damping_ref = 0.0;
  const DataPtr d_ref(mj_makeData(m_ref.get()));
  const DataPtr d_cf(mj_makeData(m_cf.get()));
  Sweep s;
  const int steps = static_cast<int>(std::lround(seconds / m_ref->opt.timestep));
  int stick = 0;
  for (int k = 0; k < steps; ++k) {
    const double u = 1.5 * kFriction_Nm * std::sin(2.0 * std::numbers::pi * d_ref->time / 0.5);
    d_ref->ctrl[0] = u;
    mj_step(m_ref.get(), d_ref.get());
    mj_step1(m_cf.get(), d_cf.get());
    d_cf->ctrl[0] = u;
    d_cf->qfrc_applied[dof] = rotor_friction_torque(m_cf.get(), d_cf.get(), r);
    if (std::abs(d_cf->qfrc_applied[dof]) < (1.0 - 1e-9) * kFriction_Nm) ++stick;
    mj_step2(m_cf.get(), d_cf.get());
    for (int v = 0; v < m_ref->nv; ++v) {
      s.max_dq_rad = std::max(s.max_dq_rad, std::abs(d_ref->qpos[v] - d_cf->qpos[v]));
      s.max_dv_rad_s = std::max(s.max_dv_rad_s, std::abs(d_ref->qvel[v] - d_cf->qvel[v]));
    }
    s.travel_rad = std::max(s.travel_rad, std::abs(d_ref->qpos[dof]));
  }
  s.stick_fraction = static_cast<double>(stick) / steps;
  return s;
}

TEST(RotorFriction, TakesTheRowOverAndZeroesFrictionloss) {
  const ModelPtr m = load_model_from_xml(kRotorAndLink);
  const int dof = m->jnt_dofadr[require_id(m.get(), mjOBJ_JOINT, "joint_m")];
  const RotorFriction r = take_rotor_friction(m.get(), dof, 0);
  EXPECT_EQ(r.dof, dof);
  EXPECT_DOUBLE_EQ(r.coulomb_Nm, kFriction_Nm);
  EXPECT_EQ(m->dof_frictionloss[dof], 0.0);
  // Default solref (0.02 s, 1) and solimp (0.9, 0.95, ...): b = 2 / (0.95 *
  // 0.02) and R = (1 - 0.9) / 0.9 w0.
  EXPECT_NEAR(r.damping_ref, 2.0 / (0.95 * 0.02), 1e-9);
  EXPECT_NEAR(r.regulariser, (0.1 / 0.9) * m->dof_invweight0[dof], 1e-12);
}

TEST(RotorFriction, MatchesMujocoFrictionlossThroughStickAndSlip) {
  const Sweep s = sweep(1.0);
  // The sweep exercises both branches of the clamp: friction inside +-F
  // (stick, as MuJoCo's soft creep) and saturated at +-F (slip).
  EXPECT_GT(s.travel_rad, 0.05);
  EXPECT_GT(s.stick_fraction, 0.1) << s.stick_fraction;
  EXPECT_LT(s.stick_fraction, 0.9) << s.stick_fraction;
  // Newton's solution of the one row is exact (the row's cost is quadratic
  // inside the clamp, linear outside): equal to round-off, bounded here at
  // 1e-9 of the travel.
  EXPECT_LT(s.max_dq_rad, 1e-9 * std::max(1.0, s.travel_rad) + 1e-10) << s.max_dq_rad;
  EXPECT_LT(s.max_dv_rad_s, 1e-6) << s.max_dv_rad_s;
  std::printf("travel %.3g rad, stick %.3g, max |dq| %.3g rad, max |dv| %.3g rad/s\n", s.travel_rad,
              s.stick_fraction, s.max_dq_rad, s.max_dv_rad_s);
}

TEST(RotorFriction, HardClampWouldDifferSoTheComparisonDiscriminates) {
  const Sweep soft = sweep(1.0);
  const Sweep hard = sweep(1.0, true);
  EXPECT_GT(hard.max_dq_rad, 1e3 * std::max(soft.max_dq_rad, 1e-12));
}

// MuJoCo's soft friction as a law of the rotor's motion: inside +-F the
// frictionloss row's force is -(a - aref) / R with a = alpha the rotor's
// acceleration and aref = -b omega, so f = -(omega + alpha / b) b / R: the
// friction of the speed the rotor will have 1 / b ahead (9.5 ms at MuJoCo's
// default time constant), saturated at F where |omega + alpha / b| >= F R / b.
// Checked on MuJoCo's own solver (the reference model, not the closed form)
// through the stick and slip of the sweep.
TEST(RotorFriction, MujocosSoftFrictionActsOnTheSpeedOneOverBAhead) {
  const ModelPtr m = load_model_from_xml(kRotorAndLink);
  const int dof = m->jnt_dofadr[require_id(m.get(), mjOBJ_JOINT, "joint_m")];
  const double I = 0.0026 + 1e-6;
  const double b = 2.0 / (0.95 * 0.02), R = (1.0 - 0.9) / 0.9 * m->dof_invweight0[dof];
  ASSERT_NEAR(m->dof_invweight0[dof], 1.0 / I, 1e-6 / I);  // the rotor's own tree: w0 = 1 / I
  const DataPtr d(mj_makeData(m.get()));
  int inside = 0, saturated = 0;
  double worst = 0.0;
  while (d->time < 1.0) {
    d->ctrl[0] = 1.5 * kFriction_Nm * std::sin(2.0 * std::numbers::pi * d->time / 0.5);
    const double omega = d->qvel[dof];
    mj_step(m.get(), d.get());
    const double f = d->qfrc_constraint[dof], lead = omega + d->qacc[dof] / b;
    if (std::abs(f) < (1.0 - 1e-9) * kFriction_Nm) {
      ++inside;
      worst = std::max(worst, std::abs(f + b * lead / R));
    } else {
      ++saturated;
      EXPECT_LT(f * lead, 0.0) << "t " << d->time;
      EXPECT_GE(b * std::abs(lead), (1.0 - 1e-6) * kFriction_Nm * R) << "t " << d->time;
    }
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(saturated, 100);
  EXPECT_LT(worst, 1e-9 * kFriction_Nm) << worst;
}

// A free rotor (armature I, frictionloss F, no damping) coasting from omega0,
// MuJoCo's row with solreffriction T (empty: its default, 0.02 s): the
// joint speed after t seconds.
double coasting_speed(const std::string& solref, double omega0, double t) {
  const std::string xml = R"(<mujoco>
  <option timestep="0.00025"><flag contact="disable"/></option>
  <worldbody><body name="rotor">
    <joint name="joint_m" type="hinge" axis="0 0 1" armature="0.0026" frictionloss="0.3" )" + solref + R"(/>
    <inertial pos="0 0 0" mass="0.5" diaginertia="1e-6 1e-6 1e-6"/>
  </body></worldbody>
</mujoco>)";
  const ModelPtr m = load_model_from_xml(xml);
  const DataPtr d(mj_makeData(m.get()));
  d->qvel[0] = omega0;
  while (d->time < t) mj_step(m.get(), d.get());
  return d->qvel[0];
}

// The drives' friction time constant (effects friction_timeconst_s,
// models/mjcf.cpp): at two physics steps a coasting rotor stops as hard
// Coulomb friction says, at t_c = I omega0 / F; at MuJoCo's default the
// friction is soft below F (b I omega / (1 + I R) with b = 2 / (dmax T), R =
// (1 - dmin) / dmin / I) and the rotor still turns at exp(-b t / (1 + I R)) of
// its speed then.
TEST(RotorFriction, TimeconstSetsHowACoastingRotorStops) {
  const double I = 0.0026 + 1e-6, F = kFriction_Nm, omega0 = 1.0;
  const double t_c = I * omega0 / F;  // 8.7 ms
  const double t = 1.2 * t_c;
  EXPECT_LT(std::abs(coasting_speed(R"(solreffriction="0.0005 1")", omega0, t)), 0.01 * omega0);
  const double b = 2.0 / (0.95 * 0.02), IR = (1.0 - 0.9) / 0.9;
  ASSERT_LT(b * I * omega0 / (1.0 + IR), F);  // the default's friction at omega0 is below F: soft from the start
  const double soft = coasting_speed("", omega0, t);
  EXPECT_NEAR(soft, omega0 * std::exp(-b * t / (1.0 + IR)), 0.05 * soft);
  EXPECT_GT(soft, 0.3 * omega0);
}

TEST(RotorFriction, RejectsADofThatIsNotARootTree) {
  const ModelPtr m = load_model_from_xml(kRotorAndLink);
  const int dof_b = m->jnt_dofadr[require_id(m.get(), mjOBJ_JOINT, "joint_b")];
  EXPECT_THROW(take_rotor_friction(m.get(), dof_b, -1), SimError);
  EXPECT_THROW(take_rotor_friction(m.get(), m->nv, -1), SimError);
  // The motor acts on joint_m, not on joint_a.
  const int dof_a = m->jnt_dofadr[require_id(m.get(), mjOBJ_JOINT, "joint_a")];
  EXPECT_THROW(take_rotor_friction(m.get(), dof_a, 0), SimError);
}

}  // namespace
}  // namespace gpm::sim
