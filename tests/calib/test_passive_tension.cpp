// Tests of calib/passive_tension.cpp: the axial force of a passive link
// against a hand-worked pose and against virtual work (finite differences of
// the distance B_i C), the reading equivalent of a length change against the
// ML closure residual of the lengthened link, and the transmitted torque by hand.
#include "calib/passive_tension.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "calib/parameterization.hpp"
#include "calib/paper_values.hpp"
#include "calib/residuals.hpp"
#include "models/kinematics.hpp"
#include "models/robot.hpp"

namespace gpm::calib {
namespace {

// Active link along +x (B at la from A), passive link along +y: a positive
// (counter-clockwise) torque pushes B towards C, so the link is in
// compression: T = -tau / la = -2.44 N m / 0.244 m = -10 N.
TEST(PassiveTension, HandWorkedPerpendicularLinks) {
  Geometry g = Robot{}.geometry;
  g.values[kLa1] = 244.0;
  EXPECT_NEAR(passive_link_tension(g, 0, 0.0, std::numbers::pi / 2, 2.44), -10.0, 1e-12);
  EXPECT_NEAR(passive_link_tension(g, 0, 0.0, -std::numbers::pi / 2, 2.44), 10.0, 1e-12);
  // 1 mm longer passive link = 1 / 244 rad more of the active link.
  EXPECT_NEAR(reading_per_passive_length(g, 0, 0.0, std::numbers::pi / 2), 1.0 / 244.0, 1e-15);
}

// Virtual work at a real pose: tau dtheta = T d|C - B| (T > 0 pulls B towards
// C), with d|C - B| / dtheta by central differences of B(theta).
TEST(PassiveTension, AgreesWithVirtualWork) {
  const Geometry g = table5_actual();
  const Eigen::Vector2d c(230.0, 265.0);
  const JointAngles q = inverse_kinematics(g, c);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d a(g[xa(i)], g[ya(i)]);
    const auto dist = [&](double t) { return (c - a - g.la_(i) * Eigen::Vector2d(std::cos(t), std::sin(t))).norm(); };
    const double h = 1e-6;
    const double ddist_m = 1e-3 * (dist(q.theta_a[i] + h) - dist(q.theta_a[i] - h)) / (2 * h);  // m/rad
    const double tau = 1.7;
    EXPECT_NEAR(passive_link_tension(g, i, q.theta_a[i], q.theta_b[i], tau), tau / ddist_m, 1e-5 * std::abs(tau / ddist_m))
        << "chain " << i + 1;
  }
}

// Lengthening passive link i by d reads as turning active link i by
// d * reading_per_passive_length: the ML residual of the lengthened geometry
// at the readings equals that of the original geometry at the shifted reading
// to second order in d, while d itself moves the residual at first order.
TEST(PassiveTension, LengthChangeEqualsAReadingShift) {
  const Geometry g = table5_actual();
  const JointAngles q = inverse_kinematics(g, Eigen::Vector2d(200.0, 240.0));
  const Eigen::Vector3d theta_m = readings_from_active(g, q.theta_a);
  const double d = 1e-3;  // mm
  for (int i = 0; i < 3; ++i) {
    Geometry longer = g;
    longer.values[lb(i)] += d;
    Eigen::Vector3d shifted = theta_m;
    shifted[i] += d * reading_per_passive_length(g, i, q.theta_a[i], q.theta_b[i]);
    double r_longer = NAN, r_shifted = NAN, r_exact = NAN;
    MlResidual{theta_m}(to_solver(longer, Cost::kML).data(), &r_longer);
    MlResidual{shifted}(to_solver(g, Cost::kML).data(), &r_shifted);
    MlResidual{theta_m}(to_solver(g, Cost::kML).data(), &r_exact);
    EXPECT_NEAR(r_exact, 0.0, 1e-12);
    EXPECT_GT(std::abs(r_longer), 1e-7) << "chain " << i + 1;
    EXPECT_NEAR(r_shifted, r_longer, 1e-4 * std::abs(r_longer)) << "chain " << i + 1;
  }
}

TEST(PassiveTension, TransmittedTorqueByHand) {
  TransmissionLoad load;
  load.coulomb_Nm = {0.3, 0.0, 0.0};
  load.viscous_Nm_s = {0.1, 0.0, 0.0};
  load.inertia_kg_m2 = {0.02, 0.0, 0.0};
  // Moving well above kFrictionSpeed: the full Coulomb friction.
  EXPECT_NEAR(transmitted_torque(load, 0, 5.0, 1.0, 10.0), 5.0 - 0.3 - 0.1 - 0.2, 1e-12);
  EXPECT_NEAR(transmitted_torque(load, 0, 5.0, -1.0, 0.0), 5.0 + 0.3 + 0.1, 1e-12);
  EXPECT_EQ(transmitted_torque(load, 1, 5.0, 1.0, 10.0), 5.0);
  // The smoothing speed is the load's (the drift monitor's 0.1 rad/s): at
  // that speed tanh(1) of the Coulomb friction; 0: the sign alone.
  load.friction_speed_rad_s = 0.1;
  EXPECT_NEAR(transmitted_torque(load, 0, 5.0, 0.1, 0.0), 5.0 - 0.3 * 0.76159415595576 - 0.01, 1e-12);
  load.friction_speed_rad_s = 0.0;
  EXPECT_NEAR(transmitted_torque(load, 0, 5.0, 0.001, 0.0), 5.0 - 0.3 - 1e-4, 1e-12);
  EXPECT_EQ(transmitted_torque(load, 0, 5.0, 0.0, 0.0), 5.0);
}

}  // namespace
}  // namespace gpm::calib
