// Tests of sim/sampling.cpp: every sample's true x,y is the analytic FK of
// the actual parameters at its true angles (eq. 32-33) within 1 um; ideal
// encoders give reading + actual offset = true angle; a calibrated controller
// reaches its targets; paths are tracked and logged at the servo rate.
#include "sim/sampling.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"

namespace gpm::sim {
namespace {

Robot perturbed_actual() {
  Robot r;
  const double d[kNumParams] = {0, 0, 0, 0, -0.3, 0.25, 0.2, -0.15, 0.5, -0.2, 0.3, 0.1, 0.012, -0.008, 0.005};
  for (int i = 0; i < kNumParams; ++i) r.geometry[i] += d[i];
  return r;
}

std::vector<Eigen::Vector2d> some_poses() {
  Rng rng(3);
  return disc_poses({216.5, 250.0}, 60.0, 8, rng);
}

TEST(Sampling, TrueXyIsTheActualForwardKinematicsOfTheTrueAngles) {
  const Robot actual = perturbed_actual();
  const Robot controller;  // nominal: servos fight, the end-effector misses
  const TwinModel m(actual, TwinConfig{});
  TwinState s(m, 9);
  Session session = make_session(m, s, controller, nullptr);
  const auto poses = some_poses();
  double worst_miss = 0.0;
  for (size_t k = 0; k < poses.size(); ++k) {
    const SampleRecord r = take_sample(session, poses[k], static_cast<long>(k), SamplingOptions{});
    EXPECT_TRUE(r.settled);
    const auto f = forward_kinematics(actual.geometry, r.theta_a);
    ASSERT_TRUE(f.has_value());
    EXPECT_LT((f->p - r.xy_mm).norm(), 1e-3) << "sample " << k;  // 1 um
    worst_miss = std::max(worst_miss, (r.xy_mm - r.target).norm());
  }
  EXPECT_GT(worst_miss, 0.5) << "a miscalibrated controller should miss its targets";
}

TEST(Sampling, IdealEncodersReadTrueAngleMinusActualOffsetAndCalibratedControllerHitsTargets) {
  const Robot actual = perturbed_actual();
  TwinConfig c;
  c.encoder.bits = 0;
  const TwinModel m(actual, c);
  TwinState s(m, 9);
  Session session = make_session(m, s, actual, nullptr);  // controller knows the truth
  const auto poses = some_poses();
  for (size_t k = 0; k < poses.size(); ++k) {
    const SampleRecord r = take_sample(session, poses[k], static_cast<long>(k), SamplingOptions{});
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(wrap_pi(r.theta_m[i] + actual.geometry.dth_(i) - r.theta_a[i])), 1e-12);
    }
    EXPECT_LT((r.xy_mm - poses[k]).norm(), 1e-3) << "sample " << k;
  }
}

TEST(Sampling, QuantisedSamplesStayWithinHalfACountOfTheTruth) {
  const Robot actual = perturbed_actual();
  const TwinModel m(actual, TwinConfig{});  // 17 bits, no noise
  TwinState s(m, 9);
  Session session = make_session(m, s, actual, nullptr);
  const double half = 0.5 * m.config().encoder.count_rad();
  for (const auto& p : some_poses()) {
    const SampleRecord r = take_sample(session, p, 0, SamplingOptions{});
    for (int i = 0; i < 3; ++i) {
      EXPECT_LE(std::abs(wrap_pi(r.theta_m[i] + actual.geometry.dth_(i) - r.theta_a[i])), half * 1.01);
    }
  }
}

TEST(Sampling, FollowsACircleAndLogsEveryServoPeriod) {
  const Robot actual;
  const TwinModel m(actual, TwinConfig{});
  TwinState s(m, 1);
  TrajectoryLog log;
  log.every = 1;
  Session session = make_session(m, s, actual, &log);
  const CirclePath c{{216.5, 250.0}, 30.0, 2.0, 1.0};
  follow_path(session, make_move(session.desired, path_at(c, 0).p, 100.0));
  const size_t before = log.rows.size();
  follow_path(session, c);
  const size_t rows = log.rows.size() - before;
  EXPECT_EQ(rows, 4001u);  // 2 s at 2 kHz, both ends
  double worst = 0.0;
  for (size_t k = before + 400; k < log.rows.size(); ++k) {  // after the start transient
    const LogRow& r = log.rows[k];
    worst = std::max(worst, (r.actual - r.desired).norm());
    EXPECT_NEAR(r.t - log.rows[k - 1].t, 0.0005, 1e-9);
  }
  // 94 mm/s with velocity feed-forward: a tracking error well below a millimetre.
  EXPECT_LT(worst, 0.5);
  EXPECT_GT(worst, 1e-4) << "a dynamic twin lags a little";
}

}  // namespace
}  // namespace gpm::sim
