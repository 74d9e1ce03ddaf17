// Tests of calib/excitation/layouts.hpp: the comparison of the paper's line,
// circle, discs and the optimised set at equal poses and noise (issue 10).
#include <gtest/gtest.h>

#include <fmt/format.h>

#include "calib/excitation/layouts.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib::excitation {
namespace {

TEST(Layouts, LineAndCircleHaveTheirShape) {
  const auto line = line_layout({0, 0}, {10, 20}, 5);
  ASSERT_EQ(line.size(), 5u);
  EXPECT_DOUBLE_EQ(line[2].x(), 5.0);
  EXPECT_DOUBLE_EQ(line[4].y(), 20.0);
  const auto circle = circle_layout({216.5, 250}, 80, 50);
  ASSERT_EQ(circle.size(), 50u);
  for (const auto& p : circle) EXPECT_NEAR((p - Eigen::Vector2d(216.5, 250)).norm(), 80.0, 1e-9);
  EXPECT_NEAR(circle[0].x(), 296.5, 1e-12);
}

TEST(Layouts, OptimisedIsAtLeastThreeTimesBetterOnTheWorstBound) {
  ComparisonOptions o;
  const Robot nominal;
  const auto rows = compare_layouts(nominal, o);
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& r : rows) {
    ASSERT_EQ(r.poses.size(), 50u) << r.name;
    fmt::print("{:10} worst {:10.4g} mm ({})  mean {:10.4g} mm  logdet {:.2f}\n", r.name, r.bounds.worst_mm,
               r.bounds.worst_param >= 0 ? param_name(r.bounds.worst_param) : "-", r.bounds.mean_mm,
               r.bounds.log_det);
  }
  // Independent facts (docs/EQUATIONS.md, issue 10): a line is practically unidentifiable,
  // a wide disc beats a circle of radius 80 by orders of magnitude.
  EXPECT_GT(rows[0].bounds.worst_mm, 100.0 * rows[1].bounds.worst_mm);
  EXPECT_LT(rows[3].bounds.worst_mm, rows[1].bounds.worst_mm / 10.0);
  const double ratio = improvement_over_best_other(rows);
  fmt::print("improvement over the best other layout: {:.2f}x\n", ratio);
  EXPECT_GE(ratio, 3.0);
}

}  // namespace
}  // namespace gpm::calib::excitation
