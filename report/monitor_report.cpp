#include "report/monitor_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/svg_plot.hpp"
#include "report/table_cell.hpp"

namespace gpm::report {
namespace {

// v to 3 significant digits, trailing zeros dropped ("1", "0.25"), a power of ten outside 1e-3 .. 1e6.
std::string g3(double v) {
  const double a = std::abs(v);
  return a == 0.0 || (a >= 1e-3 && a < 1e6) ? fmt::format("{:.3g}", v) : sci(v, 3);
}

// "a, b, c" of a per-joint value times scale, 3 significant digits.
std::string three(const std::array<double, 3>& v, double scale) {
  return fmt::format("{}, {}, {}", g3(v[0] * scale), g3(v[1] * scale), g3(v[2] * scale));
}

// "1 alarm", "2 alarms".
std::string counted(size_t n, const char* noun) { return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s"); }

// The operation, the learning phase and the reading model assumed.
void add_settings(ReportDocument& doc, const MonitorReport& m) {
  doc.paragraph(fmt::format("{:.1f} s of normal operation ({} servo cycles at {:.0f} Hz{}), {}{}, "
                            "stated false-alarm rate {} per hour (chi-square threshold {:.1f} over {} samples).",
                            m.simulated_s, m.cycles, m.cycle_hz, m.hardware.empty() ? "" : " through " + m.hardware,
                            counted(m.alarms.size(), "alarm"),
                            m.truth_known ? fmt::format(" ({} false)", m.false_alarms) : "",
                            m.false_alarms_per_hour, m.chi_threshold, m.window));
  doc.paragraph(fmt::format("Learning: {}.", readable_text(m.learning)));
  const MonitorReadingRow& r = m.reading;
  doc.paragraph(fmt::format(
      "Reading model assumed (joints 1, 2, 3): latch skew {} µs; compliance {} rad/N m; drive friction {} N m "
      "and {} N m s/rad; cyclic encoder error {} µrad; pin clearance {} µm; backlash {} µrad; drift time constant "
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
                    d.detected_s ? fmt::format("{:.3f}", *d.detected_s - d.at_s) : "", readable_text(d.explanation)});
  doc.table({"event", "at (s)", "detected (s)", "delay (s)", "explanation"}, rows);
}

// The first 20 alarms.
void add_alarms(ReportDocument& doc, const std::vector<MonitorAlarmRow>& alarms, int level) {
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < alarms.size() && k < 20; ++k) {
    const MonitorAlarmRow& a = alarms[k];
    rows.push_back({fmt::format("{:.3f}", a.t_s), a.kind, fmt::format("{:.1f}", a.statistic),
                    fmt::format("{:.1f}", a.threshold), readable_text(a.explanation)});
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
      errs.push_back({p.name, "unknown", value_to_sigma(p.estimate, p.sigma), "", sigma});
      continue;
    }
    errs.push_back({p.name, value_to_sigma(*p.actual, p.sigma), value_to_sigma(p.estimate, p.sigma),
                    fmt::format("{:.2f}", (p.estimate - *p.actual) * p.um_per_unit), sigma});
  }
  doc.heading(level, "Tracked parameters at the end");
  doc.table({"parameter", "actual", "estimate", "error (µm at the link)", "1σ (µm at the link)"}, errs);
}

// The panel of a parameter: 0 base coordinates, 1 links, 2 encoder offsets.
int panel_of(const std::string& name) { return name.starts_with("dth") ? 2 : name.starts_with("l") ? 1 : 0; }

// The alarms (the first 5) and the events' starts as vertical marks.
std::vector<XMark> track_marks(const MonitorReport& m) {
  std::vector<XMark> marks;
  for (const MonitorEventRow& e : m.detections)
    marks.push_back({e.at_s, fmt::format("event {} at {:.2f} s", e.event, e.at_s), "#555555", false});
  for (size_t k = 0; k < m.alarms.size() && k < 5; ++k)
    marks.push_back({m.alarms[k].t_s,
                     m.alarms.size() > 5 && k == 4 ? fmt::format("alarm {:.2f} s (5 of {} marked)", m.alarms[k].t_s,
                                                                  m.alarms.size())
                                                   : fmt::format("alarm {:.2f} s", m.alarms[k].t_s),
                     "#d62728", true});
  return marks;
}

// Parameter tracks: estimate minus the value at the start, in µm at the link,
// as small multiples (base coordinates, links, offsets: at most six lines a
// panel, each its own colour) with the alarms and events marked; empty
// without tracks.
std::string tracks_figure(const MonitorReport& m) {
  if (m.track_t_s.empty()) return "";
  static const char* const kTitles[] = {"Base joint coordinates", "Link lengths", "Encoder zero offsets"};
  std::vector<std::string> panels;
  for (int panel = 0; panel < 3; ++panel) {
    std::vector<Series> series;
    for (const MonitorParameterRow& p : m.parameters) {
      if (panel_of(p.name) != panel) continue;
      Series sr;
      sr.label = p.name;
      sr.color = palette_color(series.size());
      sr.x = m.track_t_s;
      for (double c : p.change) sr.y.push_back(c * p.um_per_unit);
      series.push_back(sr);
    }
    if (series.empty()) continue;
    PlotOptions po = titled_plot(kTitles[panel], "t (s)", "change since start (µm at the link)");
    po.height = 260;
    po.x_marks = track_marks(m);
    panels.push_back(svg_plot(series, po));
  }
  return panels.empty() ? "" : svg_stack(panels);
}

}  // namespace

void add_monitor_section(ReportDocument& doc, const MonitorReport& m, int level, const std::string& figure) {
  add_settings(doc, m);
  if (!m.detections.empty()) add_detections(doc, m.detections);
  if (!m.alarms.empty()) add_alarms(doc, m.alarms, level);
  add_final_estimates(doc, m.parameters, level);
  const std::string svg = tracks_figure(m);
  if (!svg.empty())
    doc.figure(figure,
               "Parameter tracks of the drift estimator, one panel per kind of parameter; dashed red: alarms, grey: "
               "the scenario's events",
               svg);
}

std::string monitor_lead(const MonitorReport& m) {
  std::string s = fmt::format("Over {:.1f} s of normal operation the drift monitor raised {}", m.simulated_s,
                              counted(m.alarms.size(), "alarm"));
  if (m.truth_known) s += fmt::format(" ({} of them false)", m.false_alarms);
  if (!m.alarms.empty()) s += fmt::format(", the first at {:.2f} s", m.alarms.front().t_s);
  size_t found = 0;
  double worst = 0.0;
  for (const MonitorEventRow& d : m.detections)
    if (d.detected_s) ++found, worst = std::max(worst, *d.detected_s - d.at_s);
  if (m.detections.size() == 1)
    s += found ? fmt::format("; it detected the scenario's event {:.2f} s after it began", worst)
               : std::string("; it missed the scenario's event");
  else if (!m.detections.empty())
    s += fmt::format("; it detected {} of the scenario's {} events", found, m.detections.size()) +
         (found > 0 ? fmt::format(", each within {:.2f} s", worst) : std::string());
  return s + ".";
}

ReportDocument monitor_report(const std::string& scenario_name, const MonitorReport& m) {
  ReportDocument doc;
  doc.heading(1, fmt::format("gpm monitor: {}", scenario_name));
  doc.lead(monitor_lead(m));
  add_monitor_section(doc, m, 2, "tracks");
  return doc;
}

}  // namespace gpm::report
