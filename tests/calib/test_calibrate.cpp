// Tests of calib/calibrate.cpp (and the Method names of calib/problem.hpp):
// every method name round-trips, an unknown one is refused in one line that
// names the valid values, LM through the entry point is calibrate_lm, a
// global method recovers the true values of exact data, and ML is refused
// for a population method; the robust losses (calib/robust_loss.hpp) against
// their closed forms and finite differences, and against outlier samples.
#include "calib/calibrate.hpp"

#include <cmath>

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include "calib/lm.hpp"
#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

TEST(Calibrate, MethodNamesRoundTripAndUnknownNamesAreRefusedInOneLine) {
  for (Method m : {Method::kLM, Method::kGA, Method::kPSO, Method::kDE, Method::kDELM})
    EXPECT_EQ(parse_method(method_name(m)), m);
  try {
    parse_method("simplex", "calibration.method");
    FAIL() << "simplex accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what, "calibration.method: unknown method 'simplex' (valid: lm, ga, pso, de, de+lm)");
  }
  EXPECT_THROW(parse_method("DE"), InputError);
  EXPECT_THROW(parse_method(""), InputError);
}

Problem exact_problem() {
  Robot r;
  r.geometry = table5_actual();
  return table5_problem(workspace_samples(r, 40, 3), default_free_mask());
}

TEST(Calibrate, LmThroughTheEntryPointIsCalibrateLm) {
  const Problem p = exact_problem();
  MethodOptions o;
  o.cost = Cost::kJ2;
  LmOptions lm;
  lm.cost = Cost::kJ2;
  const Result a = calibrate(p, o), b = calibrate_lm(p, lm);
  EXPECT_EQ(a.geometry, b.geometry);
  EXPECT_EQ(a.method, "lm");
  for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(a.geometry[i], table5_actual()[i], 1e-6) << param_name(i);
}

