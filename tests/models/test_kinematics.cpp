// Tests of models/kinematics.cpp: IK/FK round trips, cross checks of the
// three-chain and two-chain forward kinematics, the eq. 11 Jacobian against
// central differences, singularity measures, hand-worked home angles, and
// the inverse kinematics that returns nothing out of reach against the one that throws.
#include "models/kinematics.hpp"
#include "models/rng.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

namespace gpm {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

Robot nominal() { return Robot{}; }

// Dense grid of reachable targets (with the robot's margins).
std::vector<Vector2d> reachable_grid(const Robot& robot, double step) {
  std::vector<Vector2d> out;
  for (double x = -100; x <= 550; x += step)
    for (double y = -100; y <= 600; y += step)
      if (check_reach(robot, {x, y}).ok) out.emplace_back(x, y);
  return out;
}

TEST(Kinematics, HomeAnglesMatchHandWorkedValues) {
  // Chain 1 by hand: A1=(0,250), O=(216.5,250): phi = 0, d = 216.5,
  // alpha = acos(d / (2*244)) since la = lb.
  const Robot r = nominal();
  const JointAngles q = inverse_kinematics(r.geometry, r.home, r.branch);
  EXPECT_NEAR(q.theta_a[0], std::acos(216.5 / 488.0), 1e-15);
  EXPECT_NEAR(q.theta_a[0], 1.1111, 1e-4);
  EXPECT_NEAR(q.theta_a[1], 3.1107, 1e-4);
  EXPECT_NEAR(q.theta_a[2], 4.8249, 1e-4);
  // Passive angle of chain 1 mirrors the active one about the x axis.
  EXPECT_NEAR(q.theta_b[0], -q.theta_a[0], 1e-12);
}

TEST(Kinematics, IkThenFkReturnsTargetOnDenseGrid) {
  Robot r = nominal();
  r.geometry[kLa3] = 244.5;  // an asymmetric mechanism, too
  r.geometry[kXa3] = 433.05;
  for (const Robot& robot : {nominal(), r}) {
    const auto grid = reachable_grid(robot, 5.0);
    ASSERT_GT(grid.size(), 1000u);
    double worst = 0.0;
    for (const Vector2d& p : grid) {
      const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
      const auto f = forward_kinematics(robot.geometry, q.theta_a);
      ASSERT_TRUE(f.has_value());
      worst = std::max(worst, (f->p - p).norm());
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(wrap_pi(f->theta_b[i] - q.theta_b[i]), 0.0, 1e-9);
    }
    EXPECT_LT(worst, 1e-9) << "worst IK->FK error (mm)";
  }
}

TEST(Kinematics, TwoChainFkAgreesWithThreeChainFk) {
  const Robot r = nominal();
  const auto grid = reachable_grid(r, 10.0);
  const JointAngles q0 = inverse_kinematics(r.geometry, r.home, r.branch);
  for (const Vector2d& p : grid) {
    const JointAngles q = inverse_kinematics(r.geometry, p, r.branch);
    const auto f3 = forward_kinematics(r.geometry, q.theta_a);
    ASSERT_TRUE(f3);
    for (auto [i, j] : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
      const int mode = assembly_mode(r.geometry, q.theta_a, p, i, j);
      const auto f2 = forward_kinematics_two(r.geometry, q.theta_a, i, j, mode);
      ASSERT_TRUE(f2);
      EXPECT_LT((*f2 - f3->p).norm(), 1e-8) << "chains " << i << "," << j << " at " << p.transpose();
    }
  }
  // The other assembly mode is a genuinely different point.
  const auto other = forward_kinematics_two(r.geometry, q0.theta_a, 0, 1,
                                            -assembly_mode(r.geometry, q0.theta_a, r.home, 0, 1));
  ASSERT_TRUE(other);
  EXPECT_GT((*other - r.home).norm(), 1.0);
}

TEST(Kinematics, JacobianMatchesCentralDifferences) {
  const Robot r = nominal();
  const double h = 1e-4;
  for (const Vector2d& p : reachable_grid(r, 25.0)) {
    const JointAngles q = inverse_kinematics(r.geometry, p, r.branch);
    const Matrix32d J = active_jacobian(r.geometry, q);
    for (int k = 0; k < 2; ++k) {
      Vector2d e = Vector2d::Zero();
      e[k] = h;
      const Vector3d plus = inverse_kinematics(r.geometry, p + e, r.branch).theta_a;
      const Vector3d minus = inverse_kinematics(r.geometry, p - e, r.branch).theta_a;
      for (int i = 0; i < 3; ++i) {
        const double fd = wrap_pi(plus[i] - minus[i]) / (2 * h);
        EXPECT_NEAR(J(i, k), fd, 1e-7 * std::max(1.0, std::abs(fd) * 1e3)) << p.transpose();
      }
    }
  }
}

TEST(Kinematics, OutOfReachNamesChainAndShortfall) {
  const Robot r = nominal();
  try {
    inverse_kinematics(r.geometry, {216.5, 750.0}, r.branch);
    FAIL() << "expected ReachError";
  } catch (const ReachError& e) {
    // Chain 1 (A1 at (0,250)) is the first that fails: distance 544.9 > 488.
    EXPECT_EQ(e.chain, 0);
    EXPECT_NEAR(e.shortfall_mm, std::hypot(216.5, 500.0) - 488.0, 1e-9);
    EXPECT_NE(std::string(e.what()).find("chain 1"), std::string::npos);
  }
}

// try_inverse_kinematics: inverse_kinematics's angles where every chain
// reaches, nullopt (no throw) where one does not.
TEST(Kinematics, TryInverseKinematicsIsInverseKinematicsOrNothing) {
  const Robot r = nominal();
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(216.5, 250.0), Eigen::Vector2d(260.0, 210.0)}) {
    const JointAngles want = inverse_kinematics(r.geometry, p, r.branch);
    const std::optional<JointAngles> got = try_inverse_kinematics(r.geometry, p, r.branch);
    ASSERT_TRUE(got);
    EXPECT_EQ(got->theta_a, want.theta_a);
    EXPECT_EQ(got->theta_b, want.theta_b);
  }
  EXPECT_FALSE(try_inverse_kinematics(r.geometry, {216.5, 750.0}, r.branch));
}

