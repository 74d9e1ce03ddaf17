// Tests of run/offsets_first.cpp (the encoder offsets learnt from the first
// samples of a path) and of its use by run/runner.cpp: a robot whose first
// pass of the main job's path ends early is sampled a second time, planned
// with those offsets, and calibrated; the offsets stage keeps the robot that
// left its plan furthest within the watch's bound.
#include "run/offsets_first.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "calib/lm.hpp"
#include "calib/reading_model.hpp"
#include "hw/safety_limits.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/pose_layouts.hpp"
#include "models/samples.hpp"
#include "run/calibration_inputs.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"
#include "run/sampling_design.hpp"
#include "run/twin_hardware.hpp"
#include "tests/models/temp_files.hpp"
#include "tests/run/tracking_rows.hpp"

namespace gpm::scenario {
namespace {

// The main job on the robot of `seed`, as dir/robot.yaml (a file the twin
// backend can load).
RunSpec main_job_robot(const gpm::test::TempDir& dir, int seed, const std::string& deviation_mm = "10") {
  std::stringstream main_text;
  main_text << std::ifstream(gpm::scenarios_dir() + "/main.yaml").rdbuf();
  std::string text = main_text.str();
  text.replace(text.find("seed: 2026"), 10, "seed: " + std::to_string(seed));
  text.replace(text.find("deviation_mm: 10"), 16, "deviation_mm: " + deviation_mm);
  text.replace(text.find("robot: ../models/"), 17, "robot: " + gpm::models_dir() + "/");
  std::ofstream(dir / "robot.yaml") << text;
  return load_run_spec(dir / "robot.yaml");
}

// spec sampled through dir/twin.yaml: a twin backend of dir/robot.yaml with the twin's own limits.
void through_twin_backend(const gpm::test::TempDir& dir, RunSpec& spec) {
  std::ofstream(dir / "twin.yaml") << "backend: twin\nrate_hz: 4000\ncontroller: " << gpm::models_dir()
                                   << "/gpm2002.yaml\njoint_modes: [torque_off, position, position]\ntwin: {scenario: "
                                   << (dir / "robot.yaml") << "}\nsafety:\n"
                                   << hw::safety_limits_to_yaml(twin_safety_limits(spec.sim, spec.sim.controller), 2);
  spec.hardware = dir / "twin.yaml";
}

// Noise-free readings of `actual` at poses on two circles round home, one
// per 10 ms (each updates the filter).
std::vector<sim::SampleRecord> readings_of(const Geometry& actual, const Eigen::Vector2d& home) {
  std::vector<sim::SampleRecord> out;
  for (double radius : {30.0, 60.0})
    for (const Eigen::Vector2d& p : circle_points(home, radius, 50)) {
      sim::SampleRecord r;
      r.theta_m = readings_from_active(actual, inverse_kinematics(actual, p).theta_a);
      r.t_s = 0.01 * static_cast<double>(out.size());
      out.push_back(r);
    }
  return out;
}

// Noise-free readings of `actual` along a 40 mm arc from home (one corner of
// the workspace, as the first second of a path sees it), one per 10 ms.
std::vector<sim::SampleRecord> arc_readings_of(const Geometry& actual, const Eigen::Vector2d& home) {
  std::vector<sim::SampleRecord> out;
  for (int k = 0; k < 100; ++k) {
    const double a = 1.5 * k / 99.0;
    const Eigen::Vector2d p = home + Eigen::Vector2d(40.0 * std::sin(a), 25.0 * (1.0 - std::cos(a)));
    sim::SampleRecord r;
    r.theta_m = readings_from_active(actual, inverse_kinematics(actual, p).theta_a);
    r.t_s = 0.01 * k;
    out.push_back(r);
  }
  return out;
}

// The offsets are what the readings of a robot that differs only in them
// show: learnt to within a fifth of their change (0.5 mm at a 244 mm link),
// with a 1-sigma far below the prior's that covers the error; nothing but the
// offsets changes.
TEST(OffsetsFirst, LearnsTheOffsetsOfARobotThatDiffersOnlyInThem) {
  const Robot robot;
  Geometry actual = robot.geometry;
  const Eigen::Vector3d dth_change(0.012, -0.021, 0.017);
  for (int i = 0; i < 3; ++i) actual[dth(i)] += dth_change[i];
  const ModelTolerance prior;
  const OffsetsEstimate fit = offsets_learnt(robot.geometry, readings_of(actual, robot.home), prior);
  for (int k = 0; k < kNumParams; ++k) {
    if (is_offset(k)) continue;
    EXPECT_EQ(fit.geometry[k], robot.geometry[k]) << param_name(k);
  }
  for (int i = 0; i < 3; ++i) {
    const double error = std::abs(fit.geometry[dth(i)] - actual[dth(i)]);
    std::printf("dth%d: change %.4f rad, error %.2e rad, 1-sigma %.2e rad\n", i + 1, dth_change[i], error,
                fit.sigma_rad[static_cast<std::size_t>(i)]);
    EXPECT_LT(error, 0.2 * std::abs(dth_change[i])) << i;
    EXPECT_LT(fit.sigma_rad[static_cast<std::size_t>(i)], 0.5 * prior.offset_rad) << i;
    EXPECT_LT(error, 3.0 * fit.sigma_rad[static_cast<std::size_t>(i)]) << i;
  }
}

// A robot whose links and third base are off too, seen in one corner: a
// fit of the offsets alone (Levenberg-Marquardt on the same ML residual,
// every other parameter held) loads the links' errors onto the offsets; the
// learnt estimate, the links free within their prior, moves the offsets
// less far from the truth.
TEST(OffsetsFirst, ALinkErrorIsNotLoadedOntoTheOffsets) {
  const Robot robot;
  Geometry actual = robot.geometry;
  const Eigen::Vector3d dth_change(0.012, -0.021, 0.017);
  for (int i = 0; i < 3; ++i) actual[dth(i)] += dth_change[i];
  actual[la(1)] += 0.8;
  actual[lb(2)] -= 0.7;
  actual[kXa3] += 0.6;
  const std::vector<sim::SampleRecord> samples = arc_readings_of(actual, robot.home);
  const OffsetsEstimate learnt = offsets_learnt(robot.geometry, samples, ModelTolerance{});
  calib::Problem alone;
  alone.start = robot.geometry;
  for (int i = 0; i < 3; ++i) alone.free.set(static_cast<std::size_t>(dth(i)));
  for (const sim::SampleRecord& r : samples) alone.theta_m.push_back(r.theta_m);
  calib::LmOptions options;
  options.cost = calib::Cost::kML;
  const calib::Result fit = calib::calibrate_lm(alone, options);
  double learnt_error = 0.0, alone_error = 0.0;
  for (int i = 0; i < 3; ++i) {
    learnt_error = std::max(learnt_error, std::abs(learnt.geometry[dth(i)] - actual[dth(i)]));
    alone_error = std::max(alone_error, std::abs(fit.geometry[dth(i)] - actual[dth(i)]));
  }
  std::printf("worst offset error: learnt %.2e rad, offsets alone %.2e rad (the change %.3f rad)\n", learnt_error,
              alone_error, dth_change.cwiseAbs().maxCoeff());
  EXPECT_LT(learnt_error, alone_error);
  EXPECT_LT(learnt_error, 0.5 * dth_change.cwiseAbs().maxCoeff());
}

TEST(OffsetsFirst, RefusesTooFewSamples) {
  const Robot robot;
  std::vector<sim::SampleRecord> few = readings_of(robot.geometry, robot.home);
  few.resize(kMinFirstPassSamples - 1);
  EXPECT_THROW(offsets_learnt(robot.geometry, few, ModelTolerance{}), InputError);
}

// The main job on the robot of seed 7011 (its offsets move 0.032, 0.026,
// 0.012 rad from the nominal's, dth1 beyond the data sheet's tolerance of
// 0.02): the first pass of its path ends early (past 0.7 of
// the 20 mm tracking watch, sampling/test_sampling_design.cpp); the second,
// planned with the offsets of the samples it kept, runs to its end within the
// watch's bound, and the calibration from it places the tool better than the
// nominal model by two orders of magnitude.
TEST(OffsetsFirst, APathThatEndedEarlyIsSampledAgainAndCalibrated) {
  RunSpec spec = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
  spec.sim.seed = 7011;
  const RunOutcome o = run_scenario(spec, "main.yaml");
  ASSERT_TRUE(o.first_pass.has_value());
  EXPECT_NE(o.first_pass->why.find("retraced its path"), std::string::npos) << o.first_pass->why;
  EXPECT_GE(o.first_pass->samples, static_cast<std::size_t>(kMinFirstPassSamples));
  const double deviation = gpm::test::worst_row_deviation_mm(o.sim.log.rows);
  ASSERT_TRUE(o.calibration.has_value());
  ASSERT_TRUE(o.before && o.after);
  std::printf("seed 7011: first pass %zu samples, %.2f s; offsets moved %.4f %.4f %.4f rad; second pass within "
              "%.2f mm of its plan; static RMS nominal %.1f um, calibrated %.2f um, robot time %.2f s\n",
              o.first_pass->samples, o.first_pass->robot_time_s, o.first_pass->offsets_change_rad[0],
              o.first_pass->offsets_change_rad[1], o.first_pass->offsets_change_rad[2], deviation,
              o.before->static_rms_um, o.after->static_rms_um, o.sim.sampling_s);
  EXPECT_LE(deviation, 20.0);
  // The run's plan deviation is the worst of both passes: the first, sampled
  // alone here (it ends early as in the run), and the second.
  double first_pass_deviation = 0.0;
  RunSpec designed = spec;
  design_sampling(designed.sim, ~designed.calibration.fixed, effective_sigma(designed.sim));
  try {
    sample_in_process(designed);
  } catch (const sim::TrackingStop& stop) {
    first_pass_deviation = gpm::test::worst_row_deviation_mm(stop.rows);
  }
  EXPECT_GT(first_pass_deviation, 0.0);
  EXPECT_EQ(o.plan_deviation_mm, std::max(first_pass_deviation, deviation));
  EXPECT_GT(o.first_pass->robot_time_s, 0.0);
  EXPECT_GT(o.sim.sampling_s, o.first_pass->robot_time_s);
  EXPECT_LT(o.after->static_rms_um * 100.0, o.before->static_rms_um);
}

// The same robot through the hardware interface (a twin backend of the
// scenario of seed 7011, the twin's own limits): the first pass's samples
// stay in samples_first_pass.csv, the second pass records into samples.csv,
// the calibration takes those; a resumed session plans the same second pass
// from the first pass's file and gives the same calibration to the last bit.
TEST(OffsetsFirst, ThroughTheHardwareInterfaceTheFirstPassIsKeptAndResumable) {
  const gpm::test::TempDir dir("offsets_first");
  RunSpec spec = main_job_robot(dir, 7011);
  through_twin_backend(dir, spec);
  spec.compensation.reset();
  const RunOutcome o = run_scenario(spec, "robot.yaml", {}, dir / "samples.csv");
  ASSERT_TRUE(o.first_pass.has_value());
  ASSERT_TRUE(o.calibration.has_value());
  EXPECT_EQ(o.first_pass->why.find("samples kept in"), std::string::npos) << o.first_pass->why;
  EXPECT_EQ(read_samples_csv(dir / "samples_first_pass.csv").size(), o.first_pass->samples);
  EXPECT_EQ(read_samples_csv(dir / "samples.csv").size(), o.sim.samples.size());
  EXPECT_GT(o.sim.samples.size(), 5000u);
  EXPECT_GT(o.sim.sampling_s, o.first_pass->robot_time_s + 5.0);
  const calib::PositioningError p = calib::positioning_error(o.sim.actual, o.calibrated,
                                                             calib::WorkspaceDisc{o.nominal.home}, o.calibration->covariance);
  std::printf("through the twin backend: first pass %zu samples, %.2f s; second pass %zu samples; positioning RMS "
              "%.2f um (stated %.2f um)\n",
              o.first_pass->samples, o.first_pass->robot_time_s, o.sim.samples.size(), p.rms_um, p.stated_sigma_rms_um);
  // This robot (seed 7011): 2.36 um against a stated 3.17 measured (with the
  // poses for the positioning; seed 10009, this test's robot before them,
  // no longer leaves its plan far enough to end the first pass early).
  EXPECT_LE(p.rms_um, 4.0 * p.stated_sigma_rms_um);
  RunSpec again = spec;
  again.hardware_resume = true;
  const RunOutcome resumed = run_scenario(again, "robot.yaml", {}, dir / "samples.csv");
  ASSERT_TRUE(resumed.first_pass && resumed.calibration);
  EXPECT_EQ(resumed.first_pass->samples, o.first_pass->samples);
  for (int k = 0; k < kNumParams; ++k)
    EXPECT_EQ(resumed.calibration->geometry[k], o.calibration->geometry[k]) << param_name(k);
}

// The robot of seed 7023 leaves the main job's plan designed with a
// deviation margin at the tracking watch's 20 mm bound (the main job's was
// that until it became 10 mm) by 24 mm, while the watch (which sees only the
// deviation along the torque-off chain) reads less than its early end. With
// an offsets stage of 1 s its offsets are learnt first and the whole path
// stays within the bound; through the twin backend the stage's samples are
// kept in samples_first_pass.csv and the run takes the same samples.
TEST(OffsetsFirst, TheOffsetsStageKeepsARobotThatLeftItsPlanWithinTheBound) {
  const gpm::test::TempDir dir("offsets_stage");
  RunSpec spec = main_job_robot(dir, 7023, "20");
  spec.compensation.reset();
  const RunOutcome without = run_scenario(spec, "robot.yaml");
  spec.sim.sampling->offsets_first_s = 1.0;
  const RunOutcome with = run_scenario(spec, "robot.yaml");
  std::printf("seed 7023: plan deviation %.2f mm without the stage (robot time %.2f s), %.2f mm with it (%.2f s)\n",
              without.plan_deviation_mm, without.sim.sampling_s, with.plan_deviation_mm, with.sim.sampling_s);
  EXPECT_GT(without.plan_deviation_mm, 20.0);
  EXPECT_LE(with.plan_deviation_mm, 20.0);
  ASSERT_TRUE(with.first_pass.has_value());
  EXPECT_TRUE(with.first_pass->planned);
  EXPECT_EQ(static_cast<long>(with.first_pass->samples), std::lround(1.0 / 0.001) + 1);  // 1 kHz samples
  EXPECT_LE(with.sim.sampling_s, 15.0);
  ASSERT_TRUE(with.calibration.has_value());

  through_twin_backend(dir, spec);
  const RunOutcome through = run_scenario(spec, "robot.yaml", {}, dir / "samples.csv");
  ASSERT_TRUE(through.first_pass.has_value());
  EXPECT_TRUE(through.first_pass->planned);
  EXPECT_EQ(read_samples_csv(dir / "samples_first_pass.csv").size(), with.first_pass->samples);
  EXPECT_EQ(read_samples_csv(dir / "samples.csv").size(), with.sim.samples.size());
}

// A stage as long as the path is no stage: refused, naming the key, before anything moves.
TEST(OffsetsFirst, AStageAsLongAsThePathIsRefusedBeforeAnythingMoves) {
  RunSpec spec = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
  spec.sim.sampling->offsets_first_s = 60.0;
  try {
    run_scenario(spec, "main.yaml");
    ADD_FAILURE() << "a 60 s stage of a 9 s path ran";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sampling.offsets_first_s: 60 s is not shorter than the excitation path"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace gpm::scenario