TEST(Calibrate, DePlusLmOnMlRecoversExactDataAndPopulationMethodsRefuseMl) {
  const Problem p = exact_problem();
  MethodOptions o;
  o.method = Method::kDELM;
  o.cost = Cost::kML;
  o.budget = 20'000;
  const Result r = calibrate(p, o);
  EXPECT_EQ(r.method, "de+lm");
  EXPECT_GT(r.evaluations, 20'000);  // DE's budget plus LM's evaluations
  for (int i = 0; i < kNumParams; ++i) EXPECT_NEAR(r.geometry[i], table5_actual()[i], 1e-6) << param_name(i);
  for (Method m : {Method::kGA, Method::kPSO, Method::kDE}) {
    o.method = m;
    EXPECT_THROW(calibrate(p, o), InputError) << method_name(m);
  }
}

TEST(Calibrate, GlobalProgressRisesToTheBudgetAndDoesNotChangeTheResult) {
  // The progress hook sees the evaluations spent (never more than the budget,
  // never going back) and reaches the budget; the result is the same with it.
  const Problem p = exact_problem();
  MethodOptions o;
  o.method = Method::kDE;
  o.cost = Cost::kJ3;
  o.budget = 20'000;
  const Result plain = calibrate(p, o);
  long last = 0, calls = 0;
  o.progress = [&](long done, long budget, double) {
    EXPECT_EQ(budget, 20'000);
    EXPECT_GE(done, last);
    EXPECT_LE(done, budget);
    last = done;
    ++calls;
  };
  const Result watched = calibrate(p, o);
  EXPECT_GT(calls, 10);
  EXPECT_EQ(last, 20'000);
  for (int i = 0; i < kNumParams; ++i) EXPECT_EQ(watched.geometry[i], plain.geometry[i]) << param_name(i);
}

TEST(RobustLoss, NamesParseAndBadValuesAreOneLineNamingTheValidForms) {
  EXPECT_EQ(parse_loss("cauchy").kind, LossKind::kCauchy);
  EXPECT_EQ(parse_loss("cauchy").scale, 0.0);
  EXPECT_EQ(parse_loss("huber:2e-4").kind, LossKind::kHuber);
  EXPECT_EQ(parse_loss("huber:2e-4").scale, 2e-4);
  EXPECT_FALSE(parse_loss("plain").active());
  for (const char* bad : {"tukey", "huber:-1", "cauchy:0", "cauchy:abc", "huber:1e-4x", "plain:1", "", "cauchy:nan"}) {
    try {
      parse_loss(bad, "--loss");
      FAIL() << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("--loss: ", 0), 0u) << what;
      EXPECT_NE(what.find("cauchy:SCALE"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(RobustLoss, ScaleOutsideItsDocumentedRangeIsRefusedNamingTheRange) {
  // Issue 36.1: cauchy:1e-200 squared underflows to 0 and ended in SIGSEGV.
  for (const char* bad : {"cauchy:1e-200", "huber:1e-13", "cauchy:1e7"}) {
    try {
      parse_loss(bad, "--loss");
      FAIL() << bad << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(std::string("--loss: scale of '") + bad + "': must be a number from 1e-12 to 1e6", 0), 0u)
          << what;
    }
  }
  EXPECT_EQ(parse_loss("cauchy:1e-12").scale, 1e-12);
}

TEST(RobustLoss, ALossThatCannotBeEvaluatedFailsInOneLineNotASignal) {
  // A scale that reaches the solver anyway (a library caller): Ceres' Cauchy
  // loss of scale 1e-200 is NaN everywhere; the calibration fails with
  // gpm::Error (exit 1 on the command line), not InputError, never a crash.
  const Problem p = exact_problem();
  Problem noisy = p;
  for (size_t j = 0; j < noisy.theta_m.size(); ++j) noisy.theta_m[j][j % 3] += 1e-4 * (j % 2 ? 1.0 : -1.0);
  MethodOptions o;
  o.loss = {LossKind::kCauchy, 1e-200};
  try {
    calibrate(noisy, o);
    FAIL() << "a NaN loss gave a result";
  } catch (const InputError& e) {
    FAIL() << "not an input error: " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("the calibration failed"), std::string::npos) << e.what();
  }
}

// Hand-worked: Ceres' CauchyLoss(a) is rho(s) = a^2 log(1 + s / a^2), so the
// robust residual of r = 3a is r~ = sqrt(a^2 log 10), and W = dr~/dr (finite
// differences), for a 1-row and a 2-row group.
TEST(RobustLoss, ResidualMatchesTheClosedFormAndFactorIsItsDerivative) {
  const double a = 2.0;
  const ceres::CauchyLoss rho(a);
  Eigen::VectorXd r(1);
  r << 3.0 * a;
  EXPECT_NEAR(robust_residual(rho, r)[0], std::sqrt(a * a * std::log(10.0)), 1e-12);
  for (const Eigen::VectorXd& g : {Eigen::VectorXd(Eigen::VectorXd::Constant(1, 5.0)),
                                   Eigen::VectorXd(Eigen::Vector2d(1.5, -4.0))}) {
    const Eigen::MatrixXd W = robust_factor(rho, g);
    for (Eigen::Index k = 0; k < g.size(); ++k) {
      const double h = 1e-6;
      Eigen::VectorXd p = g, m = g;
      p[k] += h;
      m[k] -= h;
      const Eigen::VectorXd col = (robust_residual(rho, p) - robust_residual(rho, m)) / (2.0 * h);
      for (Eigen::Index i = 0; i < g.size(); ++i) EXPECT_NEAR(W(i, k), col[i], 1e-8);
    }
  }
  // Inside the scale the loss is the plain square: r~ = r, W = I.
  Eigen::VectorXd small(1);
  small << 1e-6 * a;
  EXPECT_NEAR(robust_residual(rho, small)[0], small[0], 1e-15);
  EXPECT_NEAR(robust_factor(rho, small)(0, 0), 1.0, 1e-9);
}

// 120 noisy samples (sigma 1e-4 rad) of the Table 5 robot, 6 of them with one
// reading off by 0.02-0.05 rad (a slipped reading): the plain ML fit is
// dragged beyond 3 of its sigmas, Cauchy and Huber stay within 3 sigma on
// every parameter, and on clean data their 1-sigma equals the plain one.
TEST(RobustLoss, RecoversTheParametersDespiteOutlierSamplesWherePlainMlDoesNot) {
  Robot actual;
  actual.geometry = table5_actual();
  const double sigma = 1e-4;
  const Samples s = samples_at(actual, workspace_poses(actual, 120, 11), sigma, 5);
  const Problem clean = table5_problem(s, default_free_mask());
  Problem dirty = clean;
  for (int k = 0; k < 6; ++k) dirty.theta_m[static_cast<size_t>(17 * k + 3)][k % 3] += 0.02 + 0.006 * k;
  auto worst = [&](const Result& r) {
    double w = 0.0;
    for (int i = 0; i < kNumParams; ++i)
      if (r.free.test(static_cast<size_t>(i))) w = std::max(w, std::abs(r.geometry[i] - table5_actual()[i]) / r.sigma[static_cast<size_t>(i)]);
    return w;
  };
  MethodOptions o;
  o.encoder_sigma = sigma;
  const Result plain_clean = calibrate(clean, o);
  EXPECT_LT(worst(plain_clean), 3.0);
  const Result plain = calibrate(dirty, o);
  EXPECT_GT(worst(plain), 3.0) << "the outliers do not disturb the plain fit: the test shows nothing";
  for (const char* name : {"cauchy", "huber"}) {
    o.loss = parse_loss(name);
    const Result robust = calibrate(dirty, o);
    EXPECT_LT(worst(robust), 3.0) << name;
    const Result robust_clean = calibrate(clean, o);
    for (int i = 0; i < kNumParams; ++i) {
      if (!robust_clean.free.test(static_cast<size_t>(i))) continue;
      const auto k = static_cast<size_t>(i);
      EXPECT_NEAR(robust_clean.sigma[k] / plain_clean.sigma[k], 1.0, 0.1) << name << " " << param_name(i);
    }
    // Without a noise figure the scale comes from a plain fit's median residual.
    MethodOptions m;
    m.loss = o.loss;
    EXPECT_LT(worst(calibrate(dirty, m)), 3.0) << name << " with the scale from the residuals";
  }
  o.loss = parse_loss("cauchy");
  o.method = Method::kDE;
  o.cost = Cost::kJ3;
  EXPECT_THROW(calibrate(dirty, o), InputError);  // population methods are not robustified
}

}  // namespace
}  // namespace gpm::calib
