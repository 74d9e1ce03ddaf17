// Tests of calib/synthetic.cpp: poses in the disc (or the base joints' box)
// and reachable, deterministic by seed, readings that close the loops (FK
// returns the pose), noise of the requested size.
#include "calib/synthetic.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

TEST(Synthetic, PosesReachableDeterministicAndReadingsClose) {
  Robot r;
  r.geometry = table5_actual();
  const auto a = disc_poses(r, 200, r.home, 80.0, 5), b = disc_poses(r, 200, r.home, 80.0, 5);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, disc_poses(r, 200, r.home, 80.0, 6));
  for (const auto& p : a) {
    EXPECT_LE((p - r.home).norm(), 80.0);
    EXPECT_TRUE(check_reach(r, p).ok);
  }
  const Samples s = samples_at(r, a);
  for (size_t j = 0; j < s.size(); ++j) {
    const auto f = forward_kinematics(r.geometry, active_from_readings(r.geometry, s.theta_m[j]));
    ASSERT_TRUE(f.has_value());
    EXPECT_LT((f->p - s.xy[j]).norm(), 1e-9);
  }
  const Samples n = samples_at(r, a, 1e-3, 9);
  double ss = 0.0;
  for (size_t j = 0; j < s.size(); ++j) ss += (n.theta_m[j] - s.theta_m[j]).squaredNorm();
  EXPECT_NEAR(std::sqrt(ss / (3.0 * static_cast<double>(s.size()))), 1e-3, 1e-4);
}

TEST(Synthetic, WorkspaceSamplesCloseTheLoopsInTheBaseBoxAndRepeat) {
  Robot r;
  r.geometry = table5_actual();
  const Samples s = workspace_samples(r, 50, 11);
  ASSERT_EQ(s.size(), 50u);
  ASSERT_TRUE(s.has_xy);
  for (size_t j = 0; j < s.size(); ++j) {
    const auto fk = forward_kinematics(r.geometry, active_from_readings(r.geometry, s.theta_m[j]));
    ASSERT_TRUE(fk);
    EXPECT_NEAR((fk->p - s.xy[j]).norm(), 0.0, 1e-9);
    EXPECT_TRUE(check_reach(r, s.xy[j]).ok);
    EXPECT_GE(s.xy[j].x(), 0.0);
    EXPECT_LE(s.xy[j].x(), 433.5);
    EXPECT_GE(s.xy[j].y(), 0.0);
    EXPECT_LE(s.xy[j].y(), 499.4);
  }
  EXPECT_EQ(workspace_samples(r, 50, 11).theta_m, s.theta_m);
  EXPECT_NE(workspace_samples(r, 50, 12).theta_m, s.theta_m);
  EXPECT_THROW(workspace_samples(r, 0, 1), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib
