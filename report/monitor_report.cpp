#include "report/monitor_report.hpp"

#include <fmt/format.h>

#include "report/svg_plot.hpp"

namespace gpm::report {
namespace {

// "a, b, c" of a per-joint value times scale, 3 significant digits.
std::string three(const std::array<double, 3>& v, double scale) {
  return fmt::format("{:.3g}, {:.3g}, {:.3g}", v[0] * scale, v[1] * scale, v[2] * scale);
}

// The operation, the learning phase and the reading model assumed.
void add_settings(ReportDocument& doc, const MonitorReport& m) {
  doc.paragraph(fmt::format("{:.1f} s of normal operation ({} servo cycles at {:.0f} Hz{}), {} alarms{}, "
                            "stated false-alarm rate {} per hour (chi-square threshold {:.1f} over {} samples).",
                            m.simulated_s, m.cycles, m.cycle_hz, m.hardware.empty() ? "" : " through " + m.hardware,
                            m.alarms.size(), m.truth_known ? fmt::format(" ({} false)", m.false_alarms) : "",
                            m.false_alarms_per_hour, m.chi_threshold, m.window));
  doc.paragraph(fmt::format("Learning: {}.", m.learning));
  const MonitorReadingRow& r = m.reading;
  doc.paragraph(fmt::format(
      "Reading model assumed (joints 1, 2, 3): latch skew {} us; compliance {} rad/N m; drive friction {} N m "
      "and {} N m s/rad; cyclic encoder error {} urad; pin clearance {} um; backlash {} urad; drift time constant "
      "{:.0f} s.",
      three(r.skew_s, 1e6), three(r.compliance_rad_per_Nm, 1.0), three(r.coulomb_Nm, 1.0),
      three(r.viscous_Nm_s, 1.0), three(r.encoder_cyclic_rad, 1e6), three(r.clearance_mm, 1e3),
      three(r.backlash_rad, 1e6), r.thermal_time_constant_s));
}

// The events and when they were detected.
void add_detections(ReportDocument& doc, const std::vector<MonitorEventRow>& detections) {
  std::vector<std::vector<std::string>> rows;
  for (const MonitorEventRow& d : detections)
    rows.push_back({std::to_string(d.event), fmt::format("{:.3f}", d.at_s),
                    d.detected_s ? fmt::format("{:.3f}", *d.detected_s) : "missed",
                    d.detected_s ? fmt::format("{:.3f}", *d.detected_s - d.at_s) : "", d.explanation});
  doc.table({"event", "at (s)", "detected (s)", "delay (s)", "explanation"}, rows);
}

// The first 20 alarms.
void add_alarms(ReportDocument& doc, const std::vector<MonitorAlarmRow>& alarms, int level) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < alarms.size() && k < 20; ++k) {
    const MonitorAlarmRow& a = alarms[k];
    rows.push_back({fmt::format("{:.3f}", a.t_s), a.kind, fmt::format("{:.1f}", a.statistic),
                    fmt::format("{:.1f}", a.threshold), a.explanation});
  }
  doc.heading(level, alarms.size() > 20 ? fmt::format("Alarms (first 20 of {})", alarms.size()) : "Alarms");
  doc.table({"t (s)", "test", "statistic", "threshold", "explanation"}, rows);
}

// The tracked parameters at the end: actual, estimate, error and 1-sigma (um at the link).
void add_final_estimates(ReportDocument& doc, const std::vector<MonitorParameterRow>& parameters, int level) {
  std::vector<std::vector<std::string>> errs;
  for (const MonitorParameterRow& p : parameters) {
    const std::string sigma = fmt::format("{:.2f}", p.sigma * p.um_per_unit);
    if (!p.actual) {
      errs.push_back({p.name, "unknown", fmt::format("{:.9g}", p.estimate), "", sigma});
      continue;
    }
    errs.push_back({p.name, fmt::format("{:.9g}", *p.actual), fmt::format("{:.9g}", p.estimate),
                    fmt::format("{:.2f}", (p.estimate - *p.actual) * p.um_per_unit), sigma});
  }
  doc.heading(level, "Tracked parameters at the end");
  doc.table({"parameter", "actual", "estimate", "error (um at the link)", "1-sigma (um)"}, errs);
}

// Parameter tracks: estimate minus the value at the start, in um at the link; empty without tracks.
std::string tracks_figure(const MonitorReport& m) {
  std::vector<Series> series;
  for (const MonitorParameterRow& p : m.parameters) {
    if (m.track_t_s.empty()) continue;
    Series sr;
    sr.label = p.name;
    sr.x = m.track_t_s;
    for (double c : p.change) sr.y.push_back(c * p.um_per_unit);
    series.push_back(sr);
  }
  if (series.empty()) return "";
  return svg_plot(series, titled_plot("Tracked change of each parameter", "t (s)",
                                      "change since start (um at the link)"));
}

}  // namespace

void add_monitor_section(ReportDocument& doc, const MonitorReport& m, int level, const std::string& figure) {
  add_settings(doc, m);
  if (!m.detections.empty()) add_detections(doc, m.detections);
  if (!m.alarms.empty()) add_alarms(doc, m.alarms, level);
  add_final_estimates(doc, m.parameters, level);
  const std::string svg = tracks_figure(m);
  if (!svg.empty()) doc.figure(figure, "Parameter tracks of the drift estimator", svg);
}

ReportDocument monitor_report(const std::string& scenario_name, const MonitorReport& m) {
  ReportDocument doc;
  doc.heading(1, fmt::format("gpm monitor: {}", scenario_name));
  add_monitor_section(doc, m, 2, "tracks");
  return doc;
}

}  // namespace gpm::report
