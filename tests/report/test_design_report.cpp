// Tests of report/design_report.cpp: gpm design --compare's table, CSV and
// figures from plain layouts and their bounds.
#include "report/design_report.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// A line (one bound infinite) and the optimised set, two free parameters.
DesignComparison two_layouts() {
  DesignComparison c{"robot.yaml", 3, 1e-4, default_free_mask(), 4.0, {}};
  c.layouts.push_back({"line", "a line", {{200, 250}, {210, 250}, {220, 250}}, {kXa3, kLa1},
                       Eigen::Vector2d(0.4, INFINITY), INFINITY, INFINITY, 1.5, kLa1});
  c.layouts.push_back({"optimised", "the design", {{150, 200}, {250, 300}, {216, 250}}, {kXa3, kLa1},
                       Eigen::Vector2d(0.1, 0.05), 0.1, 0.075, 9.25, kXa3});
  return c;
}

TEST(DesignReport, TableAgainstTheOptimisedSetAndTwoFigures) {
  const ReportDocument doc = design_comparison_report(two_layouts());
  const std::string md = doc.markdown();
  EXPECT_NE(md.find("| line | inf | la1 | inf | inf | 1.50 |"), std::string::npos);
  EXPECT_NE(md.find("| optimised | 0.1 | xa3 | 0.075 | 1 | 9.25 |"), std::string::npos);
  EXPECT_NE(md.find("- `line`: a line"), std::string::npos);
  EXPECT_NE(md.find("The optimised set is 4.0x better"), std::string::npos);
  const auto figures = doc.figure_files();
  ASSERT_EQ(figures.size(), 2u);
  EXPECT_EQ(figures[0].first, "design_comparison.svg");
  EXPECT_EQ(figures[1].first, "design_layouts.svg");
}

TEST(DesignReport, CsvRowPerLayoutWithEveryBound) {
  EXPECT_EQ(design_comparison_csv(two_layouts()),
            "layout,poses,worst_mm,worst_param,mean_mm,log_det,xa3_mm,la1_mm\n"
            "line,3,inf,la1,inf,1.5,0.4,inf\n"
            "optimised,3,0.1,xa3,0.075,9.25,0.1,0.05\n");
  EXPECT_EQ(design_bound_text(NAN), "inf");
  EXPECT_EQ(design_bound_text(0.123456), "0.1235");
}

}  // namespace
}  // namespace gpm::report
