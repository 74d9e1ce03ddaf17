// Tests of calib/residuals.cpp and models/closure.hpp: autodiff Jacobians
// against central differences, closure gradient against differences in the
// readings, E2 rows equal (docs/EQUATIONS.md), residuals zero at the truth, J3 equal to
// J2 in its own variables, the ML residual equal to the reading correction
// that closes the loops, and its invariance under the similarity gauge.
#include "calib/residuals.hpp"

#include <memory>

#include <gtest/gtest.h>

#include "calib/identifiability.hpp"
#include "calib/paper_values.hpp"
#include "calib/parameterization.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {
namespace {

using Eigen::Vector3d;

Vector3d readings_at(const Geometry& g, double x, double y) {
  return readings_from_active(g, inverse_kinematics(g, {x, y}).theta_a);
}

Eigen::VectorXd eval(Cost c, const Vector3d& t, const ParamVector& x, Eigen::MatrixXd* J = nullptr) {
  std::unique_ptr<ceres::CostFunction> f(make_autodiff_residual(c, t));
  const int m = residual_rows(c);
  Eigen::VectorXd r(m);
  Eigen::Matrix<double, Eigen::Dynamic, kNumParams, Eigen::RowMajor> Jr(m, kNumParams);
  const double* p[] = {x.data()};
  double* jac[] = {Jr.data()};
  EXPECT_TRUE(f->Evaluate(p, r.data(), J ? jac : nullptr));
  if (J) *J = Jr;
  return r;
}

// A point off the truth so residuals are not zero.
Geometry perturbed() {
  Geometry g = table5_actual();
  g[kLa2] += 0.7;
  g[kDth1] += 0.01;
  g[kXa3] -= 0.4;
  g[kLb3] += 0.3;
  return g;
}

TEST(Residuals, AutodiffJacobianMatchesCentralDifferences) {
  const Geometry truth = table5_actual();
  const Vector3d t = readings_at(truth, 230.0, 270.0);
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML}) {
    const ParamVector x = to_solver(perturbed(), c);
    Eigen::MatrixXd J;
    eval(c, t, x, &J);
    for (int i = 0; i < kNumParams; ++i) {
      const double h = 1e-6 * std::max(1.0, std::abs(x[static_cast<size_t>(i)]));
      ParamVector xp = x, xm = x;
      xp[static_cast<size_t>(i)] += h;
      xm[static_cast<size_t>(i)] -= h;
      const Eigen::VectorXd fd = (eval(c, t, xp) - eval(c, t, xm)) / (2 * h);
      const double scale = std::max(1.0, J.col(i).norm());
      EXPECT_LT((J.col(i) - fd).norm() / scale, 1e-6) << cost_name(c) << " d/d" << param_name(i);
    }
  }
}

