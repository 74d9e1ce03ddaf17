// Tests of run/population_study.cpp: a robot's scenario text is that robot
// alone (its seed, the randomized effects, no expectations, a robot path that
// works from anywhere); a robot re-run alone by its seed gives the numbers it
// had in the population, bit for bit; the summary is the robots' figures.
#include "run/population_study.hpp"

#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "models/errors.hpp"
#include "run/run_spec.hpp"

namespace gpm::scenario {
namespace {

const std::string kSmall = std::string(GPM_SOURCE_DIR) + "/tests/fixtures/population_small.yaml";

TEST(PopulationStudy, ARobotsScenarioIsThatRobotAlone) {
  const std::string text = population_robot_scenario(kSmall, 77, false);
  // Parsed from another folder: the robot path no longer depends on it.
  const RunSpec a = parse_run_spec(text, "robot_77.yaml", std::filesystem::temp_directory_path().string());
  const RunSpec b = parse_run_spec(population_robot_scenario(kSmall, 77, false), "r.yaml", ".");
  const RunSpec c = parse_run_spec(population_robot_scenario(kSmall, 78, false), "r.yaml", ".");
  EXPECT_EQ(a.sim.seed, 77u);
  EXPECT_EQ(a.sim.twin.effects.mjcf.coulomb_Nm, b.sim.twin.effects.mjcf.coulomb_Nm);
  EXPECT_NE(a.sim.twin.effects.mjcf.coulomb_Nm, c.sim.twin.effects.mjcf.coulomb_Nm);
  EXPECT_NE(a.sim.twin.effects.mjcf.coulomb_Nm[0], a.sim.twin.effects.mjcf.coulomb_Nm[1]);  // drawn per chain
  EXPECT_FALSE(a.expect.converged.has_value());
  // --keep-effects: the scenario's own (the realistic preset: one value on every chain).
  const RunSpec k = parse_run_spec(population_robot_scenario(kSmall, 77, true), "r.yaml", ".");
  EXPECT_EQ(k.sim.twin.effects.mjcf.coulomb_Nm[0], k.sim.twin.effects.mjcf.coulomb_Nm[1]);
}

TEST(PopulationStudy, AHardwareScenarioIsRefused) {
  const std::string hw = std::string(GPM_SOURCE_DIR) + "/scenarios/hardware_twin.yaml";
  EXPECT_THROW(population_robot_scenario(hw, 1, false), InputError);
}

TEST(PopulationStudy, ARobotReRunAloneGivesItsNumbersAndTheSummaryIsTheRobots) {
  PopulationOptions o;
  o.count = 2;
  const PopulationStudy study = run_population_study(kSmall, o);
  ASSERT_EQ(study.robots.size(), 2u);
  EXPECT_EQ(study.robots[0].seed, 500u);  // the scenario's seed, then the next
  EXPECT_EQ(study.robots[1].seed, 501u);
  for (const PopulationRobot& r : study.robots) {
    ASSERT_FALSE(r.failure) << *r.failure;
    EXPECT_GT(r.positioning.points, 150);
    EXPECT_GT(r.positioning.rms_um, 0.0);
    EXPECT_LE(r.positioning.rms_um, r.positioning.max_um);
    EXPECT_GT(r.estimated, 0);
  }
  o.seeds = {501};
  o.threads = 1;
  const PopulationStudy alone = run_population_study(kSmall, o);
  ASSERT_EQ(alone.robots.size(), 1u);
  EXPECT_EQ(alone.robots[0].positioning.rms_um, study.robots[1].positioning.rms_um);
  // The calibration's notes come with each robot, the same as it re-run alone.
  ASSERT_FALSE(study.robots[1].notes.empty());
  EXPECT_EQ(alone.robots[0].notes, study.robots[1].notes);
  for (size_t k = 0; k < kNumParams; ++k) {
    if (!std::isfinite(study.robots[1].error[k])) continue;
    EXPECT_EQ(alone.robots[0].error[k], study.robots[1].error[k]);
  }
  const PopulationSummary s = study.summary();
  EXPECT_EQ(s.robots, 2);
  EXPECT_DOUBLE_EQ(s.positioning_median_um,
                   0.5 * (study.robots[0].positioning.rms_um + study.robots[1].positioning.rms_um));
  EXPECT_DOUBLE_EQ(s.positioning_max_um,
                   std::max(study.robots[0].positioning.rms_um, study.robots[1].positioning.rms_um));
  // The sampling path's worst departure from its plan: known on the twin,
  // the summary's worst is the robots' and names that robot.
  const PopulationRobot& far = study.robots[0].plan_deviation_mm > study.robots[1].plan_deviation_mm
                                   ? study.robots[0] : study.robots[1];
  EXPECT_GT(far.plan_deviation_mm, 0.0);
  EXPECT_EQ(s.plan_deviation_max_mm, far.plan_deviation_mm);
  EXPECT_EQ(s.plan_deviation_worst_seed, far.seed);
  EXPECT_EQ(alone.robots[0].plan_deviation_mm, study.robots[1].plan_deviation_mm);
  const auto j = nlohmann::json::parse(population_json(study));
  EXPECT_EQ(j["robots"].size(), 2u);
  EXPECT_EQ(j["robots"][1]["seed"], 501);
  EXPECT_EQ(j["robots"][1]["plan_deviation_mm"], study.robots[1].plan_deviation_mm);
  EXPECT_EQ(j["robots"][1]["calibration_notes"].get<std::vector<std::string>>(), study.robots[1].notes);
  EXPECT_EQ(j["summary"]["plan_deviation_max_mm"], s.plan_deviation_max_mm);
}

}  // namespace
}  // namespace gpm::scenario

