// The report of `gpm study population`: a summary, one row per robot of the
// class and two figures (positioning error and parameter errors in their
// stated 1-sigma over the robots), from plain data.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "models/parameters.hpp"
#include "report/report_document.hpp"

namespace gpm::report {

// Figures over the robots that did not fail.
struct PopulationSummary {
  int robots = 0, failed = 0;
  double positioning_median_um = 0.0, positioning_max_um = 0.0;  // of each robot's RMS
  double positioning_bound_median_um = NAN;  // of each robot's least RMS its readings allow (NaN: none)
  // Calibrated static RMS over the floor's (an oracle): the median over the
  // robots measured, and the robots whose 95 % interval lies below 1.
  double floor_ratio_median = NAN;
  int robots_below_floor = 0;
  double within_3_sigma_fraction = 0.0;  // of all estimated parameters
  double worst_sigma_ratio = 0.0;
  double model_test_pass_fraction = 0.0;
  double normalised_positioning_median = 0.0;  // RMS positioning error / its stated 1-sigma (1: honest)
  // The farthest each robot went from its sampling path's plan (mm, every
  // robot where the twin knows it): median and worst, and that robot.
  double plan_deviation_median_mm = NAN, plan_deviation_max_mm = NAN;
  std::uint64_t plan_deviation_worst_seed = 0;
  // Monitoring (robots with `operation:`): pooled false alarms per hour of
  // monitored time after learning and before the event, robots with any, and
  // the detection delays of the event.
  int monitored = 0;
  int false_alarms = 0;
  double monitored_hours = 0.0;
  double false_alarms_per_hour = 0.0;
  int robots_with_false_alarms = 0;
  int events = 0, detected = 0;
  double detection_delay_median_s = 0.0, detection_delay_max_s = 0.0;
};

// One robot of the population as its row and the figures show it.
struct PopulationRobotRow {
  std::uint64_t seed = 0;
  std::optional<std::string> failure;  // why the run failed
  double positioning_rms_um = 0.0, positioning_max_um = 0.0, stated_sigma_rms_um = 0.0;
  double positioning_bound_um = NAN;  // the least RMS its readings allow (NaN: not computed)
  double calibrated_static_um = 0.0, floor_ratio = 0.0;  // NaN if not measured
  std::optional<bool> model_test_passed;
  double chi2_per_dof = 0.0;
  std::array<double, kNumParams> error{};  // estimated - actual (NaN where not estimated)
  std::array<double, kNumParams> sigma{};  // the stated 1-sigma (NaN where not estimated)
  std::string worst_param;                 // largest |error| / sigma
  double worst_sigma_ratio = 0.0;
  int estimated = 0, within_3_sigma = 0;
  bool monitored = false;
  double learning_s = 0.0, learned_scale = 0.0, monitored_s = 0.0;
  int false_alarms = 0;
  double false_alarms_per_hour = 0.0;
  bool event = false;
  std::optional<double> detection_delay_s;  // none: missed
  std::string detection;                    // the detecting alarm's explanation
  double seconds = 0.0;
};

// Everything the population report shows.
struct PopulationReport {
  std::string name;  // the scenario's name
  bool randomized = true;
  double seconds = 0.0;
  PopulationSummary summary;
  std::vector<PopulationRobotRow> robots;
};

// The table's header: with the monitor's columns when a robot was monitored.
std::vector<std::string> population_table_header(const PopulationReport& p);

// The table's rows, one per robot, cells as printed.
std::vector<std::vector<std::string>> population_table_rows(const PopulationReport& p);

// The summary and the table in Markdown (for the terminal and the README).
std::string population_markdown(const PopulationReport& p);

// The report: summary, how the robots were drawn and judged, table and figures.
ReportDocument population_report(const PopulationReport& p);

}  // namespace gpm::report
