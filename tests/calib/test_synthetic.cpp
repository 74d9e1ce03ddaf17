// Tests of calib/synthetic.cpp: poses in the disc and reachable, deterministic
// by seed, readings that close the loops (FK returns the pose), noise of the
// requested size.
#include "calib/synthetic.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
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

}  // namespace
}  // namespace gpm::calib
