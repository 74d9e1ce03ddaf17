// Tests of report/monitor_report.cpp: the drift monitor's section (settings,
// events, alarms, tracked parameters and their tracks as small multiples
// with the alarms marked) and gpm monitor's lead, from plain data.
#include "report/monitor_report.hpp"

#include <regex>
#include <set>

#include <gtest/gtest.h>

#include "models/parameters.hpp"
#include "report_text_checks.hpp"

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
  m.detections = {{0, 1.0, 1.25, "la1 grew by 1.0e-03 mm"}, {1, 1.5, std::nullopt, ""}};
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
  EXPECT_NE(md.find("latch skew 1, 2, 3 µs"), std::string::npos);
  EXPECT_NE(md.find("| 0 | 1.000 | 1.250 | 0.250 | la1 grew by 0.0010 mm |\n| 1 | 1.500 | missed |  |  |\n"), std::string::npos);
  EXPECT_NE(md.find("## Alarms (first 20 of 21)"), std::string::npos);
  EXPECT_NE(md.find("| la1 | 244.00000 | 244.00100 | 1.00 | 0.50 |\n| dth1 | 0.0000000 | 0.0000010 | 0.24 | 0.24 |\n"), std::string::npos);
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
  EXPECT_NE(md.find("| la1 | unknown | 244.00100 |  | 0.50 |"), std::string::npos);
  EXPECT_TRUE(doc.figure_files().empty());
}

TEST(MonitorReport, GpmMonitorsReportIsTitledAndHoldsTheSection) {
  const ReportDocument doc = monitor_report("op", twin_run());
  const std::string md = doc.markdown();
  EXPECT_EQ(md.rfind("# gpm monitor: op\n\n**Over 2.0 s of normal operation the drift monitor raised 21 alarms (1 of "
                     "them false), the first at 0.00 s; it detected 1 of the scenario's 2 events, each within 0.25 s.**",
                     0),
            0u)
      << md;
  EXPECT_NE(md.find("## Tracked parameters at the end"), std::string::npos);
  EXPECT_EQ(doc.figure_files().size(), 1u);
}

TEST(MonitorReport, OneAlarmIsOneAlarm) {
  MonitorReport m = twin_run();
  m.alarms.resize(1);
  m.detections.resize(1);
  const std::string md = monitor_report("op", m).markdown();
  EXPECT_NE(md.find("raised 1 alarm (1 of them false), the first at 0.00 s; it detected the scenario's event 0.25 s "
                    "after it began."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("cycles at 1000 Hz), 1 alarm (1 false)"), std::string::npos);
  EXPECT_EQ(md.find("1 alarms"), std::string::npos);
}

TEST(MonitorReport, ElevenTracksInPanelsOfDistinctColoursWithTheAlarmsMarked) {
  MonitorReport m = twin_run();
  m.alarms.resize(1);
  m.alarms[0].t_s = 1.25;
  m.parameters.clear();
  for (int k = 4; k < kNumParams; ++k)  // the 11 free parameters of the default gauge
    m.parameters.push_back({std::string(param_name(k)), 1.0, 1.0, 1e-3, 1e3, {0.0, 1e-3 * k}});
  const std::string svg = monitor_report("op", m).figure_files().at(0).second;
  // Three panels (base coordinates, links, offsets), each its lines in distinct colours.
  const std::regex panel_title(">(Base joint coordinates|Link lengths|Encoder zero offsets)<");
  EXPECT_EQ(std::distance(std::sregex_iterator(svg.begin(), svg.end(), panel_title), std::sregex_iterator()), 3);
  size_t lines = 0;
  for (size_t at = svg.find("<svg x="); at != std::string::npos;) {
    const size_t next = svg.find("<svg x=", at + 1);
    const std::string panel = svg.substr(at, next == std::string::npos ? std::string::npos : next - at);
    std::set<std::string> colours;
    size_t n = 0;
    const std::regex line("<path d=\"M[^\"]*\" fill=\"none\" stroke=\"(#[0-9a-f]{6})\"");
    for (auto it = std::sregex_iterator(panel.begin(), panel.end(), line); it != std::sregex_iterator(); ++it)
      colours.insert((*it)[1]), ++n;
    EXPECT_EQ(colours.size(), n) << "a colour repeats within a panel";
    lines += n;
    at = next;
  }
  EXPECT_EQ(lines, 11u);
  // The alarm: a dashed red line labelled with its time, in every panel.
  const std::regex alarm("stroke=\"#d62728\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>\n<text[^>]*>alarm 1.25 s<");
  EXPECT_EQ(std::distance(std::sregex_iterator(svg.begin(), svg.end(), alarm), std::sregex_iterator()), 3);
  EXPECT_NE(svg.find(">event 0 at 1.00 s<"), std::string::npos);
}

TEST(MonitorReport, TablesAreValidMarkdownAndNoMarkdownLeaksIntoHtml) {
  const ReportDocument doc = monitor_report("monitor_offset_jump_realistic", twin_run());
  int tables = 0;
  EXPECT_TRUE(testing::markdown_table_errors(doc.markdown(), &tables).empty());
  EXPECT_EQ(tables, 3);
  const auto leaks = testing::leaked_markdown(doc.html("t"));
  EXPECT_TRUE(leaks.empty()) << leaks.front();
}

}  // namespace
}  // namespace gpm::report
