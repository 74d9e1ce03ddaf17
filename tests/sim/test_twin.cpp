// Tests of sim/twin.cpp: the compiled MJCF closes its loops at qpos0 for
// random actual parameters, the encoders follow eq. 35, and fighting servos
// hold the internal preload kp kv (I - J J+) dtheta predicted by statics;
// the model's constraint rows (njmax) hold every row it can have.
//
// Derivation of the preload. The active angles of the closed chain move on a
// 2-D manifold: near a pose, theta = theta0 + J dp with J = d theta_a / d(x, y),
// the 3x2 active Jacobian of eq. 11 (models active_jacobian). Passive joints
// carry no torque and the plane is horizontal, so at rest the drive torques
// tau do no work along the manifold: J^T tau = 0. Each drive at rest is a
// spring tau = K (theta_cmd - theta) with K = kp kv. With commands theta0 +
// dtheta: J^T K (dtheta - J dp) = 0, so dp = J+ dtheta (J+ = (J^T J)^-1 J^T)
// and tau = K (I - J J+) dtheta: the part of the command error that no
// end-effector motion can absorb, projected on the null space of J^T.
#include "sim/twin.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::sim {
namespace {

Robot perturbed(Rng& rng, double sigma_mm, double sigma_rad) {
  Robot r;
  for (int i = 0; i < kNumParams; ++i) r.geometry[i] += (is_offset(i) ? sigma_rad : sigma_mm) * rng.normal();
  return r;
}

// Steps the twin for a duration; returns the mean drive torque over the last `tail` seconds.
Eigen::Vector3d run_and_average_torque(const TwinModel& m, TwinState& s, double seconds, double tail) {
  const long n = std::lround(seconds / m.timestep_s());
  const long n_tail = std::lround(tail / m.timestep_s());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (long k = 0; k < n; ++k) {
    twin_step(m, s);
    if (k >= n - n_tail) sum += s.last.torque;
  }
  return sum / static_cast<double>(n_tail);
}

TEST(Twin, LoopsCloseRightAfterForwardForRandomActualParameters) {
  Rng rng(2024);
  for (int k = 0; k < 20; ++k) {
    const Robot actual = perturbed(rng, 1.0, 0.02);
    const TwinModel m(actual, TwinConfig{});
    const TwinState s(m, 1);  // mj_forward at qpos0
    EXPECT_LT(s.last.violation_m, 1e-9) << "set " << k;
    EXPECT_LT(constraint_violation_m(m, s.data.get()), 1e-9) << "set " << k;
    // ... and the end-effector is where the actual kinematics put it.
    EXPECT_LT((s.last.ee_mm - actual.home).norm(), 1e-9) << "set " << k;
    const JointAngles q = inverse_kinematics(actual.geometry, actual.home, actual.branch);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(wrap_pi(s.last.theta_a[i] - q.theta_a[i]), 0.0, 1e-12);
  }
}

TEST(Twin, IdealEncodersReadTrueAngleMinusActualOffset) {
  Rng rng(7);
  const Robot actual = perturbed(rng, 0.3, 0.05);
  TwinConfig c;
  c.encoder.bits = 0;
  const TwinModel m(actual, c);
  TwinState s(m, 1);
  twin_command(s, s.last.readings + Eigen::Vector3d(0.02, -0.01, 0.005), Eigen::Vector3d::Zero());
  for (int k = 0; k < 400; ++k) {
    twin_step(m, s);
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(wrap_pi(s.last.readings[i] + actual.geometry.dth_(i) - s.last.theta_a[i])), 1e-12);
    }
  }
}

