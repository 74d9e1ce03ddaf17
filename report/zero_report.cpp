#include "report/zero_report.hpp"

#include <cmath>

#include <fmt/format.h>

#include "report/table_cell.hpp"

namespace gpm::report {
namespace {

// A main-method run from a --start (those the spread compares).
bool is_main_run(const ZeroReport& z, const ZeroRun& r) {
  return r.ok && r.method == z.method && r.label.rfind("start", 0) == 0;
}

// The table's cells of one run.
std::vector<std::string> run_cells(const ZeroReport& z, const ZeroRun& r) {
  const std::string start = r.start ? fmt::format("{:.2f}, {:.2f}", r.start->x(), r.start->y()) : "as found";
  std::string err = "unknown";
  if (z.actual && r.ok) err = sig((r.offsets - *z.actual).cwiseAbs().maxCoeff() * 1e6, 3);
  return {r.label, r.method, start, r.initial.allFinite() ? zero_offsets_text(r.initial) : "-",
          r.ok ? zero_offsets_text(r.offsets) : "stopped: " + r.error, err, std::to_string(r.motions),
          std::to_string(r.circles), fmt::format("{:.1f}", r.robot_s), fmt::format("{:.1f}", r.wall_s)};
}

// Spread of the main method's runs (paper Table 1: same offsets from different starts).
void add_spread(ReportDocument& d, const ZeroReport& z) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  int n = 0;
  for (const ZeroRun& r : z.runs) {
    if (!is_main_run(z, r)) continue;
    lo = lo.cwiseMin(r.offsets);
    hi = hi.cwiseMax(r.offsets);
    ++n;
  }
  if (n >= 2)
    d.paragraph(fmt::format("Spread of the {} {} runs (max - min per joint): {} rad.", n, z.method,
                            zero_offsets_text(hi - lo)));
}

}  // namespace

std::string zero_offsets_text(const Eigen::Vector3d& v) {
  return fmt::format("{:.5f}, {:.5f}, {:.5f}", v[0], v[1], v[2]);
}

ReportDocument zero_report(const ZeroReport& z) {
  ReportDocument d;
  d.heading(1, "Zero-offset auto-calibration (paper section 2.4)");
  d.paragraph(fmt::format("Hardware: {} ({}). Circle radius {} mm, {} interpolation points, joint {} read only "
                          "(torque off).",
                          z.hardware, z.hardware_description, z.radius_mm, z.points, z.sensor_joint));
  if (z.actual) d.paragraph(fmt::format("Actual offsets of the twin: {} rad.", zero_offsets_text(*z.actual)));
  std::vector<std::vector<std::string>> table;
  for (const ZeroRun& r : z.runs) table.push_back(run_cells(z, r));
  d.table({"run", "method", "start (mm, commanded)", "initial estimate (rad)", "result (rad)",
           "max error vs actual (µrad)", "motions", "circles", "robot s", "wall s"},
          table);
  add_spread(d, z);
  return d;
}

}  // namespace gpm::report
