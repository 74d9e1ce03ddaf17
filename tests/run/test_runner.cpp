// Tests of run/runner.cpp (with expectations.cpp and run_report.cpp):
// a small run end to end in-process, failing and refused expectations, and
// outputs written all or nothing.
#include "run/runner.hpp"
#include "models/data_dir.hpp"

#include <filesystem>

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm::scenario {
namespace {

namespace fs = std::filesystem;
const std::string kBase = gpm::scenarios_dir();

std::string scenario(const std::string& calibration, const std::string& expect) {
  return "robot: robots/table5_frame.yaml\nseed: 3\n"
         "actual: {geometry: {xa3: 433.5, ya3: 499.4, la1: 244.1, lb2: 244.2, dth1: 0.01, dth3: -0.01}}\n"
         "encoder: {bits: 0}\n"
         "sampling: {pattern: disc, radius: 130, count: 20, move_speed_mm_s: 250}\n"
         "compensation: {count: 4, path: {radius: 30, period_s: 2, revolutions: 0.25}}\n" +
         calibration + expect;
}

TEST(Runner, CalibratesCompensatesAndPasses) {
  const RunSpec spec = parse_run_spec(scenario("calibration: {cost: ml}\n",
                                               "expect: {error: {base_mm: 1.0e-3, link_mm: 1.0e-3, offset_rad: 1.0e-5}, "
                                               "improvement_min: 100}\n"),
                                      "t.yaml", kBase);
  const RunOutcome o = run_scenario(spec, "t.yaml");
  ASSERT_TRUE(o.calibration);
  EXPECT_TRUE(o.passed());
  for (const Check& c : o.checks) EXPECT_TRUE(c.passed) << c.name << ": " << c.detail;
  ASSERT_TRUE(o.before && o.after);
  EXPECT_LT(o.after->static_rms_um, 1.0);
  EXPECT_EQ(o.residual_urad.size(), 20u);
  // The bound is finite for the 11 free parameters and NaN for the 4 fixed.
  EXPECT_TRUE(std::isnan(o.crb[kXa1]));
  EXPECT_EQ(o.crb[kLb3], 0.0);  // ideal encoders: a zero bound

  const fs::path dir = fs::temp_directory_path() / "gpm_test_runner";
  fs::remove_all(dir);
  write_run(o, dir.string());
  for (const char* f : {"samples.csv", "trajectory.csv", "actual.yaml", "model.xml", "calibration.yaml",
                        "report.md", "report.html", "layout.svg", "errors_mm.svg", "tracking.svg"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string().starts_with(".gpm") ? 100 : 1;
  EXPECT_LT(entries, 100u) << "temporary folder left behind";
  fs::remove_all(dir);
}

TEST(Runner, FailedExpectationIsReported) {
  const RunSpec spec = parse_run_spec(scenario("outputs: {compensation: false}\n", "expect: {kmrmse_mm_max: 1.0e-12, cost_max: 1.0e-40}\n"),
                                      "t.yaml", kBase);
  const RunOutcome o = run_scenario(spec, "t.yaml");
  EXPECT_FALSE(o.passed());
  bool cost_failed = false;
  for (const Check& c : o.checks) cost_failed = cost_failed || (c.name == "cost" && !c.passed);
  EXPECT_TRUE(cost_failed);
}

TEST(Runner, RankDeficientGaugeRefusedOrExpected) {
  const std::string calib12 = "calibration: {cost: j3, fix: [xa1, ya1, ya2]}\noutputs: {compensation: false}\n";
  EXPECT_THROW(run_scenario(parse_run_spec(scenario(calib12, ""), "t.yaml", kBase), "t.yaml"), InputError);
  const RunOutcome o = run_scenario(
      parse_run_spec(scenario(calib12, "expect: {refused_contains: \"rank 11 of 12\"}\n"), "t.yaml", kBase), "t.yaml");
  ASSERT_TRUE(o.refused);
  EXPECT_TRUE(o.passed());
}

TEST(Runner, UnwritableOutputLeavesNothing) {
  const RunSpec spec = parse_run_spec(scenario("outputs: {compensation: false}\n", ""), "t.yaml", kBase);
  const RunOutcome o = run_scenario(spec, "t.yaml");
  EXPECT_THROW(write_run(o, "/proc/gpm-not-writable/x"), InputError);
}

}  // namespace
}  // namespace gpm::scenario
