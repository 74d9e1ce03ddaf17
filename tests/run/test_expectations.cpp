// Tests of run/expectations.cpp: a parameter's error judged against the
// Cramer-Rao bound and against the 1-sigma the calibration states, each on a
// hand-made outcome whose error is a known multiple of both; each text of
// note_contains looked for in the calibration's notes.
#include "run/expectations.hpp"

#include <gtest/gtest.h>

#include "run/runner.hpp"

namespace gpm::scenario {
namespace {

// An outcome whose only free parameter, la1, is 0.02 mm off, with a CRB of
// 0.005 mm (4 bounds) and a stated 1-sigma of 0.01 mm (2 sigma).
RunOutcome la1_off_by_4_bounds_and_2_sigma() {
  RunOutcome o;
  const int la1 = *param_index("la1");
  const auto u = static_cast<size_t>(la1);
  calib::Result r;
  r.free.reset();
  r.free.set(u);
  r.geometry = o.sim.actual.geometry;
  r.geometry[la1] += 0.02;
  r.sigma.fill(NAN);
  r.sigma[u] = 0.01;
  o.calibration = r;
  o.crb.fill(NAN);
  o.crb[u] = 0.005;
  return o;
}

const Check* find(const std::vector<Check>& checks, const std::string& name) {
  for (const Check& c : checks) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

TEST(Expectations, ErrorIsJudgedAgainstTheStatedSigmaAndTheBoundApart) {
  RunOutcome o = la1_off_by_4_bounds_and_2_sigma();
  o.spec.expect.crb_ratio_max = 3.0;
  o.spec.expect.sigma_ratio_max = 3.0;
  std::vector<Check> checks = evaluate_expectations(o);
  ASSERT_EQ(checks.size(), 2u);
  const Check* crb = find(checks, "crb_ratio.la1");
  const Check* sigma = find(checks, "sigma_ratio.la1");
  ASSERT_TRUE(crb && sigma);
  EXPECT_FALSE(crb->passed);   // 4 bounds > 3
  EXPECT_TRUE(sigma->passed);  // 2 sigma <= 3
  EXPECT_NE(sigma->detail.find("= 2 (limit 3)"), std::string::npos) << sigma->detail;
  o.spec.expect.sigma_ratio_max = 1.5;
  checks = evaluate_expectations(o);
  EXPECT_FALSE(find(checks, "sigma_ratio.la1")->passed);
}

TEST(Expectations, UnknownStatedSigmaFails) {
  RunOutcome o = la1_off_by_4_bounds_and_2_sigma();
  o.calibration->sigma.fill(NAN);
  o.spec.expect.sigma_ratio_max = 100.0;
  const std::vector<Check> checks = evaluate_expectations(o);
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_FALSE(checks[0].passed);
}

TEST(Expectations, NoCalibrationFailsTheStatedSigmaCheck) {
  RunOutcome o;
  o.spec.expect.sigma_ratio_max = 3.0;
  const std::vector<Check> checks = evaluate_expectations(o);
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].name, "calibration");
  EXPECT_FALSE(checks[0].passed);
}

TEST(Expectations, EachNoteTextIsLookedForInTheNotes) {
  RunOutcome o = la1_off_by_4_bounds_and_2_sigma();
  o.calibration->notes = {"the reducer's error carried: it explains 3 % of the misfit", "backlash of joint 2"};
  o.spec.expect.note_contains = {"explains 3 %", "backlash of joint"};
  std::vector<Check> checks = evaluate_expectations(o);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_TRUE(checks[0].passed && checks[1].passed);
  o.spec.expect.note_contains = {"explains 3 %", "cogging"};
  checks = evaluate_expectations(o);
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_TRUE(checks[0].passed);
  EXPECT_FALSE(checks[1].passed);
  EXPECT_EQ(checks[1].detail, "no note contains 'cogging'");
}

}  // namespace
}  // namespace gpm::scenario
