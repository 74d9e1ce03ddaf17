// Tests of run/runner.cpp (with expectations.cpp and run_report.cpp):
// a small run end to end in-process, failing and refused expectations, and
// outputs written all or nothing; gpm design's pose list as the sampling of a
// scenario and as a poses file of gpm sample; bad sampling requests refused
// before the robot moves; in process is the main procedure through the
// hardware interface (twin backend, sample plugin) to the last bit.
#include "run/runner.hpp"
#include "models/data_dir.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "calib/excitation/excitation.hpp"
#include "calib/excitation/pose_list.hpp"
#include "calib/positioning_error.hpp"
#include "models/samples.hpp"
#include "hw/procedures/session_plan.hpp"
#include "hw/safety_limits.hpp"
#include "run/twin_hardware.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"

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
                        "report.md", "report.html", "layout.svg", "errors_mm.svg", "tracking.svg",
                        "positioning.svg", "positioning.csv"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.path().filename().string().starts_with(".gpm") ? 100 : 1;
  EXPECT_LT(entries, 100u) << "temporary folder left behind";
  fs::remove_all(dir);
}

TEST(Runner, TheBudgetOfLmIsItsIterations) {
  // From the nominal start LM needs several iterations on this robot; a
  // budget of one stops it after one (and says so), the default does not.
  const auto run = [](const std::string& calibration) {
    return run_scenario(parse_run_spec(scenario(calibration, ""), "t.yaml", kBase), "t.yaml");
  };
  const RunOutcome one = run("calibration: {cost: ml, method: lm, budget: 1}\n");
  const RunOutcome free = run("calibration: {cost: ml, method: lm}\n");
  ASSERT_TRUE(one.calibration && free.calibration);
  EXPECT_LE(one.calibration->iterations, 2);  // Ceres counts its one step and the check that ends the solve
  EXPECT_FALSE(one.calibration->converged);
  EXPECT_GT(free.calibration->iterations, 1);
  EXPECT_TRUE(free.calibration->converged);
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

// The file `gpm design --count 14 --grid-step 20 --guard 12` writes
// (calib/excitation/pose_list.hpp): the 12 mm guard keeps the excitation path
// through the poses inside the limits too (the default 2 mm suits stop-and-go).
std::string design_file_text() {
  const Robot nominal = load_robot(gpm::models_dir() + "/gpm2002.yaml");
  calib::excitation::DesignOptions d;
  d.count = 14;
  d.grid_step_mm = 20.0;
  d.guard.reach_mm = 12.0;
  return calib::excitation::pose_list_yaml(calib::excitation::design_poses(nominal, d).poses, "gpm design: test");
}

// A perturbed robot with ideal encoders calibrated from the design's block
// pasted as the scenario's sampling (stop-and-go list, and on the fly).
std::string with_design(const std::string& design) {
  return design + "robot: ../models/gpm2002.yaml\nseed: 3\n"
                  "actual: {geometry: {xa3: 433.5, ya3: 499.4, la1: 244.1, lb2: 244.2, dth1: 0.01, dth3: -0.01}}\n"
                  "encoder: {bits: 0}\ncalibration: {cost: ml}\noutputs: {compensation: false}\n";
}

TEST(Runner, DesignOutputIsTheSamplingOfAScenarioAndAPosesFileOfGpmSample) {
  const std::string text = design_file_text();
  const YAML::Node design = YAML::Load(text);
  std::vector<Eigen::Vector2d> poses;
  for (const YAML::Node& p : design["sampling"]["poses"]) poses.emplace_back(p[0].as<double>(), p[1].as<double>());
  ASSERT_EQ(poses.size(), 14u);

  // gpm sample --poses reads it as is (hw/procedures/session_plan.hpp).
  const fs::path file = fs::temp_directory_path() / "gpm_test_runner_design.yaml";
  { std::ofstream(file) << text; }
  const hw::SessionPlan plan = hw::load_poses_plan(file.string());
  fs::remove(file);
  EXPECT_EQ(plan.poses, poses);

  // As the sampling of a scenario: stop-and-go, and the same poses on the
  // fly. gpm design knows the robot's limits, not the path margin: on the fly
  // its poses are refused with the default margin (a pose within the
  // model's tolerance of chain 1's reach), and run with a margin stated
  // without the tolerance.
  std::string fly = text;
  fly.replace(fly.find("pattern: list"), 13, "pattern: trajectory\n  count: 14");
  try {
    run_scenario(parse_run_spec(with_design(fly), "t.yaml", kBase), "t.yaml");
    ADD_FAILURE() << "the default margin accepted poses near the reach";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("breaks the margin"), std::string::npos) << e.what();
  }
  fly.replace(fly.find("count: 14"), 9,
              "count: 14\n  path_margin: {reach_mm: 2, tolerance: {base_mm: 0, link_mm: 0, offset_rad: 0}}");
  for (const std::string& t : {text, fly}) {
    const RunSpec spec = parse_run_spec(with_design(t), "t.yaml", kBase);
    const RunOutcome o = run_scenario(spec, "t.yaml");
    EXPECT_EQ(o.sim.samples.size() > 14, t == fly);  // on the fly: many readings per pose
    ASSERT_TRUE(o.calibration);
    EXPECT_NEAR(o.calibration->geometry[kLa1], 244.1, 1e-3);
    EXPECT_NEAR(o.calibration->geometry[kDth3], -0.01, 1e-5);
  }
}

