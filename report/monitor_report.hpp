// The drift monitor's section of a report (`gpm monitor`'s report and the
// monitor part of `gpm run`'s): operation, learning, reading model, events,
// alarms, tracked parameters and their tracks, from plain data.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "report/report_document.hpp"

namespace gpm::report {

// One event of the scenario and when an alarm explained it.
struct MonitorEventRow {
  int event = 0;                     // index in the scenario's events
  double at_s = 0.0;                 // when it began
  std::optional<double> detected_s;  // none: missed
  std::string explanation;
};

// One alarm of the change tests.
struct MonitorAlarmRow {
  double t_s = 0.0;
  std::string kind;  // chi_square or step
  double statistic = 0.0, threshold = 0.0;
  std::string explanation;
};

// One tracked parameter at the end of the operation and its track.
struct MonitorParameterRow {
  std::string name;
  std::optional<double> actual;  // the truth at the end (none: through hardware)
  double estimate = 0.0, sigma = 0.0;
  double um_per_unit = 1e3;      // um at the link tip per unit of the parameter
  std::vector<double> change;    // estimate minus the first estimate at each track time (parameter units)
};

// The reading model the monitor assumed, per joint.
struct MonitorReadingRow {
  std::array<double, 3> skew_s{}, compliance_rad_per_Nm{}, coulomb_Nm{}, viscous_Nm_s{}, encoder_cyclic_rad{},
      clearance_mm{}, backlash_rad{};  // clearance: each pin's radial clearance
  double thermal_time_constant_s = 0.0;
};

// Everything the monitor section shows.
struct MonitorReport {
  double simulated_s = 0.0, cycle_hz = 0.0;
  long cycles = 0;
  std::string hardware;  // empty: the in-process twin
  bool truth_known = true;
  int false_alarms = 0;
  double false_alarms_per_hour = 0.0, chi_threshold = 0.0;
  int window = 0;
  std::string learning;  // the learning phase in one sentence
  MonitorReadingRow reading{};
  std::vector<MonitorEventRow> detections{};
  std::vector<MonitorAlarmRow> alarms{};
  std::vector<MonitorParameterRow> parameters{};
  std::vector<double> track_t_s{};  // times of the tracks (s)
};

// Adds the monitor's section to doc: headings at level, the tracks as figure `figure`.svg.
void add_monitor_section(ReportDocument& doc, const MonitorReport& m, int level, const std::string& figure);

// The monitor's run in one sentence: alarms (false ones), the first, the events found and how fast.
std::string monitor_lead(const MonitorReport& m);

// gpm monitor's report: its title, the lead, the monitor's section (level-2 headings) and the tracks as tracks.svg.
ReportDocument monitor_report(const std::string& scenario_name, const MonitorReport& m);

}  // namespace gpm::report
