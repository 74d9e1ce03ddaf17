// The section 4.4 comparison: all runs present, deterministic whatever the
// parallelism, and truthful about the paper's rank-deficient free set.
#include "calib/global/comparison.hpp"

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib::global {
namespace {

ComparisonSettings small(const FreeMask& free) {
  ComparisonSettings s;
  s.budget = 5'000;
  s.seeds = {1, 2};
  s.free = free;
  return s;
}

TEST(Comparison, EveryRunPresentAndIndependentOfParallelism) {
  ComparisonSettings a = small(default_free_mask());
  a.parallel_runs = 1;
  ComparisonSettings b = a;
  b.parallel_runs = 3;
  const Comparison ca = run_comparison(a), cb = run_comparison(b);
  ASSERT_EQ(ca.runs.size(), 18u);  // 3 methods x 3 costs x 2 seeds
  for (size_t i = 0; i < ca.runs.size(); ++i) {
    EXPECT_EQ(ca.runs[i].result.geometry, cb.runs[i].result.geometry);
    EXPECT_EQ(ca.runs[i].result.final_cost, cb.runs[i].result.final_cost);
    EXPECT_EQ(ca.runs[i].result.evaluations, 5'000);
  }
  EXPECT_EQ(ca.at_actual.rank, 11);
  const std::string md = comparison_markdown(ca);
  EXPECT_NE(md.find("| J3 |"), std::string::npos);
  EXPECT_NE(md.find("all free parameters identifiable"), std::string::npos);
  EXPECT_EQ(md.find("Not an identification"), std::string::npos);
  // One CSV row per run plus the header; one polyline per run of a cost.
  const std::string csv = comparison_runs_csv(ca);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 19);
  const std::string svg = comparison_svg(ca, Cost::kJ2);
  size_t lines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, 6u);
}

TEST(Comparison, PaperFreeSetIsReportedAsNotAnIdentification) {
  ComparisonSettings s = small(paper_free_mask());
  s.methods = {Method::kDE};
  s.costs = {Cost::kJ3};
  s.budget = 1'500'000;
  const Comparison c = run_comparison(s);
  ASSERT_EQ(c.runs.size(), 2u);
  EXPECT_EQ(c.at_actual.rank, 11);
  const std::string md = comparison_markdown(c);
  EXPECT_NE(md.find("Not an identification"), std::string::npos);
  EXPECT_NE(md.find("rank 11 of 12"), std::string::npos);
  EXPECT_NE(md.find("2 of 2 seeds reach the floating-point floor"), std::string::npos);
}

TEST(Comparison, RejectsEmptySettings) {
  ComparisonSettings s = small(default_free_mask());
  s.seeds.clear();
  EXPECT_THROW(run_comparison(s), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global
