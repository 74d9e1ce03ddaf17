// Tests of report/paper_report.cpp: gpm paper's document (summary, one section
// per table with the printed values beside this run's and numbered reasons).
#include "report/paper_report.hpp"

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// Table 2 with one agreeing row and two rows differing for the same reason.
PaperTable table2() {
  PaperTable t;
  t.id = "table2";
  t.title = "Table 2. Zero positions";
  t.setup = "Generated data.";
  t.extra_column = "actual";
  t.rows.push_back({"dth1", "rad", 1.0, "1.0", 1.0, "1", "1", PaperReason::kAgrees, ""});
  t.rows.push_back({"dth2", "rad", 1.0, "1.0", 1.5, "1.5", "1", PaperReason::kPaperMistake, "A misprint."});
  t.rows.push_back({"dth3", "rad", 2.0, "2.0", 1.0, "1", "1", PaperReason::kPaperMistake, "A misprint."});
  t.notes = {"A finding."};
  return t;
}

TEST(PaperReport, SummaryRowsAndNumberedReasons) {
  const PaperDocument p{20000, 1, 12.0, {table2()}};
  EXPECT_EQ(paper_reason_cell(p.tables[0], p.tables[0].rows[0]), "agrees");
  EXPECT_EQ(paper_reason_cell(p.tables[0], p.tables[0].rows[2]), "[1] paper mistake");
  const std::string md = paper_document(p).markdown();
  EXPECT_NE(md.find("Budget 20000 error-function evaluations"), std::string::npos);
  EXPECT_NE(md.find("| Table 2 | 3 | 1 | 2 paper mistake |"), std::string::npos);
  const std::string table =
      "| quantity | unit | paper | this run | actual | difference | why |\n"
      "| --- | --- | --- | --- | --- | --- | --- |\n"
      "| dth1 | rad | 1.0 | 1 | 1 | 0 | agrees |\n"
      "| dth2 | rad | 1.0 | 1.5 | 1 | +0.5 | [1] paper mistake |\n"
      "| dth3 | rad | 2.0 | 1 | 1 | -1 | [1] paper mistake |\n";
  EXPECT_NE(md.find(table), std::string::npos);
  EXPECT_NE(md.find("- [1] A misprint.\n"), std::string::npos);
  EXPECT_NE(md.find("- A finding.\n"), std::string::npos);
}

TEST(PaperReport, ValuesWithSixSignificantDigits) {
  EXPECT_EQ(paper_value_text(0.0), "0");
  EXPECT_EQ(paper_value_text(1.23456789), "1.23457");
  EXPECT_EQ(paper_value_text(1.5e-7), "1.50000e-07");
  EXPECT_EQ(paper_reason_name(PaperReason::kSetup), std::string("different setup"));
}

TEST(PaperReport, ConvergenceFigureDrawsThePositivePointsOfEachCurve) {
  const std::string svg =
      paper_convergence_svg(3, "J1", {{"GA", {{0, 5.0}, {10, 1.0}, {100, 0.1}}}, {"DE", {{10, 2.0}, {50, 1.0}, {100, 0.0}}}});
  EXPECT_NE(svg.find("Figure 3: best J1 against evaluations"), std::string::npos);
  EXPECT_NE(svg.find(">GA<"), std::string::npos);
  EXPECT_NE(svg.find(">DE<"), std::string::npos);
  size_t lines = 0;
  for (size_t at = svg.find("<path d=\"M"); at != std::string::npos; at = svg.find("<path d=\"M", at + 1)) ++lines;
  EXPECT_EQ(lines, 2u);  // one line per curve; DE's J = 0 is left out
}

}  // namespace
}  // namespace gpm::report
