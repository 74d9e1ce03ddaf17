// Tests of calib/montecarlo.cpp, cheap (the full study is the montecarlo
// label): at small noise (linear regime) 40 trials give per-parameter ratios
// of ML near 1 (within sampling error) and a normalised ratio near 1, J3 is no
// better than ML on average, and the reported 1-sigma equals the bound.
#include "calib/montecarlo.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::calib {
namespace {

TEST(MonteCarlo, MlIsEfficientInTheLinearRegime) {
  MonteCarloOptions o = default_montecarlo_options();
  o.trials = 40;
  o.sigma = 1e-6;
  o.radius_mm = 120.0;
  const auto rows = run_montecarlo(o);
  ASSERT_EQ(rows.size(), 2u);
  const MonteCarloRow& ml = rows[0];
  const MonteCarloRow& j3 = rows[1];
  EXPECT_EQ(ml.failures, 0);
  EXPECT_EQ(j3.failures, 0);
  for (int i = 0; i < kNumParams; ++i) {
    if (!o.free.test(static_cast<size_t>(i))) continue;
    EXPECT_GT(ml.ratio[static_cast<size_t>(i)], 0.6) << param_name(i);
    EXPECT_LT(ml.ratio[static_cast<size_t>(i)], 1.4) << param_name(i);
    EXPECT_NEAR(ml.mean_reported_sigma[static_cast<size_t>(i)] / ml.bound[static_cast<size_t>(i)], 1.0, 0.01);
  }
  EXPECT_NEAR(ml.normalised_ratio, 1.0, 0.2);
  EXPECT_GE(j3.rms_ratio, ml.rms_ratio * 0.97);  // paired noise: J3 no better than ML
  std::printf("  40 trials, sigma 1e-6: ml rms ratio %.3f, j3 rms ratio %.3f\n", ml.rms_ratio, j3.rms_ratio);
}

}  // namespace
}  // namespace gpm::calib
