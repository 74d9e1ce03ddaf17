// Test helper of tests/calib/monitor: runs the monitor on the circle stream
// (circle_stream.hpp) for a given actual robot as a function of time and
// collects what the tests check.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "calib/monitor/monitor.hpp"
#include "tests/calib/monitor/circle_stream.hpp"

namespace gpm::calib::monitor::testing {

// Settings of the monitor without its configuration map, for the tests of
// the change tests, the filter and the learning phase on their own: the
// generated circle repeats exactly, its quantisation too, which the map would
// learn away (test_config_map.cpp tests the map).
inline MonitorSettings settings_without_map() {
  MonitorSettings s;
  s.map_radius_rad = 0.0;
  return s;
}

struct CircleRun {
  std::vector<Alarm> alarms;                   // explained alarms
  std::vector<double> alarm_times;             // crossings
  std::vector<Eigen::Vector3d> accepted;       // readings of accepted samples
  std::vector<double> z;                       // their innovations
  std::vector<std::pair<double, Estimate>> estimates;  // once per second
};

inline CircleRun run_circle(const MonitorModel& m, MonitorData& d, double duration_s,
                            const std::function<Geometry(double)>& actual, CircleStream cs = {}) {
  CircleRun out;
  const long n = static_cast<long>(duration_s * cs.rate_hz);
  for (long c = 0; c < n; ++c) {
    const double t = static_cast<double>(c) / cs.rate_hz;
    const Eigen::Vector3d theta_m = cs.readings(actual(t), t);
    const StepResult r = monitor_step(m, d, t, theta_m);
    if (r.accepted) out.accepted.push_back(theta_m), out.z.push_back(r.z);
    if (r.alarm) out.alarm_times.push_back(t);
    if (r.explained) out.alarms.push_back(last_alarm(d));
    if (c % static_cast<long>(cs.rate_hz) == 0) out.estimates.emplace_back(t, monitor_estimate(m, d));
  }
  return out;
}

// A fresh monitor of settings s run on the circle stream: its model, its
// data (large: on the heap) and what run_circle collected.
struct FreshRun {
  MonitorModel model;
  std::unique_ptr<MonitorData> data;
  CircleRun run;
};

inline FreshRun run_fresh(const MonitorSettings& s, double duration_s, const std::function<Geometry(double)>& actual,
                          CircleStream cs = {}) {
  FreshRun f{make_monitor_model(s), nullptr, {}};
  f.data = std::make_unique<MonitorData>(make_monitor_data(f.model));
  f.run = run_circle(f.model, *f.data, duration_s, actual, cs);
  return f;
}

}  // namespace gpm::calib::monitor::testing
