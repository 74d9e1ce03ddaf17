// Tests of models/drive_margin.cpp: the measures of the drives in position
// mode (the five-bar of chains 2 and 3 when joint 1 is torque-off), their
// widening by the model's tolerance, and the sentence of a violation.
#include <cmath>

#include <gtest/gtest.h>

#include "models/drive_margin.hpp"
#include "models/kinematics.hpp"

namespace gpm {
namespace {

constexpr DriveMask kAll{true, true, true};
constexpr DriveMask kFiveBar{false, true, true};  // joint 1 torque-off

TEST(DriveMargin, MeasuresAreTheConditioningOfTheDrivenChains) {
  const Robot robot;
  const Eigen::Vector2d p(250.0, 230.0);
  const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
  const Conditioning c = conditioning(robot.geometry, q);
  const DriveMargins all = drive_margins(robot, p, kAll);
  ASSERT_TRUE(all.ok);
  EXPECT_DOUBLE_EQ(all.transmission, c.min_transmission);
  EXPECT_DOUBLE_EQ(all.direct, c.direct);
  const DriveMargins five = drive_margins(robot, p, kFiveBar);
  EXPECT_DOUBLE_EQ(five.transmission, c.min_transmission);  // the free chain's own type 1 counts too
  EXPECT_NEAR(five.direct, std::sqrt(1.0 - std::abs(std::cos(q.theta_b[1] - q.theta_b[2]))), 1e-15);
  // The workspace border: the smallest distance from an annulus edge.
  double edge = INFINITY;
  for (int i = 0; i < 3; ++i) {
    const double d = (p - robot.geometry.A(i)).norm();
    edge = std::min({edge, 488.0 - d, d});
  }
  EXPECT_NEAR(five.reach_mm, edge, 1e-9);
  EXPECT_FALSE(drive_margins(robot, Eigen::Vector2d(900.0, 0.0), kAll).ok);
}

// Where passive links 2 and 3 are parallel the five-bar loses control while
// the three-chain spread (gpm::Conditioning::direct) stays comfortable: the
// margin of the drives in position mode names it.
TEST(DriveMargin, FindsTheFiveBarSingularityThatTheThreeChainMeasureMisses) {
  const Robot robot;
  bool found = false;
  for (double x = 60.0; x <= 420.0 && !found; x += 5.0)
    for (double y = 60.0; y <= 440.0 && !found; y += 5.0) {
      const Eigen::Vector2d p(x, y);
      if (!check_reach(robot, p).ok) continue;
      const DriveMargins five = drive_margins(robot, p, kFiveBar);
      const DriveMargins all = drive_margins(robot, p, kAll);
      if (five.direct < 0.05 && all.direct > 0.3 && five.transmission > 0.3) {
        found = true;
        const std::string why = margin_violation(robot, p, kFiveBar, PathMargin{});
        EXPECT_NE(why.find("type-2 singularity of the five-bar of chains 2 and 3"), std::string::npos) << why;
        EXPECT_EQ(why.find('\n'), std::string::npos);
      }
    }
  EXPECT_TRUE(found);
}

TEST(DriveMargin, ToleranceWidensEveryMeasureAndZeroToleranceChangesNothing) {
  const Robot robot;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(216.5, 250.0), Eigen::Vector2d(300.0, 180.0),
                                  Eigen::Vector2d(150.0, 320.0)}) {
    for (const DriveMask& drives : {kAll, kFiveBar}) {
      const DriveMargins nominal = drive_margins(robot, p, drives);
      const DriveMargins none = drive_margins(robot, p, drives, ModelTolerance{0.0, 0.0, 0.0});
      EXPECT_DOUBLE_EQ(none.transmission, nominal.transmission);
      EXPECT_DOUBLE_EQ(none.direct, nominal.direct);
      EXPECT_DOUBLE_EQ(none.reach_mm, nominal.reach_mm);
      const DriveMargins wide = drive_margins(robot, p, drives, ModelTolerance{});
      ASSERT_TRUE(wide.ok);
      EXPECT_LT(wide.transmission, nominal.transmission);
      EXPECT_LT(wide.direct, nominal.direct);
      EXPECT_LT(wide.reach_mm, nominal.reach_mm);
      // An offset error moves the driven mechanism (inverse kinematics alone does not see it).
      const DriveMargins offsets = drive_margins(robot, p, drives, ModelTolerance{0.0, 0.0, 0.02});
      EXPECT_LT(offsets.direct, nominal.direct);
    }
  }
}

TEST(DriveMargin, ViolationNamesTheMeasureAndIsEmptyWhereTheMarginHolds) {
  const Robot robot;
  EXPECT_EQ(margin_violation(robot, robot.home, kFiveBar, PathMargin{}), "");
  PathMargin strict;
  strict.reach_mm = 300.0;
  const std::string why = margin_violation(robot, robot.home, kFiveBar, strict);
  EXPECT_NE(why.find("from the reach of chain"), std::string::npos) << why;
  EXPECT_NE(margin_violation(robot, Eigen::Vector2d(900.0, 0.0), kAll, PathMargin{}).find("is out of reach"),
            std::string::npos);
}

}  // namespace
}  // namespace gpm
