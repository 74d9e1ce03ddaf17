// Table 5 data: the actual values and reachable, reproducible samples.
#include "calib/global/synthetic.hpp"

#include <gtest/gtest.h>

#include "models/errors.hpp"

#include "models/kinematics.hpp"

namespace gpm::calib::global {
namespace {

TEST(Synthetic, Table5ActualValues) {
  const Geometry g = table5_actual();
  EXPECT_EQ(g[kYa2], 0.3);
  EXPECT_EQ(g[kXa3], 433.5);
  EXPECT_EQ(g[kYa3], 499.4);
  EXPECT_EQ(g[kLa3], 243.5);
  EXPECT_EQ(g[kLb3], 244.6);
  EXPECT_EQ(g[kDth2], -0.01);
  EXPECT_EQ(g[kXa2], 433.0);
}

TEST(Synthetic, SamplesCloseTheLoopsOfTheActualMechanismAndRepeat) {
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
  }
  EXPECT_EQ(workspace_samples(r, 50, 11).theta_m, s.theta_m);
  EXPECT_NE(workspace_samples(r, 50, 12).theta_m, s.theta_m);
  EXPECT_THROW(workspace_samples(r, 0, 1), gpm::InputError);
}

TEST(Synthetic, ProblemFixesTheTrueValues) {
  Robot r;
  r.geometry = table5_actual();
  const Problem p = table5_problem(workspace_samples(r, 5, 1), default_free_mask());
  EXPECT_EQ(p.start[kYa2], 0.3);   // fixed: actual
  EXPECT_EQ(p.start[kLa1], 244.0); // free: nominal
  EXPECT_EQ(p.free.count(), 11u);
  EXPECT_EQ(paper_free_mask().count(), 12u);
  EXPECT_FALSE(paper_free_mask()[kXa2]);
}

}  // namespace
}  // namespace gpm::calib::global
