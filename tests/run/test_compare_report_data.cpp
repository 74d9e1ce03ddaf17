// Tests of run/compare_report_data.cpp: a comparison of global methods copied
// into gpm compare's report (Table 6 in Markdown, one polyline per run of a
// cost) and the report's truth about the paper's rank-deficient free set.
#include "run/compare_report_data.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"

namespace gpm::scenario {
namespace {

using calib::Cost;
using calib::Method;
using calib::global::Comparison;
using calib::global::ComparisonSettings;

// The comparison of the given methods on the given costs from seeds 1 and 2.
Comparison compared(const FreeMask& free, std::vector<Method> methods, std::vector<Cost> costs, long budget) {
  ComparisonSettings s;
  s.free = free;
  s.methods = std::move(methods);
  s.costs = std::move(costs);
  s.budget = budget;
  s.seeds = {1, 2};
  return calib::global::run_comparison(s);
}

TEST(CompareReportData, TableAndOnePolylinePerRunOfACost) {
  const Comparison c = compared(default_free_mask(), {Method::kGA, Method::kPSO, Method::kDE},
                                {Cost::kJ1, Cost::kJ2, Cost::kJ3}, 5'000);
  const report::CompareReport data = compare_report_data(c);
  ASSERT_EQ(data.runs.size(), 18u);  // 3 methods x 3 costs x 2 seeds
  EXPECT_EQ(data.methods, (std::vector<std::string>{"ga", "pso", "de"}));
  EXPECT_DOUBLE_EQ(data.paper_j[2][0], calib::global::paper_table6(Method::kGA, Cost::kJ3));
  const std::string md = report::compare_markdown(data);
  EXPECT_NE(md.find("| J3 |"), std::string::npos);
  EXPECT_NE(md.find("all free parameters identifiable"), std::string::npos);
  EXPECT_EQ(md.find("Not an identification"), std::string::npos);
  const std::string svg = report::compare_svg(data, "j2");
  size_t lines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, 6u);
}

TEST(CompareReportData, PaperFreeSetIsReportedAsNotAnIdentification) {
  const Comparison c = compared(calib::paper_free_mask(), {Method::kDE}, {Cost::kJ3}, 1'500'000);
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_EQ(c.at_actual.rank, 11);
  const std::string md = report::compare_markdown(compare_report_data(c));
  EXPECT_NE(md.find("Not an identification"), std::string::npos);
  EXPECT_NE(md.find("rank 11 of 12"), std::string::npos);
  EXPECT_NE(md.find("2 of 2 seeds reach the floating-point floor"), std::string::npos);
}

}  // namespace
}  // namespace gpm::scenario
