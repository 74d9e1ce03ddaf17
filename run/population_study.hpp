// `gpm study population`: a scenario run over N robots of the class instead
// of one. Robot k takes the seed s_k (the scenario's seed + k, or the seeds
// given), which draws its actual geometry and, with the `randomized` effects
// preset (sim/effects_random.hpp), every effect per chain; each robot is run
// through the runner (run/runner.hpp) and judged by what a user gets: the
// positioning error of its calibrated model over the workspace
// (calib/positioning_error.hpp), and its parameter errors in units of the
// 1-sigma its result states.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calib/friction_balance.hpp"
#include "calib/positioning_error.hpp"
#include "models/parameters.hpp"
#include "report/population_report.hpp"
#include "sim/effects.hpp"

namespace gpm::scenario {

struct PopulationOptions {
  int count = 30;                      // robots (seeds scenario seed + 0 .. count - 1)
  std::vector<std::uint64_t> seeds;    // these robots instead (re-run chosen ones)
  bool keep_effects = false;           // the scenario's own effects (only the geometry varies)
  int threads = 2;                     // robots in parallel
};

// One robot of the population.
struct PopulationRobot {
  std::uint64_t seed = 0;
  std::string scenario_text;            // the scenario that is this robot alone (gpm run re-runs it)
  sim::Effects effects;                 // its drawn effects
  std::optional<std::string> failure;   // refused, diverged, stopped or not converged: why
  calib::PositioningError positioning;  // of the calibrated model (RunOutcome::positioning; zero when failed)
  double positioning_bound_um = NAN;    // the least the readings allow (RunOutcome::positioning_bound_um; NaN: none)
  double calibrated_static_um = 0.0, floor_um = 0.0, floor_ratio = 0.0;  // NaN if not measured
  std::array<double, 2> floor_ratio_ci95{NAN, NAN};  // its 95 % interval (RunOutcome::floor_ratio_ci95)
  std::optional<bool> model_test_passed;
  double chi2_per_dof = 0.0;
  std::vector<std::string> calls_for;   // failed on the fly: the effects left out the residuals call for
  std::vector<std::string> notes;       // the calibration's notes, as gpm run reports them (what it estimated,
                                        // chose and left out, and why)
  std::array<double, kNumParams> error{};  // estimated - actual (mm, rad; NaN where not estimated)
  std::array<double, kNumParams> sigma{};  // the stated 1-sigma (NaN where not estimated)
  std::string worst_param;                 // largest |error| / sigma
  double worst_sigma_ratio = 0.0;
  int estimated = 0, within_3_sigma = 0;   // parameters with a stated 1-sigma; of those within 3 of it
  // With `operation:` (the calibrated model monitors it, run/monitor_run.hpp):
  bool monitored = false;
  double learning_s = 0.0;        // length of the monitor's learning phase (no alarm in it)
  double learned_scale = 0.0;     // the innovation scale it learnt (1: as stated)
  double monitored_s = 0.0;       // monitored time after learning and before the first event
  int false_alarms = 0;           // alarms in that time (the robot was healthy)
  double false_alarms_per_hour = 0.0;  // false_alarms / monitored_s, per hour (NaN: no time)
  bool event = false;             // the scenario injects an event (first of its events)
  std::optional<double> detection_delay_s;  // its first alarm after it, minus its time (none: missed)
  std::string detection;          // that alarm's explanation
  int alarms_after_event = 0;     // every alarm from the event on (the detection among them)
  double plan_deviation_mm = NAN;  // farthest from its sampling path's plan, every pass (NaN: not known)
  std::optional<calib::BalanceFriction> friction_balance;  // each drive's friction as the calibration found it
  double seconds = 0.0;
};

// Figures over the robots that did not fail (report/population_report.hpp).
using PopulationSummary = report::PopulationSummary;

struct PopulationStudy {
  std::string scenario;  // the scenario file
  std::string name;      // its name
  bool randomized = true;
  std::vector<PopulationRobot> robots;
  double seconds = 0.0;
  PopulationSummary summary() const;
};

using PopulationProgress = std::function<void(const PopulationRobot&, int done, int total)>;

// The scenario text of robot `seed`: scenario_file's YAML with that seed,
// `effects: randomized` (unless keep_effects), no expectations, and the
// robot file's path made absolute so the text runs from anywhere. Throws
// InputError for a scenario that cannot be read.
std::string population_robot_scenario(const std::string& scenario_file, std::uint64_t seed, bool keep_effects);

// Runs every robot (options.threads at a time), calling progress as each
// finishes. A robot whose run fails gives a row with `failure`; bad input of
// the scenario itself throws InputError before any run.
PopulationStudy run_population_study(const std::string& scenario_file, const PopulationOptions& options,
                                     const PopulationProgress& progress = {});

// The table, one row per robot: header and cells as printed (with the
// monitor's columns when the study monitored).
std::vector<std::string> population_table_header(const PopulationStudy& study);
std::vector<std::vector<std::string>> population_table_rows(const PopulationStudy& study);

// The summary and the table in Markdown (for the terminal and the README).
std::string population_markdown(const PopulationStudy& study);

// DIR/population.json: the summary and every robot (seed, effects, numbers).
std::string population_json(const PopulationStudy& study);

// The report: summary, table, figures (distributions of the accuracy and of
// the parameter errors in their stated 1-sigma).
report::ReportDocument population_report(const PopulationStudy& study);

// Writes DIR/population.md, population.html, population.json, the figures
// and robot_<seed>.yaml per robot, all or none.
void write_population_study(const PopulationStudy& study, const std::string& dir);

}  // namespace gpm::scenario