// Each refused with one line naming the key before anything moves (the
// runner throws before the twin is built).
TEST(Runner, BadSamplingRequestsAreRefusedBeforeTheRobotMoves) {
  auto refused = [](const std::string& sampling, const std::string& contains) {
    try {
      run_scenario(parse_run_spec(with_design(sampling), "t.yaml", kBase), "t.yaml");
      ADD_FAILURE() << sampling << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(contains), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  // A designed count below the 11 free parameters.
  EXPECT_THROW(parse_run_spec(with_design("sampling: {pattern: designed, count: 8}\n"), "t.yaml", kBase), InputError);
  // Designed poses given, fewer than the free parameters.
  refused("sampling: {pattern: trajectory, count: 11, poses: [[216.5, 250], [236.5, 260], [196.5, 240], [230, 225]]}\n",
          "4 designed poses cannot determine 11 free parameters");
  // Poses inside the robot's limits but not its path margin: on an arc 484 mm
  // from A2 (reach 488), inside sampling.path_margin.reach_mm.
  refused("sampling: {pattern: trajectory, count: 11, poses: [[267.462, 454.811], [228.453, 438.653], [191.0, 419.156], "
          "[155.389, 396.47], [121.891, 370.766], [90.76, 342.24], [62.234, 311.109], [216.5, 250], [236.5, 260], "
          "[196.5, 240], [230, 225]]}\n",
          "sampling: excitation path refused before anything moves: pose 0 (267.462, 454.811) breaks the margin");
}

// The main job's procedure through the hardware interface on the twin
// backend (hw/examples/twin_main.yaml: the main job's robot, commanded at the
// twin drives' own 4 kHz, a sample every 1 ms as in process): the excitation
// path sampled on the fly with the drive torques and read times, the
// calibration on the fly, robot time within 15 s, and the calibrated model's
// positioning error over the workspace within 1.5x the in-process run's and
// within its stated 1-sigma (the goal is 1.2x: docs/PROCEDURES.md has the measurement).
// A hardware file of the main job's twin with the limits of the in-process
// twin (run/twin_hardware.hpp), backend twin or the sample plugin's card.
std::string twin_hardware_file(const RunSpec& spec, const std::string& backend) {
  const std::string root = fs::path(kBase).parent_path().string();
  std::string text = "backend: " + backend + "\nrate_hz: 4000\ncontroller: " + root +
                     "/models/gpm2002.yaml\njoint_modes: [torque_off, position, position]\n";
  if (backend == "twin") text += "twin: {scenario: " + root + "/scenarios/main.yaml}\n";
#ifdef GPM_MOTION_CARD_PLUGIN
  if (backend == "plugin")
    text += std::string("plugin:\n  library: ") + GPM_MOTION_CARD_PLUGIN + "\n  config:\n    scenario: " + root +
            "/scenarios/main.yaml\n    clock_offset_s: 1000.0\n";
#endif
  return text + "safety:\n" + hw::safety_limits_to_yaml(twin_safety_limits(spec.sim, spec.sim.controller), 2);
}

// The same samples to the last bit: readings, torques, times.
void expect_same_samples(const RunOutcome& a, const RunOutcome& b) {
  ASSERT_EQ(a.sim.samples.size(), b.sim.samples.size());
  for (std::size_t k = 0; k < a.sim.samples.size(); ++k) {
    const sim::SampleRecord &x = a.sim.samples[k], &y = b.sim.samples[k];
    ASSERT_EQ(x.id, y.id);
    ASSERT_TRUE(x.theta_m == y.theta_m && x.target == y.target && x.tau_last == y.tau_last &&
                x.tau_between == y.tau_between && x.t_s == y.t_s)
        << "sample " << k;
  }
  for (int i = 0; i < kNumParams; ++i) EXPECT_EQ(a.calibration->geometry[i], b.calibration->geometry[i]) << param_name(i);
}

TEST(Runner, InProcessIsTheTwinBackendThroughTheHardwareInterfaceBitForBit) {
  // One operation loop: gpm run in process drives the twin through the twin
  // backend behind the safety supervisor with the hw procedure, so a hardware
  // file of that twin with the same limits gives the same samples to the last bit.
  RunSpec spec = load_run_spec(kBase + "/main.yaml");
  spec.compensation.reset();  // the accuracy test is the same twin either way
  spec.expect = {};
  const RunOutcome twin = run_scenario(spec, "main.yaml");
  const fs::path dir = fs::temp_directory_path() / "gpm_test_runner_hw";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "twin.yaml") << twin_hardware_file(spec, "twin");
  RunSpec on_hw = spec;
  on_hw.hardware = (dir / "twin.yaml").string();
  const RunOutcome hw = run_scenario(on_hw, "main.yaml", {}, (dir / "samples.csv").string());
  const Samples file = read_samples_csv((dir / "samples.csv").string());
  ASSERT_TRUE(twin.calibration && hw.calibration);
  EXPECT_TRUE(twin.in_motion && hw.in_motion);
  EXPECT_EQ(file.size(), hw.sim.samples.size());
  EXPECT_EQ(file.t_read.size(), file.size());
  EXPECT_GT(twin.sim.samples.size(), 5000u);  // one per ms of the path
  EXPECT_LE(twin.sim.sampling_s, 15.0);
  EXPECT_EQ(twin.sim.sampling_s, hw.sim.sampling_s);
  expect_same_samples(twin, hw);
  // What only the twin knows came with its samples: the true end-effector
  // within the servo's tracking of the planned point, and a trajectory log.
  double worst_mm = 0.0;
  for (const sim::SampleRecord& r : twin.sim.samples) worst_mm = std::max(worst_mm, (r.xy_mm - r.target).norm());
  EXPECT_LT(worst_mm, spec.sim.max_tracking_mm);
  ASSERT_GT(twin.sim.log.rows.size(), 100u);
  EXPECT_NEAR(twin.sim.log.rows.back().t, twin.sim.simulated_s, 0.01);  // logged to the end
  const calib::PositioningError in_process = calib::positioning_error(
      twin.sim.actual, twin.calibrated, calib::WorkspaceDisc{twin.nominal.home}, twin.calibration->covariance,
      twin.calibration->carried_covariance);
  std::printf("positioning RMS in process (the twin backend): %.2f um (stated %.2f um)\n", in_process.rms_um,
              in_process.stated_sigma_rms_um);
  // The main job's robot (docs/PROCEDURES.md): 8.3 um against a stated 5.5
  // (1.5x; 19.6 um and 3.5x while the reducer's drive-train effects were
  // candidates behind encoders that turn with the joints).
  EXPECT_LE(in_process.rms_um, 2.0 * in_process.stated_sigma_rms_um);
  // The encoders turn with the joints: their error once per joint revolution
  // (the data sheet's +-2e-5 rad) is estimated with the geometry under that
  // prior, nothing of it carried beside the 1-sigma.
  EXPECT_EQ(in_process.carried_sigma_rms_um, 0.0);
  // The least RMS the readings allow (the bound with that error estimated
  // under its prior): known in process only (the truth), and below the RMS
  // error the stated 1-sigma stands for (sqrt 2 of it per axis), which
  // carries that error whole.
  ASSERT_TRUE(twin.positioning_bound_um.has_value());
  EXPECT_FALSE(hw.positioning_bound_um.has_value());
  // Through hardware no error (no truth), but the 1-sigma stated over the
  // same disc by the calibrated model's own sensitivities: within 2 % of the
  // one the actual robot's give (the same covariance; models 10 um apart).
  EXPECT_FALSE(hw.positioning.has_value());
  EXPECT_FALSE(twin.stated_positioning.has_value());
  ASSERT_TRUE(hw.stated_positioning.has_value());
  EXPECT_NEAR(hw.stated_positioning->stated_sigma_rms_um, in_process.stated_sigma_rms_um,
              0.02 * in_process.stated_sigma_rms_um);
  EXPECT_EQ(hw.stated_positioning->carried_sigma_rms_um, 0.0);
  EXPECT_EQ(hw.stated_positioning->points, in_process.points);
  EXPECT_GT(*twin.positioning_bound_um, 0.0);
  EXPECT_LT(*twin.positioning_bound_um, std::sqrt(2.0) * in_process.stated_sigma_rms_um);
#ifdef GPM_MOTION_CARD_PLUGIN
  // The same through the sample plugin (a motion card over the same twin,
  // behind the C ABI, reading all encoders in one call with its own clock).
  std::ofstream(dir / "card.yaml") << twin_hardware_file(spec, "plugin");
  on_hw.hardware = (dir / "card.yaml").string();
  const RunOutcome card = run_scenario(on_hw, "main.yaml", {}, (dir / "card_samples.csv").string());
  ASSERT_TRUE(card.calibration);
  expect_same_samples(twin, card);
#endif
  fs::remove_all(dir);
}

}  // namespace
}  // namespace gpm::scenario
