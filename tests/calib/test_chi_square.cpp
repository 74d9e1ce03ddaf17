// Tests of calib/chi_square.cpp against closed forms: for even k the
// chi-square survival is the Poisson sum e^{-x/2} sum_{j<k/2} (x/2)^j / j!,
// for k = 1 it is erfc(sqrt(x/2)), for k = 2 the quantile is -2 ln p; and two
// table values; the misfit share by hand.
#include "calib/chi_square.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::calib {
namespace {

double poisson_tail(int k, double x) {  // chi-square survival for even k
  double term = 1.0, sum = 1.0;
  for (int j = 1; j < k / 2; ++j) term *= 0.5 * x / j, sum += term;
  return std::exp(-0.5 * x) * sum;
}

TEST(ChiSquare, SurvivalMatchesThePoissonSumForEvenDegrees) {
  for (int k : {2, 4, 10, 20, 40, 100, 200})
    for (double f : {0.1, 0.5, 1.0, 1.5, 3.0, 6.0}) {
      const double x = f * k;
      const double want = poisson_tail(k, x);
      EXPECT_NEAR(chi2_survival(k, x), want, 1e-12 * want + 1e-300) << "k=" << k << " x=" << x;
    }
}

TEST(ChiSquare, SurvivalOfOneDegreeIsErfc) {
  for (double x : {0.01, 0.3, 1.0, 2.0, 4.0, 9.0, 25.0, 49.0})
    EXPECT_NEAR(chi2_survival(1, x), std::erfc(std::sqrt(0.5 * x)), 1e-13 * std::erfc(std::sqrt(0.5 * x)));
}

TEST(ChiSquare, QuantileInvertsTheSurvival) {
  // k = 2: Q = exp(-x/2), so the quantile is -2 ln p exactly.
  for (double p : {0.5, 1e-3, 1e-8, 1e-12}) EXPECT_NEAR(chi2_upper_quantile(2, p), -2.0 * std::log(p), 1e-10);
  // Round trip through the Poisson sum in the far tail (the monitor's case).
  for (int k : {20, 100})
    for (double p : {0.05, 1e-6, 2.8e-8}) {
      const double x = chi2_upper_quantile(k, p);
      EXPECT_NEAR(poisson_tail(k, x), p, 1e-9 * p) << "k=" << k;
    }
  // Table values (any chi-square table): 95% points of 1 and 10 degrees.
  EXPECT_NEAR(chi2_upper_quantile(1, 0.05), 3.841458820694124, 1e-9);
  EXPECT_NEAR(chi2_upper_quantile(10, 0.05), 18.307038053275146, 1e-9);
}

TEST(ChiSquare, RejectsArgumentsOutsideTheDomain) {
  EXPECT_THROW(chi2_upper_quantile(0, 0.1), std::invalid_argument);
  EXPECT_THROW(chi2_upper_quantile(3, 1.0), std::invalid_argument);
  EXPECT_THROW(chi2_survival(-1.0, 1.0), std::invalid_argument);
}

TEST(ChiSquare, MisfitShareIsTheExcessALargerModelTakesAway) {
  // chi2 200 for 100 degrees of freedom: 100 above the noise.
  EXPECT_DOUBLE_EQ(misfit_share(200.0, 100.0, 150.0), 0.5);
  EXPECT_DOUBLE_EQ(misfit_share(200.0, 100.0, 100.0), 1.0) << "down to the noise: all of it";
  EXPECT_DOUBLE_EQ(misfit_share(200.0, 100.0, 200.0), 0.0) << "nothing taken";
  EXPECT_LT(misfit_share(200.0, 100.0, 210.0), 0.0) << "a worse fit takes a negative share";
  // A fit at or below the noise has no misfit to share.
  EXPECT_EQ(misfit_share(90.0, 100.0, 80.0), 0.0);
  EXPECT_EQ(misfit_share(100.0, 100.0, 50.0), 0.0);
}

}  // namespace
}  // namespace gpm::calib
