// Tests of calib/monitor/monitor.cpp over one hour of simulated operation
// (CTest label long): no false alarm with 17-bit encoders, without and with a
// thermal warm-up (20 um per link, tau 60 s), at the stated rate of 0.01
// false alarms per hour.
#include <cmath>

#include <gtest/gtest.h>

#include "calib/monitor/monitor.hpp"
#include "tests/calib/monitor/run_circle.hpp"

namespace gpm::calib::monitor {
namespace {

TEST(MonitorLong, NoFalseAlarmInOneHour) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  ASSERT_DOUBLE_EQ(m.settings.false_alarms_per_hour, 0.01);
  MonitorData d = make_monitor_data(m);
  const Geometry g = m.settings.geometry;
  const auto run = testing::run_circle(m, d, 3600.0, [&](double) { return g; });
  EXPECT_EQ(run.alarm_times.size(), 0u);
  EXPECT_GT(d.accepted, 500000);
}

TEST(MonitorLong, NoFalseAlarmInOneHourWithThermalWarmUp) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  MonitorData d = make_monitor_data(m);
  const Geometry base = m.settings.geometry;
  const auto run = testing::run_circle(m, d, 3600.0, [&](double t) {
    Geometry g = base;
    for (int i = 0; i < 3; ++i) {
      g[la(i)] += 0.020 * (1.0 - std::exp(-t / 60.0));
      g[lb(i)] += 0.020 * (1.0 - std::exp(-t / 60.0));
    }
    return g;
  });
  EXPECT_EQ(run.alarm_times.size(), 0u);
}

}  // namespace
}  // namespace gpm::calib::monitor
