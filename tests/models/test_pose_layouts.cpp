// Tests of models/pose_layouts.cpp: hand-worked points of a circle and a line.
#include "models/pose_layouts.hpp"

#include <gtest/gtest.h>

namespace gpm {
namespace {

TEST(PoseLayouts, CircleStartsOnPlusXAndTurnsCounterClockwise) {
  const auto c = circle_points({1, 2}, 10.0, 4);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_LT((c[0] - Eigen::Vector2d(11, 2)).norm(), 1e-12);
  EXPECT_LT((c[1] - Eigen::Vector2d(1, 12)).norm(), 1e-12);
  EXPECT_LT((c[2] - Eigen::Vector2d(-9, 2)).norm(), 1e-12);
  for (const auto& p : circle_points({216.5, 250}, 80, 50)) EXPECT_NEAR((p - Eigen::Vector2d(216.5, 250)).norm(), 80, 1e-12);
}

TEST(PoseLayouts, LineIncludesBothEnds) {
  const auto l = line_points({0, 0}, {10, 20}, 3);
  ASSERT_EQ(l.size(), 3u);
  EXPECT_LT((l[1] - Eigen::Vector2d(5, 10)).norm(), 1e-12);
  EXPECT_LT((l[2] - Eigen::Vector2d(10, 20)).norm(), 1e-12);
  EXPECT_EQ(line_points({3, 4}, {5, 6}, 1).front(), Eigen::Vector2d(3, 4));
}

}  // namespace
}  // namespace gpm