TEST(Twin, ConsistentCommandsHoldStillWithoutTorque) {
  TwinConfig c;
  c.encoder.bits = 0;
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  const Eigen::Vector2d p0 = s.last.ee_mm;
  const Eigen::Vector3d tau = run_and_average_torque(m, s, 0.2, 0.1);
  EXPECT_LT(tau.cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((s.last.ee_mm - p0).norm(), 1e-9);
}

TEST(Twin, OneCommandOffHoldsThePredictedInternalPreload) {
  Rng rng(11);
  for (const Robot& actual : {Robot{}, perturbed(rng, 0.5, 0.01)}) {
    for (int j = 0; j < 3; ++j) {
      const TwinModel m(actual, TwinConfig{});  // 17-bit encoders
      TwinState s(m, 1);
      const JointAngles q = inverse_kinematics(actual.geometry, actual.home, actual.branch);
      const Matrix32d J = active_jacobian(actual.geometry, q);
      const Eigen::Matrix3d P =
          Eigen::Matrix3d::Identity() - J * (J.transpose() * J).inverse() * J.transpose();
      Eigen::Vector3d dtheta = Eigen::Vector3d::Zero();
      dtheta[j] = 0.01;
      Eigen::Vector3d cmd;
      for (int i = 0; i < 3; ++i) cmd[i] = wrap_2pi(q.theta_a[i] - actual.geometry.dth_(i) + dtheta[i]);
      twin_command(s, cmd, Eigen::Vector3d::Zero());
      const Eigen::Vector3d tau = run_and_average_torque(m, s, 1.0, 0.2);
      const Eigen::Vector3d want = m.config().drives[0].stiffness() * P * dtheta;
      ASSERT_GT(want.norm(), 1.0) << "the preload should be substantial";
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(tau[i], want[i], 0.05 * std::abs(want[i])) << "joint " << i << " off " << j;
      }
      // The stiff constraints keep the loops closed under the preload.
      EXPECT_LT(s.last.violation_m, 1e-7);
      EXPECT_LT(s.last.velocity.norm(), 1e-2);
    }
  }
}

TEST(Twin, TorqueOffJointIsOnlyASensor) {
  TwinConfig c;
  c.drives[2].mode = ServoMode::kTorqueOff;
  const TwinModel m(Robot{}, c);
  TwinState s(m, 1);
  twin_command(s, s.last.readings + Eigen::Vector3d(0.01, 0.0, 0.3), Eigen::Vector3d::Zero());
  const Eigen::Vector3d tau = run_and_average_torque(m, s, 0.5, 0.1);
  EXPECT_EQ(tau[2], 0.0);
  // Two drives and two degrees of freedom: nothing to fight, the torques vanish.
  EXPECT_LT(tau.head<2>().cwiseAbs().maxCoeff(), 0.1);
  EXPECT_LT(std::abs(wrap_pi(s.last.readings[0] - s.command_position[0])), 1e-3);
}

// Every row the solver can be given (3 per connect, 1 per tendon equality,
// up to 2 per limited joint or tendon, 1 per frictionloss dof or tendon)
// fits in the model's njmax with the effects off, realistic and with hub pin
// offsets, and a run with them never fills it.
TEST(Twin, ConstraintRowsFitTheModelsRoom) {
  std::vector<Effects> cases = {Effects{}, realistic_effects()};
  cases.push_back(realistic_effects());
  cases.back().mjcf.hub_pin_m = {{{0.0, 0.0}, {0.01, 0.0}, {0.0, 0.01}}};
  for (const Effects& fx : cases) {
    TwinConfig c;
    c.mjcf.timestep_s = 0.00025;
    c.servo_rate_hz = 4000.0;
    c.effects = fx;
    const TwinModel model(Robot{}, c);
    const mjModel* m = model.mj();
    int rows = 0;
    for (int e = 0; e < m->neq; ++e) rows += m->eq_type[e] == mjEQ_CONNECT ? 3 : m->eq_type[e] == mjEQ_WELD ? 6 : 1;
    for (int j = 0; j < m->njnt; ++j) rows += m->jnt_limited[j] ? 2 : 0;
    for (int t = 0; t < m->ntendon; ++t) rows += (m->tendon_limited[t] ? 2 : 0) + (m->tendon_frictionloss[t] > 0.0);
    for (int v = 0; v < m->nv; ++v) rows += m->dof_frictionloss[v] > 0.0;
    EXPECT_LE(rows, m->njmax / 3);
    TwinState state(model, 1);
    twin_command(state, state.last.readings + Eigen::Vector3d(0.01, -0.01, 0.005), Eigen::Vector3d::Zero());
    for (int k = 0; k < 2000; ++k) ASSERT_NO_THROW(twin_step(model, state));  // no row dropped (sim/twin.cpp)
    EXPECT_EQ(state.data->warning[mjWARN_CNSTRFULL].number, 0);
  }
}

TEST(Twin, ServoRateMustBeAWholeNumberOfSteps) {
  TwinConfig c;
  c.servo_rate_hz = 1500.0;  // 2000 Hz physics
  EXPECT_THROW(TwinModel(Robot{}, c), InputError);
  c.servo_rate_hz = 1000.0;
  const TwinModel m(Robot{}, c);
  EXPECT_EQ(m.steps_per_tick(), 2);
}

TEST(Twin, RefusesActualParametersThatCannotAssemble) {
  Robot r;
  r.geometry[kLb2] = 20.0;
  EXPECT_THROW(TwinModel(r, TwinConfig{}), InputError);
}

}  // namespace
}  // namespace gpm::sim
