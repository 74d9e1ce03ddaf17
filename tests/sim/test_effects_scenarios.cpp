// Tests of the effects scenarios scenarios/effects_*.yaml through sim/simulate.cpp:
// each effect leaves its physical signature in the samples of its scenario, so
// these fail if the effect were silently dropped (the runner's expectation keys
// are upper bounds only and cannot see that):
// - compliance: |theta_a - (theta_m + dth)| = compliance x |tau| per sample;
// - clearance: the true link angles leave the rigid closure (IK at the true
//   end-effector) by about clearance / link length, never much more;
// - thermal: trajectory.csv carries the actual parameters at t, lengths
//   L0 (1 + alpha rise (1 - exp(-t / tau)));
// - encoder: at rest the reading error is A sin(reading + phase) per encoder;
// - friction: the drives spend extra power c sum|w| + b sum w^2 while moving.
#include "sim/simulate.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/kinematics.hpp"

namespace gpm::sim {
namespace {

Scenario load(const char* stem) {
  Scenario s = load_scenario(gpm::scenarios_dir() + "/effects_" + stem + ".yaml");
  if (s.sampling) s.sampling->count = std::min(s.sampling->count, 12);  // enough for a signature
  return s;
}

TEST(EffectsScenarios, ComplianceTwistIsComplianceTimesTorquePerSample) {
  const Scenario s = load("compliance");
  const double c = s.twin.effects.mjcf.compliance_rad_per_Nm[0];
  ASSERT_GT(c, 0.0);
  const SimulationResult r = run_simulation(s);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (const SampleRecord& smp : r.samples) {
    for (int i = 0; i < 3; ++i) {
      if (std::abs(smp.tau[i]) < 1.0) continue;
      const double twist = std::abs(wrap_pi(smp.theta_a[i] - smp.theta_m[i] - r.actual.geometry.dth_(i)));
      const double ratio = twist / (c * std::abs(smp.tau[i]));
      sum += ratio, sum2 += ratio * ratio, ++n;
    }
  }
  ASSERT_GE(n, 10) << "the drives should fight with a preload of several N m";
  const double mean = sum / n, spread = std::sqrt(std::max(0.0, sum2 / n - mean * mean));
  std::printf("compliance: |theta_a - (theta_m + dth)| / (c |tau|) over %d joint samples: mean %.5f, spread %.2e\n",
              n, mean, spread);
  EXPECT_NEAR(mean, 1.0, 0.01);
  EXPECT_LT(spread, 0.01);
}

TEST(EffectsScenarios, ClearanceMovesTheLinksOffTheRigidClosure) {
  const Scenario s = load("clearance");
  const double c_mm = s.twin.effects.mjcf.clearance_m[0] * 1e3;
  ASSERT_GT(c_mm, 0.0);
  const SimulationResult r = run_simulation(s);
  double worst = 0.0;
  for (const SampleRecord& smp : r.samples) {
    const JointAngles q = inverse_kinematics(r.actual.geometry, smp.xy_mm, r.actual.branch);
    for (int i = 0; i < 3; ++i)
      worst = std::max(worst, std::abs(wrap_pi(smp.theta_a[i] - q.theta_a[i])) * r.actual.geometry.la_(i));
  }
  std::printf("clearance %.4f mm: largest departure from the rigid closure %.4f mm at the link tip\n", c_mm, worst);
  EXPECT_GT(worst, 0.5 * c_mm);
  EXPECT_LT(worst, 20.0 * c_mm);  // two loose joints per chain, amplified by the transmission angle
}

TEST(EffectsScenarios, ThermalTrajectoryLogsTheGrowingParameters) {
  const Scenario s = load("thermal");
  const ThermalEffect th = s.twin.effects.thermal;
  ASSERT_TRUE(th.on());
  const SimulationResult r = run_simulation(s);
  ASSERT_TRUE(r.log.thermal_reference.has_value());
  const std::string csv = trajectory_csv(r.log);
  EXPECT_NE(csv.substr(0, csv.find('\n')).find(",growth,xa1,ya1"), std::string::npos);
  const LogRow& last = r.log.rows.back();
  const double t = last.t;  // the geometry set at the start of the logged step
  EXPECT_NEAR(last.growth, th.expansion_per_K * th.rise_K * (1.0 - std::exp(-t / th.time_constant_s)), 1e-12);
  const Geometry g = thermal_geometry(r.actual.geometry, last.growth);
  EXPECT_GT(g.la_(0) - r.actual.geometry.la_(0), 0.5 * 244.0 * th.expansion_per_K * th.rise_K *
                                                      (1.0 - std::exp(-t / th.time_constant_s)));
  EXPECT_LT(r.max_violation_m, 2e-6) << "the loops stay closed while the links grow";
}

TEST(EffectsScenarios, EncoderCyclicErrorAtRest) {
  Scenario s = load("encoder");
  const Effects fx = s.twin.effects;
  ASSERT_GT(fx.encoder_cyclic_rad[0], 0.0);
  const SimulationResult r = run_simulation(s);
  for (const SampleRecord& smp : r.samples) {
    for (int i = 0; i < 3; ++i) {
      const double x = smp.theta_a[i] - r.actual.geometry.dth_(i);
      const double want = fx.encoder_cyclic_rad[i] * std::sin(x + fx.encoder_phase_rad[i]);
      EXPECT_NEAR(wrap_pi(smp.theta_m[i] - x), want, 0.02 * fx.encoder_cyclic_rad[i]) << "encoder " << i + 1;
    }
  }
}

TEST(EffectsScenarios, FrictionCostsDrivePower) {
  Scenario s = load("friction");
  s.sampling->count = 4;
  s.log_every = 1;
  const MjcfEffects fx = s.twin.effects.mjcf;
  ASSERT_GT(fx.coulomb_Nm[0], 0.0);
  // Mean drive power and the power friction should take, from the log
  // (velocities by central differences of the readings).
  const auto power = [](const SimulationResult& r, double c, double b, double& expected) {
    double p = 0.0;
    expected = 0.0;
    const auto& rows = r.log.rows;
    for (size_t k = 1; k + 1 < rows.size(); ++k) {
      const double dt = rows[k + 1].t - rows[k - 1].t;
      for (int i = 0; i < 3; ++i) {
        const double w = wrap_pi(rows[k + 1].readings[i] - rows[k - 1].readings[i]) / dt;
        p += rows[k].torque[i] * w;
        expected += c * std::abs(w) + b * w * w;
      }
    }
    expected /= static_cast<double>(rows.size());
    return p / static_cast<double>(rows.size());
  };
  double expected = 0.0, unused = 0.0;
  const double with = power(run_simulation(s), fx.coulomb_Nm[0], fx.viscous_Nm_s[0], expected);
  s.twin.effects = Effects{};
  const double without = power(run_simulation(s), 0.0, 0.0, unused);
  std::printf("friction: extra drive power %.4f W, expected %.4f W\n", with - without, expected);
  EXPECT_NEAR((with - without) / expected, 1.0, 0.15);
}

}  // namespace
}  // namespace gpm::sim