TEST(Kinematics, BranchesGiveMirroredElbows) {
  const Robot r = nominal();
  const Vector2d p(230.0, 260.0);
  for (int i = 0; i < 3; ++i) {
    const auto ccw = chain_ik(r.geometry, i, p, +1);
    const auto cw = chain_ik(r.geometry, i, p, -1);
    const Vector2d A_p = p - r.geometry.A(i);
    const double phi = std::atan2(A_p.y(), A_p.x());
    EXPECT_NEAR(wrap_pi(ccw.theta_a - phi), -wrap_pi(cw.theta_a - phi), 1e-12);
    EXPECT_GT(wrap_pi(ccw.theta_a - phi), 0.0);
  }
}

TEST(Kinematics, SingularityMeasures) {
  const Robot r = nominal();
  const JointAngles q = inverse_kinematics(r.geometry, r.home, r.branch);
  const Conditioning c = conditioning(r.geometry, q);
  EXPECT_GT(c.min_transmission, 0.5);
  EXPECT_GT(c.direct, 0.5);
  EXPECT_LE(c.direct, 1.0 + 1e-12);
  EXPECT_GE(c.jacobian_condition, 1.0);
  // Type 1: a target at full stretch of chain 1 (active and passive aligned).
  const Vector2d stretched = r.geometry.A(0) + Vector2d(488.0 - 1e-9, 0.0) ;
  const auto q1 = chain_ik(r.geometry, 0, stretched, +1);
  EXPECT_LT(std::abs(std::sin(q1.theta_a - q1.theta_b)), 1e-3);
  // Type 2: three parallel passive links give zero spread.
  JointAngles par;
  par.theta_a = Vector3d(1.0, 2.0, 3.0);
  par.theta_b = Vector3d(0.3, 0.3, 0.3 + std::numbers::pi);
  EXPECT_NEAR(conditioning(r.geometry, par).direct, 0.0, 1e-12);
  // Directions 120 degrees apart give spread 1.
  par.theta_b = Vector3d(0.0, 2 * std::numbers::pi / 3, 4 * std::numbers::pi / 3);
  EXPECT_NEAR(conditioning(r.geometry, par).direct, 1.0, 1e-12);
  // Hand-worked between the two: directions 0, 0 and 90 degrees give U^T U =
  // diag(2, 1), smallest singular value 1, spread 1 / sqrt(3/2).
  par.theta_b = Vector3d(0.0, 0.0, std::numbers::pi / 2);
  EXPECT_NEAR(conditioning(r.geometry, par).direct, 1.0 / std::sqrt(1.5), 1e-12);
  // Issue 14.14: the spread stays in 0..1 for any finite angles (trace(U^T U) = 3,
  // so the smaller eigenvalue is at most 3/2), and is NaN, never 204, for NaN.
  Rng rng(7);
  const auto angle = [&](Rng& g) { return g.uniform(-10.0, 10.0); };
  for (int k = 0; k < 1000; ++k) {
    par.theta_a = Vector3d(angle(rng), angle(rng), angle(rng));
    par.theta_b = Vector3d(angle(rng), angle(rng), angle(rng));
    const double d = conditioning(r.geometry, par).direct;
    EXPECT_GE(d, 0.0);
    EXPECT_LE(d, 1.0 + 1e-12);
  }
  par.theta_a = par.theta_b = Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(std::isnan(conditioning(r.geometry, par).direct));
}

