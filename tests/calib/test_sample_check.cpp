// Tests of calib/sample_check.cpp: counts, non-finite readings, circles that
// do not meet (named by the caller's label), tolerance for an approximate start.
#include "calib/sample_check.hpp"

#include <limits>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

Problem problem(int n) {
  Robot r;
  r.geometry = table5_actual();
  Problem p;
  p.theta_m = samples_at(r, disc_poses(r, n, r.home, 100.0, 8)).theta_m;
  p.start = Geometry::gpm2002_nominal();  // offsets and lengths off by up to 0.6 mm / 0.01 rad
  p.free = default_free_mask();
  return p;
}

std::string message(const Problem& p, const std::vector<std::string>& labels = {}) {
  try {
    check_samples(p, labels);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(SampleCheck, GoodSamplesFromAnApproximateStartPass) { EXPECT_EQ(message(problem(30)), "accepted"); }

TEST(SampleCheck, FewerSamplesThanFreeParameters) {
  EXPECT_NE(message(problem(10)).find("10 samples for 11 free parameters"), std::string::npos);
  Problem p = problem(30);
  p.free.reset();
  EXPECT_NE(message(p).find("nothing to estimate"), std::string::npos);
}

TEST(SampleCheck, NonFiniteReading) {
  Problem p = problem(30);
  p.theta_m[3][2] = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(p).find("sample 3: readings must be finite"), std::string::npos);
}

TEST(SampleCheck, CirclesThatDoNotMeetAreNamedByLabel) {
  Problem p = problem(30);
  p.theta_m[12][0] += 1.5;
  std::vector<std::string> labels;
  for (int j = 0; j < 30; ++j) labels.push_back("s.csv:" + std::to_string(j + 2));
  const std::string m = message(p, labels);
  EXPECT_NE(m.find("s.csv:14: the passive circles of chains 1 and"), std::string::npos) << m;
}

TEST(SampleCheck, ConstantReadingColumnRefused) {
  // Issue 36.5: a joint that never moved calibrated to "converged" with la2 ~ 1e-10.
  Problem p = problem(30);
  for (auto& t : p.theta_m) t[0] = p.theta_m[0][0];
  EXPECT_NE(message(p).find("theta_m1 is "), std::string::npos) << message(p);
  EXPECT_NE(message(p).find("in all 30 samples: joint 1 never moved"), std::string::npos);
}

}  // namespace
}  // namespace gpm::calib
