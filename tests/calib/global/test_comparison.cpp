// Tests of calib/global/comparison.cpp: all runs present, deterministic
// whatever the parallelism; the paper's Table 6 values.
#include "calib/global/comparison.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "calib/global/synthetic.hpp"
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
  // One CSV row per run plus the header (the report: tests/app/test_compare_report.cpp).
  const std::string csv = comparison_runs_csv(ca);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 19);
}

TEST(Comparison, PaperTable6ValuesForGaPsoDe) {
  EXPECT_EQ(paper_table6(Method::kDe, Cost::kJ3), 3.5946e-20);
  EXPECT_EQ(paper_table6(Method::kGa, Cost::kJ1), 1.3447e3);
  EXPECT_TRUE(std::isnan(paper_table6(Method::kDe, Cost::kML)));
}

TEST(Comparison, RejectsEmptySettings) {
  ComparisonSettings s = small(default_free_mask());
  s.seeds.clear();
  EXPECT_THROW(run_comparison(s), gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global