TEST(Kinematics, CheckReachHonoursMargins) {
  Robot r = nominal();
  EXPECT_TRUE(check_reach(r, r.home).ok);
  // Just inside the annulus but inside the margin: refused with a reason.
  const Vector2d edge = r.geometry.A(0) + Vector2d(488.0 - 1.0, 0.0);
  const Reach far = check_reach(r, edge);
  EXPECT_FALSE(far.ok);
  EXPECT_NE(far.reason.find("chain 1"), std::string::npos);
  r.limits.reach_margin = 0.5;
  r.limits.min_transmission = 0.0;
  r.limits.min_direct = 0.0;
  EXPECT_FALSE(check_reach(r, edge + Vector2d(0.6, 0)).ok);
}

TEST(Kinematics, ReadingsAndActiveAnglesInvert) {
  Geometry g = Geometry::gpm2002_nominal();
  g[kDth1] = 0.01; g[kDth2] = -0.02; g[kDth3] = 0.03;
  const Vector3d ta(1.1, 3.1, 4.8);
  const Vector3d tm = readings_from_active(g, ta);
  EXPECT_DOUBLE_EQ(tm[1], 3.1 + 0.02);
  EXPECT_TRUE(active_from_readings(g, tm).isApprox(ta, 1e-15));
}

TEST(Kinematics, InconsistentReadingsGiveEqualPowers) {
  // docs/EQUATIONS.md: at the radical centre the power w.r.t. all three circles is equal.
  const Geometry g = Geometry::gpm2002_nominal();
  const JointAngles q = inverse_kinematics(g, {220, 240});
  const Vector3d perturbed = q.theta_a + Vector3d(1e-3, -2e-3, 5e-4);
  const auto f = forward_kinematics(g, perturbed);
  ASSERT_TRUE(f);
  const auto B = elbows(g, perturbed);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR((f->p - B[i]).squaredNorm() - g.lb_(i) * g.lb_(i), f->power, 1e-7);
  EXPECT_GT(std::abs(f->power), 1e-3);
}

TEST(Kinematics, CircleIntersectionsHandWorked) {
  const auto x = circle_intersections({0, 0}, 5.0, {8, 0}, 5.0);
  ASSERT_TRUE(x);
  EXPECT_NEAR((*x)[0].x(), 4.0, 1e-15);
  EXPECT_NEAR((*x)[0].y(), 3.0, 1e-15);
  EXPECT_NEAR((*x)[1].y(), -3.0, 1e-15);
  EXPECT_FALSE(circle_intersections({0, 0}, 1.0, {5, 0}, 1.0));
}

}  // namespace
}  // namespace gpm
