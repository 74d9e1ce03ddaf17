// Tests of run/calibration_procedure.cpp: gpm run's calibration of a short
// on-the-fly scenario made again from its samples.csv alone (the readings,
// times and drive torques, and the robot file's data sheet, as gpm calibrate
// does) gives the same result to the last bit; samples without times or
// torques get the static fit and its model test; missing inputs refused.
#include "run/calibration_procedure.hpp"

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/runner.hpp"
#include "sim/simulate.hpp"

namespace gpm::scenario {
namespace {

const std::string kSmall = std::string(GPM_SOURCE_DIR) + "/tests/fixtures/on_the_fly_small.yaml";

// The fixture's run, made once for every test of this file.
const RunOutcome& small_run() {
  static const RunOutcome o = run_scenario(load_run_spec(kSmall), kSmall);
  return o;
}

// What gpm calibrate runs on a samples file (app/cmd_calibrate.cpp at its
// defaults): the robot file's data sheet, no scenario.
CalibrationOutcome calibrate_file(const Samples& s, bool static_model = false) {
  const Robot robot = load_robot(std::string(GPM_SOURCE_DIR) + "/models/gpm2002.yaml");
  calib::MethodOptions mo;
  if (s.has_xy) mo.true_xy = &s.xy;
  const FileProcedure p = samples_file_procedure(s, robot, robot.geometry, ~parse_param_list("xa1,ya1,xa2,ya2", "--fix"),
                                                 mo, std::nullopt, static_model);
  EXPECT_EQ(p.options.in_motion, !static_model && taken_on_the_fly(s));
  return calibrate_samples(sample_series(s), p.inputs, p.options);
}

TEST(CalibrationProcedure, SamplesFileGivesTheRunsResultBitForBit) {
  const RunOutcome& o = small_run();
  ASSERT_TRUE(o.calibration && o.model_test && o.in_motion);
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  ASSERT_TRUE(taken_on_the_fly(s));
  const CalibrationOutcome c = calibrate_file(s);
  ASSERT_TRUE(c.with_effects && c.model_test);
  for (int i = 0; i < kNumParams; ++i) {
    EXPECT_EQ(c.result.geometry[i], o.calibration->geometry[i]) << param_name(i);
    const double a = c.result.sigma[static_cast<size_t>(i)], b = o.calibration->sigma[static_cast<size_t>(i)];
    EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << param_name(i);
  }
  EXPECT_EQ(c.model_test->chi2, o.model_test->chi2);
  EXPECT_EQ(c.model_test->dof, o.model_test->dof);
  EXPECT_EQ(c.model_test->passed, o.model_test->passed);
  EXPECT_EQ(c.result.notes, o.calibration->notes);
  EXPECT_EQ(c.fit.nu, o.motion_nu);
}

TEST(CalibrationProcedure, WithoutTimesAndTorquesTheStaticFitAndItsModelTest) {
  const RunOutcome& o = small_run();
  Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  s.t.clear(), s.tau.clear(), s.tau_last.clear(), s.tau_between.clear();
  EXPECT_FALSE(taken_on_the_fly(s));
  const CalibrationOutcome c = calibrate_file(s);
  EXPECT_FALSE(c.with_effects);
  ASSERT_TRUE(c.model_test);
  // The static model leaves the twist out: the readings disagree with it.
  EXPECT_FALSE(c.model_test->passed);
  EXPECT_NE(model_test_line(*c.model_test, true).find("the stated 1-sigma understates the error"), std::string::npos);
  EXPECT_NE(model_test_yaml(*c.model_test, 2).find("  model_test_chi2: "), std::string::npos);
}

TEST(CalibrationProcedure, MotionModelWithoutTimesOrTorquesRefused) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  const Robot robot = load_robot(std::string(GPM_SOURCE_DIR) + "/models/gpm2002.yaml");
  const FileProcedure p = samples_file_procedure(s, robot, robot.geometry, ~parse_param_list("xa1,ya1,xa2,ya2", "--fix"),
                                                 {}, std::nullopt, false);
  const CalibrationInputs& in = p.inputs;
  const ProcedureOptions& po = p.options;
  SampleSeries no_t = sample_series(s), no_tau = sample_series(s), short_t = sample_series(s);
  no_t.t_s.clear();
  no_tau.tau.clear();
  short_t.t_s.pop_back();
  EXPECT_THROW(calibrate_samples(no_t, in, po), InputError);
  EXPECT_THROW(calibrate_samples(no_tau, in, po), InputError);
  EXPECT_THROW(calibrate_samples(short_t, in, po), InputError);
}

}  // namespace
}  // namespace gpm::scenario
