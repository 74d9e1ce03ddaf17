// Tests of report/effects_report.cpp: gpm study effects' table, figures and
// parameter errors per procedure from plain data.
#include "report/effects_report.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// One procedure estimating la1 and dth1 on two cases (the second failed).
EffectsReport one_procedure() {
  EffectsReport e;
  e.realistic.compliance_rad_per_Nm = 1e-4;
  e.procedures = {{"stop_and_go", "stop and go", {kLa1, kDth1}}};
  e.cases = {"ideal", "all"};
  EffectsRow ideal;
  ideal.procedure = "stop_and_go", ideal.effect = "ideal";
  ideal.error.fill(NAN);
  ideal.error[kLa1] = 0.002, ideal.error[kDth1] = 1e-6;
  ideal.worst_param = "la1", ideal.worst_error_um = 2.0, ideal.worst_crb_param = "la1", ideal.worst_crb_ratio = 1.25;
  ideal.calibrated_um = 3.0, ideal.floor_um = 2.0, ideal.floor_ratio = 1.5, ideal.model_test_passed = true;
  EffectsRow all;
  all.procedure = "stop_and_go", all.effect = "all", all.failure = "refused";
  all.error.fill(NAN);
  all.worst_error_um = all.worst_crb_ratio = all.calibrated_um = all.floor_um = all.floor_ratio = NAN;
  e.rows = {ideal, all};
  e.seconds = 5;
  return e;
}

TEST(EffectsReport, OneRowPerCaseAndTheFailureInTheModelTestColumn) {
  const auto rows = effects_table_rows(one_procedure().rows);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"stop_and_go", "ideal", "la1", "2.0", "1.25 (la1)", "3.0", "2.0",
                                               "1.50", "passes"}));
  EXPECT_EQ(rows[1][8], "- (refused)");
  EXPECT_EQ(effects_table_header().size(), 9u);
}

TEST(EffectsReport, ReportHoldsTheTableThreeFiguresAndTheParameterErrors) {
  const EffectsReport e = one_procedure();
  const ReportDocument doc = effects_report(e);
  const std::string md = doc.markdown();
  EXPECT_NE(md.find("transmission compliance 0.0001 rad/N m"), std::string::npos);
  EXPECT_NE(md.find(effects_markdown_table(e.rows)), std::string::npos);
  EXPECT_NE(md.find("| effect | la1 (um) | dth1 (urad) |\n| --- | --- | --- |\n| ideal | 2.0 | 1.0 |\n| all | - | - |"),
            std::string::npos);
  EXPECT_EQ(doc.figure_files().size(), 3u);
  EXPECT_NE(md.find("2 runs in 5 s."), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
