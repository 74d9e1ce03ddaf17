// Tests of models/drive_margin.cpp: the measures of the drives in position
// mode (the five-bar of chains 2 and 3 when joint 1 is torque-off), their
// widening by the model's tolerance, and the sentence of a violation.
#include <cmath>

#include <Eigen/LU>
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

// An encoder offset error e on driven joint k turns that joint by e from
// where the controller thinks it is: to first order the hub moves by
// J^-1 e e_k, with J the driven rows of the active Jacobian (eq. 11). So for
// offsets alone the deviation's stack-up is t ||J^-1||_F; the torque-off
// chain's offset does not move the five-bar's hub.
TEST(DriveMargin, OffsetDeviationIsTheInverseJacobianOfTheDrivenChains) {
  const Robot robot;
  const double t = 1e-5;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(216.5, 250.0), Eigen::Vector2d(300.0, 180.0),
                                  Eigen::Vector2d(380.0, 300.0)}) {
    const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
    const Matrix32d J = active_jacobian(robot.geometry, q);
    const Eigen::Matrix2d J23 = J.bottomRows<2>();
    const double expected = t * J23.inverse().norm();  // Frobenius
    const DriveMargins m = drive_margins(robot, p, kFiveBar, ModelTolerance{0.0, 0.0, t});
    EXPECT_NEAR(m.deviation_mm, expected, 1e-4 * expected) << p.transpose();
    EXPECT_EQ(drive_margins(robot, p, kFiveBar).deviation_mm, 0.0);  // the controller's own model
  }
}

// Near the five-bar's type-2 pose a small model error carries the hub far:
// the deviation grows there, and a margin on it names the deviation.
TEST(DriveMargin, DeviationGrowsNearTheFiveBarSingularityAndIsNamed) {
  const Robot robot;
  const ModelTolerance tol{};
  const double home = drive_margins(robot, robot.home, kFiveBar, tol).deviation_mm;
  EXPECT_GT(home, 0.0);
  double worst = 0.0;
  Eigen::Vector2d at = robot.home;
  for (double x = 60.0; x <= 420.0; x += 10.0)
    for (double y = 60.0; y <= 440.0; y += 10.0) {
      const Eigen::Vector2d p(x, y);
      if (!check_reach(robot, p).ok) continue;
      const DriveMargins m = drive_margins(robot, p, kFiveBar, tol);
      if (m.ok && m.direct > 0.0 && m.direct < 0.2 && m.deviation_mm > worst) worst = m.deviation_mm, at = p;
    }
  EXPECT_GT(worst, 2.0 * home);
  PathMargin margin;
  margin.singularity = 0.0;
  margin.deviation_mm = 0.5 * (home + worst);
  EXPECT_EQ(margin_violation(robot, robot.home, kFiveBar, margin), "");
  const std::string why = margin_violation(robot, at, kFiveBar, margin);
  EXPECT_NE(why.find("mm from the plan (RSS over the parameters), beyond the margin"), std::string::npos) << why;
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
