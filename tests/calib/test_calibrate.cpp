// Tests of calib/calibrate.cpp (and the Method names of calib/problem.hpp):
// every method name round-trips, an unknown one is refused in one line that
// names the valid values, LM through the entry point is calibrate_lm, a
// global method recovers the true values of exact data, and ML is refused
// for a population method.
#include "calib/calibrate.hpp"

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

}  // namespace
}  // namespace gpm::calib
