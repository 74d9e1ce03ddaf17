// Tests of calib/kmrmse.cpp (eq. 40): zero for the true geometry, the
// hand-computable value for a pure offset of all true points, NaN for
// mismatched sizes.
#include "calib/kmrmse.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::calib {
namespace {

TEST(Kmrmse, ZeroAtTruthAndKnownForShiftedPoints) {
  Robot r;
  r.geometry = table5_actual();
  const Samples s = samples_at(r, disc_poses(r, 20, r.home, 80.0, 2));
  EXPECT_LT(kmrmse(r.geometry, s.theta_m, s.xy), 1e-9);
  std::vector<Eigen::Vector2d> shifted = s.xy;
  for (auto& p : shifted) p += Eigen::Vector2d(0.3, 0.4);  // every point 0.5 mm away
  EXPECT_NEAR(kmrmse(r.geometry, s.theta_m, shifted), 0.5, 1e-9);
  // Translating the whole mechanism by (0.3, 0.4) moves every FK point alike.
  Geometry g = r.geometry;
  for (int i = 0; i < 3; ++i) g[xa(i)] += 0.3, g[ya(i)] += 0.4;
  EXPECT_NEAR(kmrmse(g, s.theta_m, s.xy), 0.5, 1e-9);
  EXPECT_TRUE(std::isnan(kmrmse(g, s.theta_m, {})));
}

}  // namespace
}  // namespace gpm::calib
