// Tests of run/sampling_design.cpp: the main job's excitation path (40 poses
// designed at run time, joint 1 torque-off) keeps sampling.path_margin from
// every singularity of the driven five-bar, and the twin follows it within
// the tracking bound on every robot of a population (seeds of `actual:
// perturb:`): three robots in the default suite, thirty under label long.
#include "run/sampling_design.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include <gtest/gtest.h>

#include "calib/excitation/positioning_design.hpp"
#include "calib/model_test.hpp"
#include "calib/reading_model.hpp"
#include "models/data_dir.hpp"
#include "models/drive_margin.hpp"
#include "models/errors.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"
#include "sim/simulate.hpp"
#include "tests/run/tracking_rows.hpp"

namespace gpm::scenario {
namespace {

// The main job's scenario changed by edit, with its poses designed as gpm
// run designs them (at the encoders' reading sigma).
RunSpec designed_main_job(const std::function<void(RunSpec&)>& edit = [](RunSpec&) {}) {
  RunSpec s = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
  edit(s);
  design_sampling(s.sim, ~s.calibration.fixed,
                  calib::reading_sigma(calib::encoder_step_rad(s.sim.twin.encoder.bits), s.sim.twin.encoder.noise_rad));
  return s;
}

const RunSpec& main_job() {
  static const RunSpec spec = designed_main_job();
  return spec;
}

// Largest distance of the twin's true end-effector from the plan over the
// main job's sampling of the robot of seed, as gpm run samples it (through
// the hardware interface, with the tracking watch and the path's early end
// and retreat: the whole motion counts, the retreat too).
double max_deviation_mm(std::uint64_t seed, bool* ended_early = nullptr) {
  RunSpec spec = main_job();
  spec.sim.seed = seed;
  std::vector<sim::LogRow> rows;
  try {
    rows = sample_in_process(spec).log.rows;
    if (ended_early) *ended_early = false;
  } catch (const sim::TrackingStop& stop) {
    rows = stop.rows;
    if (ended_early) *ended_early = std::string(stop.what()).find("retraced its path") != std::string::npos;
  }
  return gpm::test::worst_row_deviation_mm(rows);
}

TEST(SamplingDesign, MainJobPosesAndPathKeepTheMarginOfTheDrivenFiveBar) {
  const sim::Scenario& s = main_job().sim;
  ASSERT_EQ(s.sampling->poses.size(), 40u);
  const DriveMask drives = sim::position_drives(s);
  EXPECT_EQ(drives, (DriveMask{false, true, true}));
  for (const Eigen::Vector2d& p : s.sampling->poses)
    EXPECT_EQ(margin_violation(s.controller, p, drives, s.sampling->margin), "");
  sim::PathRepair repair;
  const sim::WaypointPath path = sim::excitation_plan(s, s.sampling->poses, &repair);
  for (const Eigen::Vector2d& p : path.p)
    ASSERT_EQ(margin_violation(s.controller, p, drives, s.sampling->margin), "") << p.transpose();
  std::printf("main job: excitation path of %.1f mm, %.2f s, %d via points\n", path.length_mm,
              sim::waypoint_duration(path), repair.vias);
  EXPECT_LE(sim::waypoint_duration(path), 15.0);  // the robot time the main job expects
}

// A margin that too few poses keep is refused before anything moves (one
// line, exit 2), naming the key.
TEST(SamplingDesign, AMarginTooFewPosesKeepIsRefused) {
  RunSpec spec = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
  spec.sim.sampling->margin.singularity = 0.85;
  try {
    design_sampling(spec.sim, ~spec.calibration.fixed, 1e-5);
    FAIL() << "designed inside an impossible margin";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("sampling.path_margin: only 0 points of the 5 mm grid joined to home keep the margin"),
              std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
}

// A design is made once per process for the same inputs (a population of
// robots shares its data sheet) and again whenever anything it reads changes.
TEST(SamplingDesign, ADesignIsRememberedForItsInputsOnly) {
  const auto designed = [](const std::function<void(RunSpec&)>& change) {
    RunSpec spec = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
    change(spec);
    design_sampling(spec.sim, ~spec.calibration.fixed, 1e-5);
    return spec.sim.sampling->poses;
  };
  const std::vector<Eigen::Vector2d> first = designed([](RunSpec&) {});
  EXPECT_EQ(designed([](RunSpec& s) { s.sim.seed = 99; s.sim.actual.sigma_link_mm = 0.5; }), first);  // another robot, one data sheet
  EXPECT_EQ(designed([](RunSpec& s) { s.sim.sampling->count = 30; }).size(), 30u);
  EXPECT_NE(designed([](RunSpec& s) { s.sim.controller.geometry[la(1)] += 20.0; }), first);
  EXPECT_NE(designed([](RunSpec& s) { s.calibration.fixed.set(lb(2)); }), first);
  // The encoder offsets only relabel the readings: the design is the same for any.
  EXPECT_EQ(designed([](RunSpec& s) {
              for (int i = 0; i < 3; ++i) s.sim.controller.geometry[dth(i)] += 0.013 * (i + 1);
            }),
            first);
  EXPECT_THROW(designed([](RunSpec& s) { s.sim.sampling->margin.singularity = 0.85; }), InputError);
  EXPECT_NE(designed([](RunSpec& s) { s.sim.sampling->criterion = sim::DesignCriterion::kWorst; }), first);
}

// On the fly the poses are designed for the positioning (the data sheet
// states an error once per joint revolution): their positioning bound is
// below that of the poses designed for the worst parameter in the same
// region; with the offsets fixed the criterion is refused in one line.
TEST(SamplingDesign, OnTheFlyThePosesAreDesignedForThePositioning) {
  namespace ex = calib::excitation;
  const RunSpec worst = designed_main_job([](RunSpec& s) { s.sim.sampling->criterion = sim::DesignCriterion::kWorst; });
  const RunSpec& positioning = main_job();
  const FreeMask free = ~positioning.calibration.fixed;
  const double sigma = calib::reading_sigma(calib::encoder_step_rad(17), 0.0);
  const auto bound = [&](const std::vector<Eigen::Vector2d>& poses) {
    const Eigen::MatrixXd rows = ex::rows_with_cyclic_error(positioning.sim.controller, free, poses);
    std::vector<int> all(poses.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = static_cast<int>(k);
    return ex::positioning_bound_um(rows, all,
                                    ex::positioning_criterion(positioning.sim.controller, free, {}, sigma, rows));
  };
  const double b_worst = bound(worst.sim.sampling->poses), b_positioning = bound(positioning.sim.sampling->poses);
  std::printf("positioning bound of the main job's poses: %.2f um designed for the worst parameter, %.2f um for "
              "the positioning\n",
              b_worst, b_positioning);
  EXPECT_LT(b_positioning, 0.9 * b_worst);
  RunSpec fixed = load_run_spec(gpm::scenarios_dir() + "/main.yaml");
  fixed.sim.sampling->criterion = sim::DesignCriterion::kPositioning;
  fixed.calibration.fixed.set(kDth1);
  try {
    design_sampling(fixed.sim, ~fixed.calibration.fixed, sigma);
    FAIL() << "designed for the positioning with dth1 fixed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("main.yaml: sampling.criterion: positioning needs"), std::string::npos)
        << e.what();
  }
}

// The main job's path_margin.deviation_mm (10 mm, half the tracking watch's
// 20 mm) keeps the design and its path inside it, and on a robot whose
// offsets lie beyond the tolerance (seed 10009: dth2, dth3 1.1 and 1.2 times
// 0.02 rad) the hub stays closer to the plan than with a margin at the
// watch's bound.
TEST(SamplingDesign, ATighterDeviationMarginKeepsTheHubCloserToThePlan) {
  const sim::Scenario& s = main_job().sim;
  ASSERT_EQ(s.sampling->margin.deviation_mm, 10.0);
  const DriveMask drives = sim::position_drives(s);
  const sim::WaypointPath path = sim::excitation_plan(s, s.sampling->poses);
  double worst = 0.0;
  for (const Eigen::Vector2d& p : path.p) {
    worst = std::max(worst, drive_margins(s.controller, p, drives, s.sampling->margin.tolerance).deviation_mm);
    ASSERT_EQ(margin_violation(s.controller, p, drives, s.sampling->margin), "") << p.transpose();
  }
  EXPECT_LE(worst, 10.0);
  const RunSpec wide = designed_main_job([](RunSpec& w) { w.sim.sampling->margin.deviation_mm = 20.0; });
  const auto deviation = [](sim::Scenario t) {
    t.seed = 10009;
    t.max_tracking_mm = 0.0;
    const sim::SimulationResult r = sim::run_simulation(t);
    return gpm::test::worst_row_deviation_mm(r.log.rows, r.sampling_s);
  };
  const double tight = deviation(s), at_watch = deviation(wide.sim);
  std::printf("seed 10009: max deviation %.2f mm with deviation_mm 10, %.2f mm with 20\n", tight, at_watch);
  EXPECT_LT(tight, at_watch - 1.0);
}

TEST(SamplingDesign, MainJobTracksItsPathWithin20MmOnThreeRobots) {
  for (std::uint64_t seed : {2026u, 7u, 11u}) {
    const double d = max_deviation_mm(seed);
    std::printf("seed %llu: max deviation from the plan %.2f mm\n", static_cast<unsigned long long>(seed), d);
    EXPECT_LE(d, 20.0) << "seed " << seed;
  }
}

// Robots whose geometry (offsets beyond the planner's tolerance) takes them
// far from the main job's plan (on the path designed for the worst
// parameter, without the early end, `gpm simulate` with the watch off: 10009
// 22 mm; 7011 19 mm, its watch tripping at its 20 mm bound): 7011's path ends
// early, the robot retraces it, and neither leaves its plan by more than
// 20 mm (10009 now stays within it on the path designed for the positioning,
// 15.5 mm, without an early end).
TEST(SamplingDesign, ARobotBeyondItsToleranceEndsThePathWithin20Mm) {
  for (std::uint64_t seed : {10009u, 7011u}) {
    bool early = false;
    const double d = max_deviation_mm(seed, &early);
    std::printf("seed %llu: max deviation from the plan %.2f mm, ended early: %d\n",
                static_cast<unsigned long long>(seed), d, early);
    if (seed == 7011u) {
      EXPECT_TRUE(early);
    }
    EXPECT_LE(d, 20.0) << "seed " << seed;
  }
}

TEST(SamplingDesignLong, DISABLED_MainJobTracksItsPathWithin20MmOnThirtyRobots) {
  double worst = 0.0;
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const double d = max_deviation_mm(seed);
    std::printf("seed %llu: max deviation from the plan %.2f mm\n", static_cast<unsigned long long>(seed), d);
    worst = std::max(worst, d);
    EXPECT_LE(d, 20.0) << "seed " << seed;
  }
  std::printf("population of 30: worst max deviation %.2f mm\n", worst);
}

}  // namespace
}  // namespace gpm::scenario
