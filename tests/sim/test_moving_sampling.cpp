// Tests of sim/moving_sampling.cpp: each sample on the fly is the drive loop
// instant of its tick in the servo-rate log (readings and torque), and its
// record of the torques applied before the instant (tau_last, tau_between)
// is, by the log's independent rows, the previous period's torque and the
// mean over the periods since the sample before.
#include "sim/moving_sampling.hpp"

#include <gtest/gtest.h>

namespace gpm::sim {
namespace {

TEST(MovingSampling, RecordsTheTorquesAppliedBetweenSamples) {
  const Robot actual;
  const TwinModel m(actual, TwinConfig{});
  TwinState s(m, 4);
  TrajectoryLog log;
  log.every = 1;
  Session session = make_session(m, s, actual, &log);
  const std::vector<Eigen::Vector2d> points = {session.desired, {236.5, 250.0}, {216.5, 275.0}};
  const WaypointPath path = make_waypoint_path(points, WaypointLimits{});
  const std::size_t first_row = log.rows.size();
  const int every = 3;
  const std::vector<SampleRecord> samples = sample_along(session, path, every, 10);
  ASSERT_GE(samples.size(), 20u);
  // One row per tick, a sample every `every` ticks from the first.
  const std::size_t rows = log.rows.size() - first_row;
  ASSERT_GE(rows, static_cast<std::size_t>(every) * (samples.size() - 1) + 1);
  ASSERT_LT(rows, static_cast<std::size_t>(every) * samples.size() + 1);
  double largest_change = 0.0;
  for (std::size_t j = 0; j < samples.size(); ++j) {
    const SampleRecord& r = samples[j];
    EXPECT_EQ(r.id, 10 + static_cast<long>(j));
    const std::size_t row = first_row + j * every;
    EXPECT_EQ(r.theta_m, log.rows[row].readings);
    EXPECT_EQ(r.tau, log.rows[row].torque);
    if (j == 0) {  // no period before the first: its own torque
      EXPECT_EQ(r.tau_last, r.tau);
      EXPECT_EQ(r.tau_between, r.tau);
      continue;
    }
    EXPECT_EQ(r.tau_last, log.rows[row - 1].torque);
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (int k = 1; k <= every; ++k) mean += log.rows[row - k].torque / every;
    EXPECT_LT((r.tau_between - mean).cwiseAbs().maxCoeff(), 1e-12 * (1.0 + mean.cwiseAbs().maxCoeff())) << "sample " << j;
    largest_change = std::max(largest_change, (r.tau_last - r.tau).cwiseAbs().maxCoeff());
  }
  EXPECT_GT(largest_change, 0.0) << "in motion the torque changes from one period to the next";
}

}  // namespace
}  // namespace gpm::sim
