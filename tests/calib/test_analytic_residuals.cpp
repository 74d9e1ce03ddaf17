// Tests of calib/analytic_residuals.cpp: on random parameter sets and random
// readings (the loops far from closed) and at exact data (closed), residuals
// equal the autodiff functors of calib/residuals.hpp, and the analytic
// Jacobians equal Ceres' automatic derivatives (1e-10 relative) and central
// differences (1e-6 relative), for E1, E2, E3 and ML.
#include "calib/analytic_residuals.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/parameterization.hpp"
#include "calib/residuals.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::calib {
namespace {

using RowJacobian = Eigen::Matrix<double, Eigen::Dynamic, kNumParams, Eigen::RowMajor>;

Eigen::VectorXd eval(const ceres::CostFunction& f, int rows, const ParamVector& x, RowJacobian* J) {
  Eigen::VectorXd r(rows);
  RowJacobian Jr(rows, kNumParams);
  const double* p[] = {x.data()};
  double* jac[] = {Jr.data()};
  EXPECT_TRUE(f.Evaluate(p, r.data(), J ? jac : nullptr));
  if (J) *J = Jr;
  return r;
}

// A geometry with every parameter perturbed from nominal (mm, rad).
Geometry random_geometry(Rng& rng) {
  Geometry g = Geometry::gpm2002_nominal();
  for (int p = 0; p < kNumParams; ++p) g[p] += is_offset(p) ? rng.uniform(-0.1, 0.1) : rng.uniform(-3.0, 3.0);
  return g;
}

// Compares analytic with autodiff and central differences at x.
void expect_jacobians_agree(Cost c, const Eigen::Vector3d& t, const ParamVector& x, const std::string& what) {
  const int rows = residual_rows(c);
  std::unique_ptr<ceres::CostFunction> an(make_analytic_residual(c, t)), ad(make_autodiff_residual(c, t));
  RowJacobian Ja, Jd;
  const Eigen::VectorXd ra = eval(*an, rows, x, &Ja), rd = eval(*ad, rows, x, &Jd);
  // P = |u|^2 - lb1^2 cancels terms of ~6e4 mm^2: values agree to rounding of those.
  EXPECT_LE((ra - rd).norm(), 1e-9 * std::max(1.0, rd.norm())) << what;
  const double scale = Jd.norm();
  ASSERT_GT(scale, 0.0) << what;
  EXPECT_LE((Ja - Jd).norm(), 1e-10 * scale) << what << "\nanalytic\n" << Ja << "\nautodiff\n" << Jd;
  for (int i = 0; i < kNumParams; ++i) {
    const double h = 1e-6 * std::max(1.0, std::abs(x[static_cast<size_t>(i)]));
    ParamVector xp = x, xm = x;
    xp[static_cast<size_t>(i)] += h;
    xm[static_cast<size_t>(i)] -= h;
    const Eigen::VectorXd fd = (eval(*an, rows, xp, nullptr) - eval(*an, rows, xm, nullptr)) / (2 * h);
    // Differences carry the rounding of P (about 1e-11 mm^2 of ~6e4 cancelled) over 2h.
    EXPECT_LE((Ja.col(i) - fd).norm(), 1e-6 * std::max(Ja.col(i).norm(), 1e-6 * scale) + 1e-10 / h)
        << what << " d/d" << param_name(i);
  }
}

TEST(AnalyticResiduals, EqualAutodiffAndCentralDifferencesOnRandomParametersAndReadings) {
  Rng rng(31);
  for (int trial = 0; trial < 25; ++trial) {
    const Geometry g = random_geometry(rng);
    const Eigen::Vector3d t(1.111 + rng.uniform(-0.3, 0.3), 3.111 + rng.uniform(-0.3, 0.3),
                            4.825 + rng.uniform(-0.3, 0.3));
    for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML})
      expect_jacobians_agree(c, t, to_solver(g, c), std::string(cost_name(c)) + " trial " + std::to_string(trial));
  }
}

TEST(AnalyticResiduals, EqualAutodiffWhereTheLoopsClose) {
  // Exact readings of the true mechanism: P = 0, so ML's derivative is dP/|g|
  // alone and E1's rows vanish; the Jacobians must still agree.
  const Geometry truth = table5_actual();
  Rng rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Vector2d p(216.5 + rng.uniform(-70.0, 70.0), 250.0 + rng.uniform(-70.0, 70.0));
    const Eigen::Vector3d t = readings_from_active(truth, inverse_kinematics(truth, p).theta_a);
    for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML})
      expect_jacobians_agree(c, t, to_solver(truth, c), std::string(cost_name(c)) + " exact " + std::to_string(trial));
  }
}

TEST(AnalyticResiduals, ImpliedPowerDerivativeIsTheBarycentricHandWorkedCase) {
  // Hand-worked: elbows at A_i + la (theta_a) chosen so that B = (0,0), (2,0),
  // (0,2) with lb = (2, 1, 1.5): O = (7/4, 23/16) (models/closure.hpp's
  // hand-worked case). Moving lb_1 changes P by 2 lb_1 q_1 with -q_1 the
  // barycentric coordinate of O at B1: 1 - 7/8 - 23/32 = -19/32.
  Geometry g = Geometry::gpm2002_nominal();
  const double Bx[3] = {0.0, 2.0, 0.0}, By[3] = {0.0, 0.0, 2.0};
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) {
    g[xa(i)] = Bx[i] - 1.0;  // A_i one mm left of B_i, theta_a = 0
    g[ya(i)] = By[i];
    g[la(i)] = 1.0;
    g[dth(i)] = 0.0;
    t[i] = 0.0;
  }
  g[kLb1] = 2.0, g[kLb2] = 1.0, g[kLb3] = 1.5;
  std::unique_ptr<ceres::CostFunction> f(make_analytic_residual(Cost::kJ2, t));
  RowJacobian J;
  const ParamVector x = to_solver(g, Cost::kJ2);
  const Eigen::VectorXd r = eval(*f, 1, x, &J);
  EXPECT_NEAR(r[0], 1.75 * 1.75 + 1.4375 * 1.4375 - 4.0, 1e-14);
  EXPECT_NEAR(J(0, kLb1), 2.0 * 2.0 * (-(1.0 - 1.75 / 2.0 - 1.4375 / 2.0)), 1e-13);
}

}  // namespace
}  // namespace gpm::calib
