// Tests of models/closure.hpp: the radical centre in a hand-worked case, equal
// power for the three circles, against the two-circle intersection of
// models/kinematics.cpp where the loops close, collinear elbows refused,
// eq. 34's atan2 in every quadrant, and both parameter layouts of closure().
#include "models/closure.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm {
namespace {

TEST(RadicalCentre, HandWorkedCase) {
  // Circles (0,0; 2), (2,0; 1), (0,2; 1.5): subtracting circle 1 from 2 and 3,
  // 4x = 4 + 4 - 1 and 4y = 4 + 4 - 2.25, so O = (7/4, 23/16), P = |O|^2 - 4.
  const double Bx[3] = {0.0, 2.0, 0.0}, By[3] = {0.0, 0.0, 2.0}, lb[3] = {2.0, 1.0, 1.5};
  const RadicalCentre<double> c = radical_centre(Bx, By, lb);
  ASSERT_TRUE(c.ok);
  EXPECT_DOUBLE_EQ(c.Ox, 1.75);
  EXPECT_DOUBLE_EQ(c.Oy, 1.4375);
  EXPECT_DOUBLE_EQ(c.P, 1.75 * 1.75 + 1.4375 * 1.4375 - 4.0);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(std::pow(c.Ox - Bx[i], 2) + std::pow(c.Oy - By[i], 2) - lb[i] * lb[i], c.P, 1e-14) << i;
  EXPECT_DOUBLE_EQ(c.det, 4.0);
}

TEST(RadicalCentre, EqualsTheTwoCircleIntersectionWhenTheLoopsClose) {
  Rng rng(13);
  const Geometry nominal = Geometry::gpm2002_nominal();
  int checked = 0;
  for (int t = 0; t < 200; ++t) {
    Geometry g = nominal;
    for (int p = 0; p < kNumParams; ++p) g[p] += is_offset(p) ? rng.uniform(-0.05, 0.05) : rng.uniform(-2.0, 2.0);
    const Eigen::Vector2d target(216.5 + rng.uniform(-60.0, 60.0), 250.0 + rng.uniform(-60.0, 60.0));
    const JointAngles q = inverse_kinematics(g, target);
    const auto B = elbows(g, q.theta_a);
    const double Bx[3] = {B[0].x(), B[1].x(), B[2].x()}, By[3] = {B[0].y(), B[1].y(), B[2].y()};
    const double lb[3] = {g[kLb1], g[kLb2], g[kLb3]};
    const RadicalCentre<double> c = radical_centre(Bx, By, lb);
    ASSERT_TRUE(c.ok);
    const int mode = assembly_mode(g, q.theta_a, target, 0, 1);
    const auto two = forward_kinematics_two(g, q.theta_a, 0, 1, mode);
    ASSERT_TRUE(two);
    EXPECT_LT((Eigen::Vector2d(c.Ox, c.Oy) - *two).norm(), 1e-9);
    EXPECT_LT((Eigen::Vector2d(c.Ox, c.Oy) - target).norm(), 1e-9);
    EXPECT_LT(std::abs(c.P), 1e-7 * lb[0] * lb[0]);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(passive_angle(c.Ox, c.Oy, Bx[i], By[i]), q.theta_b[i], 1e-9) << "eq. 34, chain " << i;
    ++checked;
  }
  EXPECT_EQ(checked, 200);
}

TEST(RadicalCentre, CollinearElbowsHaveNoCentre) {
  const double Bx[3] = {0.0, 1.0, 3.0}, By[3] = {1.0, 2.0, 4.0}, lb[3] = {1.0, 1.0, 1.0};
  const RadicalCentre<double> c = radical_centre(Bx, By, lb);
  EXPECT_FALSE(c.ok);
  EXPECT_EQ(c.P, 0.0);
}

TEST(PassiveAngle, UsesTheFullCircle) {
  const double pi = std::numbers::pi;
  EXPECT_DOUBLE_EQ(passive_angle(1.0, 1.0, 0.0, 0.0), pi / 4);
  EXPECT_DOUBLE_EQ(passive_angle(-1.0, 1.0, 0.0, 0.0), 3 * pi / 4);
  EXPECT_DOUBLE_EQ(passive_angle(-1.0, -1.0, 0.0, 0.0), -3 * pi / 4);
  EXPECT_DOUBLE_EQ(passive_angle(1.0, -1.0, 0.0, 0.0), -pi / 4);
}

TEST(Closure, BothLayoutsGiveTheForwardKinematicsPoint) {
  Geometry g = Geometry::gpm2002_nominal();
  g[kDth1] = 0.02, g[kDth2] = -0.01, g[kDth3] = 0.015, g[kLa3] = 244.3;
  const JointAngles q = inverse_kinematics(g, {230.0, 240.0});
  const Eigen::Vector3d tm = readings_from_active(g, q.theta_a);
  const Closure<double> a = closure(g.values.data(), tm.data(), false, true);
  Geometry d = g;  // decoupled: l_ac = l_a cos dth, l_as = l_a sin dth (eq. 41)
  for (int i = 0; i < 3; ++i) {
    d[la(i)] = g[la(i)] * std::cos(g[dth(i)]);
    d[dth(i)] = g[la(i)] * std::sin(g[dth(i)]);
  }
  const Closure<double> b = closure(d.values.data(), tm.data(), true, false);
  const auto fk = forward_kinematics(g, active_from_readings(g, tm));
  ASSERT_TRUE(a.ok && b.ok && fk);
  EXPECT_NEAR(a.Ox, 230.0, 1e-9);
  EXPECT_NEAR(a.Oy, 240.0, 1e-9);
  EXPECT_NEAR(b.Ox, a.Ox, 1e-9);
  EXPECT_NEAR(b.Oy, a.Oy, 1e-9);
  EXPECT_LT((fk->p - Eigen::Vector2d(a.Ox, a.Oy)).norm(), 1e-12);  // the same code
  EXPECT_NEAR(fk->power, a.P, 1e-9);
  // dP / d theta_m by central differences of the readings.
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d tp = tm, tn = tm;
    tp[k] += 1e-6, tn[k] -= 1e-6;
    const double fd = (closure(g.values.data(), tp.data(), false, false).P -
                       closure(g.values.data(), tn.data(), false, false).P) / 2e-6;
    EXPECT_NEAR(a.dP[k], fd, 1e-5 * std::abs(fd) + 1e-6) << k;
  }
}

}  // namespace
}  // namespace gpm
