// The report of `gpm zero` (paper section 2.4, Table 1): one row per run of
// the zero-offset search or the section-3 comparison, from plain data.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "report/report_document.hpp"

namespace gpm::report {

// One run of the zero-offset search (or the section-3 comparison), as its row shows it.
struct ZeroRun {
  std::string label, method;               // "start 1", "grid"
  std::optional<Eigen::Vector2d> start;    // commanded start (mm); none: as found
  Eigen::Vector3d initial = Eigen::Vector3d::Constant(NAN);  // rad; NaN: not known
  Eigen::Vector3d offsets = Eigen::Vector3d::Constant(NAN);  // rad
  int motions = 0, circles = 0;
  double robot_s = 0, wall_s = 0;
  bool ok = false;
  std::string error;                       // why the run stopped (when !ok)
};

// Everything the zero report shows.
struct ZeroReport {
  std::string hardware, hardware_description;  // the hardware file and its robot's description
  std::string method;                          // the main method: "grid" or "direct"
  double radius_mm = 0.0;
  int points = 0, sensor_joint = 1;            // sensor_joint counts from 1
  std::optional<Eigen::Vector3d> actual;       // the twin's offsets (rad); none: a real robot
  std::vector<ZeroRun> runs;
};

// "a, b, c" with 5 decimals: offsets (rad) as the report and the terminal show them.
std::string zero_offsets_text(const Eigen::Vector3d& v);

// The report: settings, the table of runs and the spread of the main method's runs.
ReportDocument zero_report(const ZeroReport& z);

}  // namespace gpm::report
