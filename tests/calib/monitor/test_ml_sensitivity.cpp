// Tests of calib/monitor/ml_sensitivity.cpp: the residual equals the ML
// residual of calib/residuals.hpp evaluated by Ceres, its gradient matches
// central finite differences, and an offset column equals the reading
// column (theta_a = theta_m + dth, eq. 35).
#include "calib/monitor/ml_sensitivity.hpp"

#include <memory>

#include <gtest/gtest.h>

#include "calib/residuals.hpp"
#include "tests/calib/monitor/circle_stream.hpp"

namespace gpm::calib::monitor {
namespace {

TEST(MlSensitivity, MatchesCeresResidualAndFiniteDifferences) {
  Geometry truth = Geometry::gpm2002_nominal();
  Geometry model = truth;
  model[kLa2] += 0.01;
  model[kDth3] -= 2e-4;
  testing::CircleStream cs;
  for (double t : {0.0, 0.7, 1.9, 3.1}) {
    const Eigen::Vector3d th = cs.readings(truth, t);
    double r = 0.0;
    ParamRow g;
    ASSERT_TRUE(ml_residual_and_gradient(model, th, r, g));
    std::unique_ptr<ceres::CostFunction> f(make_residual(Cost::kML, th));
    const double* params[] = {model.values.data()};
    double r_ceres = 0.0;
    ASSERT_TRUE(f->Evaluate(params, &r_ceres, nullptr));
    EXPECT_NEAR(r, r_ceres, 1e-15);
    EXPECT_GT(std::abs(r), 1e-7);  // the model is off: a real residual
    for (int i = 0; i < kNumParams; ++i) {
      const double h = is_offset(i) ? 1e-7 : 1e-5;
      Geometry a = model, b = model;
      a[i] += h;
      b[i] -= h;
      double ra = 0.0, rb = 0.0;
      ParamRow ga, gb;
      ASSERT_TRUE(ml_residual_and_gradient(a, th, ra, ga));
      ASSERT_TRUE(ml_residual_and_gradient(b, th, rb, gb));
      EXPECT_NEAR(g[i], (ra - rb) / (2 * h), 1e-6 * std::max(1.0, std::abs(g[i]))) << param_name(i);
    }
    // d r / d dth_k = d r / d theta_m^k
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d ta = th, tb = th;
      ta[k] += 1e-7;
      tb[k] -= 1e-7;
      double ra = 0.0, rb = 0.0;
      ParamRow unused;
      ASSERT_TRUE(ml_residual_and_gradient(model, ta, ra, unused));
      ASSERT_TRUE(ml_residual_and_gradient(model, tb, rb, unused));
      EXPECT_NEAR(g[dth(k)], (ra - rb) / 2e-7, 1e-6);
    }
  }
}

TEST(MlSensitivity, ZeroAtTheTrueGeometryWithExactReadings) {
  const Geometry g = Geometry::gpm2002_nominal();
  testing::CircleStream cs;
  cs.bits = 0;
  double r = 1.0;
  ParamRow grad;
  ASSERT_TRUE(ml_residual_and_gradient(g, cs.readings(g, 1.3), r, grad));
  EXPECT_NEAR(r, 0.0, 1e-12);
}

}  // namespace
}  // namespace gpm::calib::monitor
