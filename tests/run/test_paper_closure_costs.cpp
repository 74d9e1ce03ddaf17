// Tests of run/paper/closure_costs.cpp: J1 and J2 (= J3) at one geometry,
// cross-checked against the solver's residual functors (calib/residuals.hpp)
// and zero at the true geometry for exact readings.
#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/residuals.hpp"
#include "calib/synthetic.hpp"
#include "run/paper/closure_costs.hpp"

namespace gpm::paper {
namespace {

Samples table5_samples(int n) {
  Robot actual;
  actual.geometry = calib::table5_actual();
  return calib::workspace_samples(actual, n, 7);
}

TEST(ClosureCosts, ZeroAtTheTruthForExactReadings) {
  const Samples s = table5_samples(20);
  const ClosureCosts c = closure_costs(calib::table5_actual(), s.theta_m);
  EXPECT_LT(c.j1, 1e-18);
  EXPECT_LT(c.j23, 1e-12);
}

TEST(ClosureCosts, MatchesTheResidualFunctorsAwayFromTheTruth) {
  const Samples s = table5_samples(10);
  const Geometry g = Geometry::gpm2002_nominal();
  double j1 = 0, j2 = 0;
  for (const Eigen::Vector3d& m : s.theta_m) {
    double r1[6], r2[1];
    ASSERT_TRUE(calib::E1Residual(m)(g.values.data(), r1));
    ASSERT_TRUE(calib::E2Residual(m)(g.values.data(), r2));
    for (double v : r1) j1 += v * v;
    j2 += r2[0] * r2[0];
  }
  const ClosureCosts c = closure_costs(g, s.theta_m);
  EXPECT_GT(c.j1, 1.0);  // the nominal values are millimetres off
  EXPECT_NEAR(c.j1, j1, 1e-9 * j1);
  // J2 = 3 sum g^2 (the three rows of E2 are equal, docs/PAPER_NOTES.md).
  EXPECT_NEAR(c.j23, calib::paper_cost(calib::Cost::kJ2, j2), 1e-9 * c.j23);
  // For small closure errors J2 is about (2 l_b)^2 J1.
  EXPECT_NEAR(c.j23 / c.j1, 4 * 244.0 * 244.0, 0.05 * 4 * 244.0 * 244.0);
}

}  // namespace
}  // namespace gpm::paper
