// Tests of calib/excitation/candidates.hpp: the candidate grid is exactly the
// lattice points that pass check_reach with the guarded margins.
#include <gtest/gtest.h>

#include <cmath>

#include "calib/excitation/candidates.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {
namespace {

TEST(Candidates, GridIsTheReachableLatticeWithGuardedMargins) {
  const Robot robot;
  const Guard guard;
  const double step = 10.0;
  const auto grid = reachable_grid(robot, step, guard);
  ASSERT_GT(grid.size(), 100u);
  const Robot strict = guarded_robot(robot, guard);
  EXPECT_DOUBLE_EQ(strict.limits.reach_margin, robot.limits.reach_margin + guard.reach_mm);
  bool has_home = false;
  for (const auto& p : grid) {
    EXPECT_TRUE(check_reach(robot, p).ok) << p.transpose();
    EXPECT_TRUE(check_reach(strict, p).ok) << p.transpose();
    const Eigen::Vector2d k = (p - robot.home) / step;
    EXPECT_NEAR(k.x(), std::round(k.x()), 1e-9);
    EXPECT_NEAR(k.y(), std::round(k.y()), 1e-9);
    has_home |= (p - robot.home).norm() < 1e-12;
  }
  EXPECT_TRUE(has_home);
  // Every lattice point of a wide box that is not in the grid fails the check.
  long in_box_reachable = 0;
  for (int j = -60; j <= 60; ++j)
    for (int i = -60; i <= 60; ++i)
      in_box_reachable += check_reach(strict, robot.home + step * Eigen::Vector2d(i, j)).ok ? 1 : 0;
  EXPECT_EQ(in_box_reachable, static_cast<long>(grid.size()));
}

TEST(Candidates, BadStepIsAnInputError) {
  EXPECT_THROW(reachable_grid(Robot{}, 0.0, Guard{}), InputError);
  EXPECT_THROW(reachable_grid(Robot{}, -1.0, Guard{}), InputError);
  EXPECT_THROW(reachable_grid(Robot{}, NAN, Guard{}), InputError);
}

}  // namespace
}  // namespace gpm::calib::excitation