namespace gpm::scenario {
namespace {

// The monitor's figures of a population (issue 31): false alarms pooled per
// hour of healthy monitored time, detection delays over the robots that
// detected, failed robots left out; the table gains the monitor's columns
// only when the study monitored.
// Calibrated / floor: its median over the robots measured, and the robots
// whose interval lies wholly below 1 (an upper end of exactly 1 does not).
TEST(PopulationStudy, FloorRatiosMedianAndTheRobotsBelowIt) {
  PopulationStudy study;
  study.robots.resize(4);
  const double ratio[] = {0.9, 1.2, 1.05, NAN};
  const std::array<double, 2> ci[] = {{0.8, 0.99}, {1.1, 1.3}, {0.9, 1.0}, {NAN, NAN}};
  for (std::size_t k = 0; k < 4; ++k) study.robots[k].floor_ratio = ratio[k], study.robots[k].floor_ratio_ci95 = ci[k];
  const PopulationSummary s = study.summary();
  EXPECT_DOUBLE_EQ(s.floor_ratio_median, 1.05);
  EXPECT_EQ(s.robots_below_floor, 1);
  const std::string json = population_json(study);
  EXPECT_NE(json.find("\"robots_below_floor\": 1"), std::string::npos);
  EXPECT_NE(json.find("\"floor_ratio_ci95\": [\n"), std::string::npos);
}

// The bound's median is over the robots that have one (on the fly) and did not fail.
TEST(PopulationStudy, TheBoundsMedianIsOverTheRobotsThatHaveOne) {
  PopulationStudy study;
  study.robots.resize(5);
  const double bound[] = {4.0, 9.0, NAN, 5.0, 1.0};
  for (std::size_t k = 0; k < study.robots.size(); ++k) study.robots[k].positioning_bound_um = bound[k];
  study.robots[4].failure = "diverged";  // not counted
  EXPECT_DOUBLE_EQ(study.summary().positioning_bound_median_um, 5.0);
  EXPECT_NE(population_json(study).find("\"positioning_bound_median_um\": 5.0"), std::string::npos);
  for (PopulationRobot& r : study.robots) r.positioning_bound_um = NAN;
  EXPECT_TRUE(std::isnan(study.summary().positioning_bound_median_um));
}

TEST(PopulationStudy, MonitorFiguresArePooledOverTheMonitoredRobots) {
  PopulationStudy study;
  study.robots.resize(4);
  for (std::size_t k = 0; k < study.robots.size(); ++k) study.robots[k].seed = k + 1;
  EXPECT_EQ(population_table_header(study).size(), 11u);  // nothing monitored: no monitor columns
  PopulationRobot& a = study.robots[0];
  a.monitored = a.event = true;
  a.false_alarms = 2, a.monitored_s = 30.0, a.false_alarms_per_hour = 240.0;
  a.detection_delay_s = 0.2;
  PopulationRobot& b = study.robots[1];
  b.monitored = b.event = true;
  b.monitored_s = 30.0;  // no false alarm, the event missed
  PopulationRobot& c = study.robots[2];
  c.monitored = c.event = true;
  c.monitored_s = 60.0, c.detection_delay_s = 0.6;
  study.robots[3].failure = "diverged";
  study.robots[3].monitored = true, study.robots[3].false_alarms = 100;  // failed: not counted
  const PopulationSummary s = study.summary();
  EXPECT_EQ(s.monitored, 3);
  EXPECT_EQ(s.false_alarms, 2);
  EXPECT_DOUBLE_EQ(s.monitored_hours, 120.0 / 3600.0);
  EXPECT_DOUBLE_EQ(s.false_alarms_per_hour, 60.0);
  EXPECT_EQ(s.robots_with_false_alarms, 1);
  EXPECT_EQ(s.events, 3);
  EXPECT_EQ(s.detected, 2);
  EXPECT_DOUBLE_EQ(s.detection_delay_median_s, 0.4);
  EXPECT_DOUBLE_EQ(s.detection_delay_max_s, 0.6);
  const auto header = population_table_header(study);
  EXPECT_EQ(header.size(), 16u);
  const auto rows = population_table_rows(study);
  for (const auto& row : rows) EXPECT_EQ(row.size(), header.size());
  EXPECT_EQ(rows[1][14], "missed");
  EXPECT_NE(population_json(study).find("\"false_alarms_per_hour\": 60.0"), std::string::npos);
}

}  // namespace
}  // namespace gpm::scenario
