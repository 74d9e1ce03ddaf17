// Tests of app/compare_report.cpp: the gpm compare report (Table 6 in
// Markdown, one polyline per run of a cost) and its truth about the paper's
// rank-deficient free set.
#include "app/compare_report.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"

namespace gpm::cli {
namespace {

using namespace calib::global;
using calib::Cost;
using calib::Method;
using calib::paper_free_mask;

ComparisonSettings small(const FreeMask& free) {
  ComparisonSettings s;
  s.budget = 5'000;
  s.seeds = {1, 2};
  s.free = free;
  return s;
}

TEST(CompareReport, TableAndOnePolylinePerRunOfACost) {
  const Comparison ca = run_comparison(small(default_free_mask()));
  ASSERT_EQ(ca.runs.size(), 18u);  // 3 methods x 3 costs x 2 seeds
  const std::string md = compare_markdown(ca);
  EXPECT_NE(md.find("| J3 |"), std::string::npos);
  EXPECT_NE(md.find("all free parameters identifiable"), std::string::npos);
  EXPECT_EQ(md.find("Not an identification"), std::string::npos);
  const std::string svg = compare_svg(ca, Cost::kJ2);
  size_t lines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, 6u);
}

TEST(CompareReport, PaperFreeSetIsReportedAsNotAnIdentification) {
  ComparisonSettings s = small(paper_free_mask());
  s.methods = {Method::kDE};
  s.costs = {Cost::kJ3};
  s.budget = 1'500'000;
  const Comparison c = run_comparison(s);
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_EQ(c.at_actual.rank, 11);
  const std::string md = compare_markdown(c);
  EXPECT_NE(md.find("Not an identification"), std::string::npos);
  EXPECT_NE(md.find("rank 11 of 12"), std::string::npos);
  EXPECT_NE(md.find("2 of 2 seeds reach the floating-point floor"), std::string::npos);
}

}  // namespace
}  // namespace gpm::cli