TEST(Residuals, ClosureGradientMatchesDifferencesInReadings) {
  const Geometry g = perturbed();
  const Vector3d t = readings_at(table5_actual(), 200.0, 230.0);
  const auto c = closure(g.values.data(), t.data(), false, true);
  ASSERT_TRUE(c.ok);
  for (int k = 0; k < 3; ++k) {
    Vector3d tp = t, tm = t;
    tp[k] += 1e-6;
    tm[k] -= 1e-6;
    const double fd = (closure(g.values.data(), tp.data(), false, false).P -
                       closure(g.values.data(), tm.data(), false, false).P) / 2e-6;
    EXPECT_NEAR(c.dP[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << k;
  }
}

TEST(Residuals, ZeroAtTheTruthAndE2RowsEqualThePower) {
  const Geometry truth = table5_actual();
  const Vector3d t = readings_at(truth, 250.0, 220.0);
  for (Cost c : {Cost::kJ1, Cost::kJ2, Cost::kJ3, Cost::kML})
    EXPECT_LT(eval(c, t, to_solver(truth, c)).norm(), 1e-9) << cost_name(c);
  // Off the truth: each eq. 38 row |O - B_i|^2 - lb_i^2 equals the power.
  const Geometry g = perturbed();
  const auto f = forward_kinematics(g, active_from_readings(g, t));
  ASSERT_TRUE(f.has_value());
  const auto B = elbows(g, active_from_readings(g, t));
  const double g2 = eval(Cost::kJ2, t, to_solver(g, Cost::kJ2))[0];
  EXPECT_GT(std::abs(g2), 1.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR((f->p - B[static_cast<size_t>(i)]).squaredNorm() - g.lb_(i) * g.lb_(i), g2, 1e-8) << i;
  }
  EXPECT_NEAR(f->power, g2, 1e-8);
  // J3 is J2 in the decoupled variables.
  EXPECT_NEAR(eval(Cost::kJ3, t, to_solver(g, Cost::kJ3))[0], g2, 1e-8);
  EXPECT_DOUBLE_EQ(paper_cost(Cost::kJ2, 2.0), 6.0);
  EXPECT_DOUBLE_EQ(paper_cost(Cost::kML, 2.0), 2.0);
}

// Eq. 36's six E1 rows (E1Residual, the paper's form) at x.
Eigen::VectorXd eval_eq36(const Vector3d& t, const ParamVector& x) {
  const ceres::AutoDiffCostFunction<E1Residual, 6, kNumParams> f(new E1Residual(t));
  Eigen::VectorXd r(6);
  const double* p[] = {x.data()};
  EXPECT_TRUE(f.Evaluate(p, r.data(), nullptr));
  return r;
}

TEST(Residuals, E1RowsAreEq36WithPassiveAnglesFromFk) {
  const Geometry g = perturbed();
  const Vector3d t = readings_at(table5_actual(), 190.0, 260.0);
  const Eigen::VectorXd r = eval_eq36(t, to_solver(g, Cost::kJ1));
  const Vector3d ta = active_from_readings(g, t);
  const auto f = forward_kinematics(g, ta);
  ASSERT_TRUE(f.has_value());
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d e = f->p - g.A(i) - g.la_(i) * Eigen::Vector2d(std::cos(ta[i]), std::sin(ta[i])) -
                              g.lb_(i) * Eigen::Vector2d(std::cos(f->theta_b[i]), std::sin(f->theta_b[i]));
    EXPECT_NEAR(r[2 * i], e.x(), 1e-9);
    EXPECT_NEAR(r[2 * i + 1], e.y(), 1e-9);
  }
}

TEST(Residuals, E1SolverRowsAreTheSignedLengthsOfEq36Rows) {
  // The solver's three J1 rows e_i = |O - B_i| - lb_i: |e_i| = |E1_i|, so both
  // forms give the same J1 everywhere; the sign is that of |O - B_i| - lb_i.
  const Geometry g = perturbed();
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(190.0, 260.0), Eigen::Vector2d(250.0, 210.0)}) {
    const Vector3d t = readings_at(table5_actual(), p.x(), p.y());
    const ParamVector x = to_solver(g, Cost::kJ1);
    const Eigen::VectorXd e = eval(Cost::kJ1, t, x), r6 = eval_eq36(t, x);
    ASSERT_EQ(e.size(), 3);
    const auto f = forward_kinematics(g, active_from_readings(g, t));
    ASSERT_TRUE(f.has_value());
    const auto B = elbows(g, active_from_readings(g, t));
    for (int i = 0; i < 3; ++i) {
      EXPECT_GT(std::abs(e[i]), 1e-3) << i;  // off the truth: a real error
      EXPECT_NEAR(std::abs(e[i]), r6.segment<2>(2 * i).norm(), 1e-9) << i;
      EXPECT_NEAR(e[i], (f->p - B[static_cast<size_t>(i)]).norm() - g.lb_(i), 1e-9) << i;
    }
    EXPECT_NEAR(e.squaredNorm(), r6.squaredNorm(), 1e-9 * r6.squaredNorm());
  }
}

TEST(Residuals, MlResidualIsTheSmallestReadingCorrectionThatClosesTheLoops) {
  // Readings of the truth plus a small error e: to first order the ML
  // residual is the component of e along the closure gradient.
  const Geometry truth = table5_actual();
  const Vector3d t0 = readings_at(truth, 240.0, 280.0);
  const auto c0 = closure(truth.values.data(), t0.data(), false, true);
  const Vector3d grad(c0.dP[0], c0.dP[1], c0.dP[2]);
  const Vector3d e = 1e-6 * Vector3d(1.0, -2.0, 0.5);
  const Vector3d t = t0 + e;
  const double r = eval(Cost::kML, t, to_solver(truth, Cost::kML))[0];
  EXPECT_NEAR(r, grad.dot(e) / grad.norm(), 1e-10);
}

TEST(Residuals, MlResidualIsInvariantUnderTheSimilarityGauge) {
  const Geometry g = perturbed();
  const Vector3d t = readings_at(table5_actual(), 210.0, 240.0);
  Eigen::MatrixXd J;
  eval(Cost::kML, t, to_solver(g, Cost::kML), &J);
  const auto G = gauge_generators(g);
  for (int q = 0; q < 4; ++q) EXPECT_NEAR((J * G.col(q))(0), 0.0, 1e-12) << "generator " << q;
  // ... while the power (J2) is not invariant under scale away from the truth.
  eval(Cost::kJ2, t, to_solver(g, Cost::kJ2), &J);
  EXPECT_GT(std::abs((J * G.col(3))(0)), 1e-3);
}

}  // namespace
}  // namespace gpm::calib
