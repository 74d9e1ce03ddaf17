#include "report/population_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"

namespace gpm::report {
namespace {

constexpr auto cell = table_cell;

bool any_monitored(const PopulationReport& p) {
  for (const PopulationRobotRow& r : p.robots)
    if (r.monitored) return true;
  return false;
}

// The monitor's cells of a robot (false alarms, per hour, learning, scale, detection).
std::vector<std::string> monitor_cells(const PopulationRobotRow& r) {
  if (!r.monitored) return {"-", "-", "-", "-", "-"};
  std::string detection = "-";
  if (r.event)
    detection = r.detection_delay_s ? fmt::format("{:.3f} ({})", *r.detection_delay_s, r.detection) : "missed";
  return {fmt::format("{} in {:.1f} s", r.false_alarms, r.monitored_s), cell(r.false_alarms_per_hour, "{:.0f}"),
          cell(r.learning_s, "{:.1f}"), cell(r.learned_scale, "{:.2f}"), detection};
}

// The row of a robot whose run failed.
std::vector<std::string> failed_row(const PopulationRobotRow& r, bool monitored) {
  std::vector<std::string> row{std::to_string(r.seed), "failed: " + *r.failure, "-", "-", "-", "-", "-", "-", "-", "-"};
  if (monitored) row.insert(row.end(), {"-", "-", "-", "-", "-"});
  row.push_back(cell(r.seconds, "{:.0f}"));
  return row;
}

// The row of a calibrated robot: accuracy, parameter errors, model test (and the monitor's cells).
std::vector<std::string> robot_row(const PopulationRobotRow& r, bool monitored) {
  const std::string test = r.model_test_passed ? (*r.model_test_passed ? "passes" : "fails") : "-";
  std::vector<std::string> row{
      std::to_string(r.seed), cell(r.positioning_rms_um, "{:.2f}"), cell(r.positioning_max_um, "{:.2f}"),
      cell(r.stated_sigma_rms_um, "{:.2f}"), cell(r.positioning_bound_um, "{:.2f}"),
      r.worst_param.empty() ? "-" : fmt::format("{} ({})", cell(r.worst_sigma_ratio, "{:.2f}"), r.worst_param),
      fmt::format("{}/{}", r.within_3_sigma, r.estimated), cell(r.calibrated_static_um, "{:.2f}"),
      cell(r.floor_ratio, "{:.2f}"), fmt::format("{} ({})", test, cell(r.chi2_per_dof, "{:.2f}"))};
  if (monitored) {
    const std::vector<std::string> m = monitor_cells(r);
    row.insert(row.end(), m.begin(), m.end());
  }
  row.push_back(cell(r.seconds, "{:.0f}"));
  return row;
}

std::string monitor_summary_text(const PopulationSummary& s) {
  return fmt::format(
      "Monitoring the operation after calibration ({} robots): {} false alarms in {:.2f} h of monitored time after "
      "the learning phase and before the event ({} per hour; {} robots with any); the event detected on {} of {} "
      "robots, delay median {} s, worst {} s.",
      s.monitored, s.false_alarms, s.monitored_hours, cell(s.false_alarms_per_hour, "{:.1f}"),
      s.robots_with_false_alarms, s.detected, s.events, cell(s.detection_delay_median_s, "{:.3f}"),
      cell(s.detection_delay_max_s, "{:.3f}"));
}

std::string summary_text(const PopulationReport& p) {
  const PopulationSummary& s = p.summary;
  return fmt::format(
      "{} robots of `{}` ({}), {} failed. Positioning error of the calibrated model over a disc round home "
      "(noise-free, three drives holding the readings it commands): median of the robots' RMS {} µm, worst robot {} µm. Parameters within 3 "
      "of their stated 1-sigma: {} %; the worst parameter {} sigma. Positioning error over its stated 1-sigma "
      "(median over robots, 1 when the 1-sigma is honest): {}. Model test passes on {} % of the robots.",
      s.robots, p.name,
      p.randomized ? "every effect drawn per chain from its plausible range" : "the scenario's own effects",
      s.failed, cell(s.positioning_median_um, "{:.2f}"), cell(s.positioning_max_um, "{:.2f}"),
      cell(100.0 * s.within_3_sigma_fraction, "{:.0f}"), cell(s.worst_sigma_ratio, "{:.1f}"),
      cell(s.normalised_positioning_median, "{:.2f}"), cell(100.0 * s.model_test_pass_fraction, "{:.0f}")) +
         (std::isfinite(s.floor_ratio_median)
              ? fmt::format(" Calibrated static RMS over the floor's (a controller given the actual parameters and "
                            "the twin's transmission and encoder errors): median {}; {} robots with its 95 % "
                            "interval below 1.",
                            cell(s.floor_ratio_median, "{:.2f}"), s.robots_below_floor)
              : std::string()) +
         (std::isfinite(s.positioning_bound_median_um)
              ? fmt::format(" The least positioning RMS the robots' readings allow (the Cramér-Rao bound at the "
                            "truth of the calibration's reading model, its carried error estimated under its "
                            "prior): median {} µm.",
                            cell(s.positioning_bound_median_um, "{:.2f}"))
              : std::string()) +
         (std::isfinite(s.plan_deviation_max_mm)
              ? fmt::format(" The sampling path: the farthest a robot went from its plan, median {} mm, worst {} mm "
                            "(robot {}; every pass and retreat).",
                            cell(s.plan_deviation_median_mm, "{:.1f}"), cell(s.plan_deviation_max_mm, "{:.1f}"),
                            s.plan_deviation_worst_seed)
              : std::string()) +
         (s.monitored > 0 ? " " + monitor_summary_text(s) : std::string());
}

// Figure: each robot's positioning RMS, its stated 1-sigma and (where known)
// the least RMS its readings allow, robots sorted by the RMS.
std::string positioning_plot(const PopulationReport& p) {
  std::vector<const PopulationRobotRow*> ok;
  for (const PopulationRobotRow& r : p.robots)
    if (!r.failure) ok.push_back(&r);
  std::sort(ok.begin(), ok.end(),
            [](const auto* a, const auto* b) { return a->positioning_rms_um < b->positioning_rms_um; });
  Series rms, sigma, bound;
  rms.label = "positioning error RMS";
  sigma.label = "its stated 1-sigma (RMS per axis)";
  bound.label = "the least RMS its readings allow";
  rms.style = Series::Style::kLineMarkers;
  sigma.style = bound.style = Series::Style::kMarkers;
  sigma.marker = Series::Marker::kTriangle;
  bound.marker = Series::Marker::kCross;
  for (size_t k = 0; k < ok.size(); ++k) {
    const double f = (k + 0.5) / static_cast<double>(ok.size());
    rms.x.push_back(f), rms.y.push_back(ok[k]->positioning_rms_um);
    sigma.x.push_back(f), sigma.y.push_back(ok[k]->stated_sigma_rms_um);
    if (std::isfinite(ok[k]->positioning_bound_um)) bound.x.push_back(f), bound.y.push_back(ok[k]->positioning_bound_um);
  }
  PlotOptions po = titled_plot("Positioning error of the calibrated model, over the population",
                               "fraction of robots (sorted by their error)", "µm");
  po.log_y = true;
  std::vector<Series> series{rms, sigma};
  if (!bound.x.empty()) series.push_back(bound);
  return svg_plot(series, po);
}

// Figure: every estimated parameter's |error| / stated 1-sigma, per parameter.
std::string sigma_plot(const PopulationReport& p) {
  Series pts, bound;
  pts.label = "one robot";
  bound.label = "3 sigma";
  pts.style = Series::Style::kMarkers;
  PlotOptions po = titled_plot("Parameter errors in units of their stated 1-sigma", "parameter",
                               "|estimated - actual| / stated 1-sigma");
  po.width = 720;
  int column = 0;
  for (int k = 0; k < kNumParams; ++k) {
    bool any = false;
    for (const PopulationRobotRow& r : p.robots)
      if (!r.failure && std::isfinite(r.sigma[static_cast<size_t>(k)])) {
        pts.x.push_back(column);
        pts.y.push_back(std::abs(r.error[static_cast<size_t>(k)]) / r.sigma[static_cast<size_t>(k)]);
        any = true;
      }
    if (any) po.x_categories.push_back(std::string(param_name(k))), ++column;
  }
  bound.x = {-0.5, column - 0.5};
  bound.y = {3.0, 3.0};
  return svg_plot({pts, bound}, po);
}

}  // namespace

std::vector<std::string> population_table_header(const PopulationReport& p) {
  std::vector<std::string> h{"seed", "positioning RMS (um)", "max (um)", "its stated 1-sigma (um)",
                             "least RMS the readings allow (um)",
                             "worst parameter / its 1-sigma", "within 3 sigma", "static RMS (um)",
                             "calibrated / floor", "model test (chi2/dof)"};
  if (any_monitored(p))
    h.insert(h.end(), {"false alarms (after learning, before the event)", "false alarms per hour", "learning (s)",
                       "learnt scale", "event detected after (s)"});
  h.push_back("s");
  return h;
}

std::vector<std::vector<std::string>> population_table_rows(const PopulationReport& p) {
  std::vector<std::vector<std::string>> rows;
  const bool monitored = any_monitored(p);
  for (const PopulationRobotRow& r : p.robots) rows.push_back(r.failure ? failed_row(r, monitored) : robot_row(r, monitored));
  return rows;
}

std::string population_markdown(const PopulationReport& p) {
  ReportDocument doc;
  doc.paragraph(summary_text(p));
  doc.table(population_table_header(p), population_table_rows(p));
  return doc.markdown();
}

// The lead: where the calibrated robots put their tool tips, and whether their stated 1-sigma holds.
std::string population_lead(const PopulationReport& p) {
  const PopulationSummary& s = p.summary;
  return fmt::format("Each calibrated from its own encoder readings, the {} robots put the tool tip within {} µm of "
                     "where it is sent (RMS; median over the robots, worst robot {} µm){}; the error is {}× the 1σ "
                     "each calibration states (median; 1 is honest).",
                     s.robots - s.failed, sig(s.positioning_median_um, 3), sig(s.positioning_max_um, 3),
                     s.failed > 0 ? fmt::format(", {} failed", s.failed) : std::string(),
                     sig(s.normalised_positioning_median, 2));
}

ReportDocument population_report(const PopulationReport& p) {
  ReportDocument doc;
  doc.heading(1, fmt::format("Population study: {}", p.name));
  doc.lead(population_lead(p));
  doc.paragraph(summary_text(p));
  doc.paragraph(
      "Each robot is the scenario with its own seed: its actual geometry and (randomized) every effect per chain "
      "drawn from its plausible range; robot_SEED.yaml in this folder is that robot alone (gpm run re-runs it). "
      "Positioning error: at points 10 mm apart within 80 mm of home, the readings the calibrated model commands, "
      "and where the actual robot stands when its three drives hold them (equally stiff: its joint angles nearest "
      "to the commanded ones), noise-free. Its stated 1-sigma propagates the calibration's covariance to the same "
      "points (per axis; the RMS of the 2-d error is about 1.4 times it when the 1-sigma is honest). The least RMS "
      "the readings allow is of the 2-d error, as the positioning RMS is: a robot far above it is held back by its "
      "reading model, one near it by its data (on the fly, in simulation; '-' otherwise).");
  doc.table(population_table_header(p), population_table_rows(p));
  doc.figure("population_positioning",
             "Positioning error of the calibrated model per robot, with its stated 1-sigma and the least its readings "
             "allow",
             positioning_plot(p));
  doc.figure("population_sigma", "Every estimated parameter's error in units of its stated 1-sigma", sigma_plot(p));
  doc.paragraph(fmt::format("{} robots in {:.0f} s.", p.robots.size(), p.seconds));
  return doc;
}

}  // namespace gpm::report
