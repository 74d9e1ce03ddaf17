#include "run/monitor_report_data.hpp"

namespace gpm::scenario {
namespace {

// One tracked parameter k at the end of the run and its track since the first estimate.
report::MonitorParameterRow parameter_row(const MonitorOutcome& o, int k) {
  const auto i = static_cast<std::size_t>(k);
  report::MonitorParameterRow p;
  p.name = std::string(param_name(k));
  if (o.truth_known) p.actual = o.final_truth.values[i];
  p.estimate = o.final_estimate.value[i];
  p.sigma = o.final_estimate.sigma[i];
  p.um_per_unit = is_offset(k) ? o.controller.geometry.la_(k - kDth1) * 1e3 : 1e3;  // um at the link tip
  for (const MonitorEstimateRow& r : o.estimates) p.change.push_back(r.value[i] - o.estimates.front().value[i]);
  return p;
}

}  // namespace

report::MonitorReport monitor_report_data(const MonitorOutcome& o) {
  const auto& st = o.model.settings;
  report::MonitorReport m{.simulated_s = o.simulated_s, .cycle_hz = st.cycle_hz, .cycles = o.cycles,
                          .hardware = o.hardware, .truth_known = o.truth_known, .false_alarms = o.false_alarms,
                          .false_alarms_per_hour = st.false_alarms_per_hour, .chi_threshold = o.model.threshold,
                          .window = st.window, .learning = learning_text(o)};
  const calib::ReadingModel& r = o.reading.reading;
  m.reading = {r.skew_s,        r.compliance_rad_per_Nm, r.load.coulomb_Nm,  r.load.viscous_Nm_s,
               r.cyclic_rad,    calib::pin_clearance_mm(r),     r.backlash_rad,     o.reading.thermal_time_constant_s};
  for (const MonitorDetection& d : o.detections) m.detections.push_back({d.event, d.at_s, d.detected_s, d.explanation});
  for (const MonitorAlarm& a : o.alarms) m.alarms.push_back({a.t_s, a.kind, a.statistic, a.threshold, a.explanation});
  for (int k = 0; k < kNumParams; ++k)
    if (st.estimate[static_cast<std::size_t>(k)]) m.parameters.push_back(parameter_row(o, k));
  for (const MonitorEstimateRow& e : o.estimates) m.track_t_s.push_back(e.t_s);
  return m;
}

}  // namespace gpm::scenario
