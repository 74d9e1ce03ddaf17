// Tests of report/population_report.cpp: gpm study population's summary,
// table (with the monitor's columns only when a robot was monitored) and
// figures from plain data.
#include "report/population_report.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// Two robots: one calibrated (la1 estimated), one failed.
PopulationReport two_robots() {
  PopulationReport p;
  p.name = "class";
  p.seconds = 12;
  p.summary.robots = 2;
  p.summary.failed = 1;
  p.summary.positioning_median_um = 9.4;
  p.summary.positioning_max_um = 9.4;
  p.summary.within_3_sigma_fraction = 1.0;
  p.summary.worst_sigma_ratio = 1.5;
  p.summary.model_test_pass_fraction = 1.0;
  p.summary.normalised_positioning_median = 1.05;
  PopulationRobotRow ok;
  ok.seed = 7;
  ok.positioning_rms_um = 9.4, ok.positioning_max_um = 20.0, ok.stated_sigma_rms_um = 8.0;
  ok.positioning_bound_um = 4.5;
  ok.calibrated_static_um = 3.0, ok.floor_ratio = 1.2, ok.model_test_passed = true, ok.chi2_per_dof = 1.1;
  ok.error.fill(NAN), ok.sigma.fill(NAN);
  ok.error[kLa1] = 0.003, ok.sigma[kLa1] = 0.002;
  ok.worst_param = "la1", ok.worst_sigma_ratio = 1.5, ok.estimated = 1, ok.within_3_sigma = 1, ok.seconds = 6;
  PopulationRobotRow failed;
  failed.seed = 8;
  failed.failure = "diverged";
  failed.seconds = 2;
  p.robots = {ok, failed};
  return p;
}

TEST(PopulationReport, SummaryAndOneRowPerRobot) {
  const PopulationReport p = two_robots();
  EXPECT_EQ(population_table_header(p).size(), 11u);
  const auto rows = population_table_rows(p);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"7", "9.40", "20.00", "8.00", "4.50", "1.50 (la1)", "1/1", "3.00",
                                               "1.20", "passes (1.10)", "6"}));
  EXPECT_EQ(rows[1].size(), rows[0].size());
  EXPECT_EQ(rows[1][1], "failed: diverged");
  const std::string md = population_markdown(p);
  EXPECT_NE(md.find("2 robots of `class` (every effect drawn per chain from its plausible range), 1 failed."),
            std::string::npos);
  EXPECT_EQ(md.find("Monitoring the operation"), std::string::npos);
  EXPECT_EQ(md.find("The least positioning RMS"), std::string::npos);  // no bound in the summary: no sentence
  const ReportDocument doc = population_report(p);
  ASSERT_EQ(doc.figure_files().size(), 2u);
  EXPECT_NE(doc.markdown().find("2 robots in 12 s."), std::string::npos);
}

TEST(PopulationReport, MonitorColumnsWhenARobotWasMonitored) {
  PopulationReport p = two_robots();
  p.robots[0].monitored = true;
  p.robots[0].event = true;
  p.robots[0].false_alarms = 0;
  p.robots[0].monitored_s = 30;
  p.robots[0].detection_delay_s = 0.25;
  p.robots[0].detection = "la1";
  p.summary.monitored = 1;
  EXPECT_EQ(population_table_header(p).size(), 16u);
  const auto rows = population_table_rows(p);
  EXPECT_EQ(rows[0][10], "0 in 30.0 s");
  EXPECT_EQ(rows[0][14], "0.250 (la1)");
  EXPECT_EQ(rows[1].size(), 16u);
  EXPECT_NE(population_markdown(p).find("Monitoring the operation after calibration (1 robots)"), std::string::npos);
}

TEST(PopulationReport, TheFloorRatioInTheSummary) {
  PopulationReport p = two_robots();
  EXPECT_EQ(population_markdown(p).find("over the floor's"), std::string::npos);  // not measured: not said
  p.summary.floor_ratio_median = 1.09, p.summary.robots_below_floor = 2;
  EXPECT_NE(population_markdown(p).find("median 1.09; 2 robots with its 95 % interval below 1."), std::string::npos);
}

TEST(PopulationReport, TheBoundsMedianInTheSummary) {
  PopulationReport p = two_robots();
  p.summary.positioning_bound_median_um = 4.5;
  EXPECT_NE(population_markdown(p).find("median 4.50 µm."), std::string::npos);
}

// The positioning figure marks each robot's bound where the study knows it.
TEST(PopulationReport, ThePositioningFigureMarksTheBoundsWhereKnown) {
  const auto positioning_svg = [](const PopulationReport& p) {
    for (const auto& [name, svg] : population_report(p).figure_files())
      if (name.find("population_positioning") != std::string::npos) return svg;
    return std::string();
  };
  PopulationReport p = two_robots();
  p.robots[0].positioning_bound_um = NAN;
  const std::string without = positioning_svg(p);
  ASSERT_FALSE(without.empty());
  EXPECT_EQ(without.find("the least RMS its readings allow"), std::string::npos);
  p.robots[0].positioning_bound_um = 4.5;
  EXPECT_NE(positioning_svg(p).find("the least RMS its readings allow"), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
