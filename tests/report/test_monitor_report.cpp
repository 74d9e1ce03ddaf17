// Tests of report/monitor_report.cpp: the drift monitor's section (settings,
// events, alarms, tracked parameters and their tracks) from plain data.
#include "report/monitor_report.hpp"

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// A twin run of 2 s: one event detected, 21 alarms, two tracked parameters.
MonitorReport twin_run() {
  MonitorReport m;
  m.simulated_s = 2.0;
  m.cycle_hz = 1000;
  m.cycles = 2000;
  m.false_alarms = 1;
  m.false_alarms_per_hour = 0.01;
  m.chi_threshold = 321.5;
  m.window = 250;
  m.learning = "no learning phase";
  m.reading.skew_s = {1e-6, 2e-6, 3e-6};
  m.reading.thermal_time_constant_s = 60;
  m.detections = {{0, 1.0, 1.25, "la1 grew"}, {1, 1.5, std::nullopt, ""}};
  for (int k = 0; k < 21; ++k) m.alarms.push_back({0.1 * k, "step", 40.0, 30.0, "la1"});
  m.parameters = {{"la1", 244.0, 244.001, 0.0005, 1e3, {0.0, 0.001}}, {"dth1", 0.0, 1e-6, 1e-6, 244e3, {0.0, 1e-6}}};
  m.track_t_s = {0.0, 2.0};
  return m;
}

TEST(MonitorReport, SettingsEventsAlarmsAndFinalEstimates) {
  ReportDocument doc;
  add_monitor_section(doc, twin_run(), 2, "tracks");
  const std::string md = doc.markdown();
  EXPECT_NE(md.find("2.0 s of normal operation (2000 servo cycles at 1000 Hz), 21 alarms (1 false), stated "
                    "false-alarm rate 0.01 per hour (chi-square threshold 321.5 over 250 samples)."),
            std::string::npos);
  EXPECT_NE(md.find("latch skew 1, 2, 3 us"), std::string::npos);
  EXPECT_NE(md.find("| 0 | 1.000 | 1.250 | 0.250 | la1 grew |\n| 1 | 1.500 | missed |  |  |\n"), std::string::npos);
  EXPECT_NE(md.find("## Alarms (first 20 of 21)"), std::string::npos);
  EXPECT_NE(md.find("| la1 | 244 | 244.001 | 1.00 | 0.50 |\n| dth1 | 0 | 1e-06 | 0.24 | 0.24 |\n"), std::string::npos);
  ASSERT_EQ(doc.figure_files().size(), 1u);
  EXPECT_EQ(doc.figure_files()[0].first, "tracks.svg");
}

TEST(MonitorReport, ThroughHardwareTheTruthIsUnknownAndNoTrackWithoutEstimates) {
  MonitorReport m = twin_run();
  m.truth_known = false;
  m.hardware = "modbus";
  for (auto& p : m.parameters) p.actual.reset();
  m.track_t_s.clear();
  ReportDocument doc;
  add_monitor_section(doc, m, 3, "tracks");
  const std::string md = doc.markdown();
  EXPECT_NE(md.find("cycles at 1000 Hz through modbus), 21 alarms, stated"), std::string::npos);
  EXPECT_NE(md.find("| la1 | unknown | 244.001 |  | 0.50 |"), std::string::npos);
  EXPECT_TRUE(doc.figure_files().empty());
}

TEST(MonitorReport, GpmMonitorsReportIsTitledAndHoldsTheSection) {
  const ReportDocument doc = monitor_report("op", twin_run());
  const std::string md = doc.markdown();
  EXPECT_EQ(md.rfind("# gpm monitor: op\n", 0), 0u);
  EXPECT_NE(md.find("## Tracked parameters at the end"), std::string::npos);
  EXPECT_EQ(doc.figure_files().size(), 1u);
}

}  // namespace
}  // namespace gpm::report
