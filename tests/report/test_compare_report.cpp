// Tests of report/compare_report.cpp: gpm compare's Table 6, every run, the
// estimates of the shown cost, the verdict and one convergence line per run.
#include "report/compare_report.hpp"

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// Two methods on J1 and J3 from two seeds; DE reaches the floor, GA does not.
CompareReport two_methods(int rank) {
  CompareReport c;
  c.samples = 50;
  c.free = default_free_mask();
  c.budget = 1000;
  c.seeds = {1, 2};
  c.methods = {"ga", "de"};
  c.costs = {"j1", "j3"};
  c.paper_j = {{1.0, 2.0}, {3.0, 4.0}};
  c.diagnosis = "rank " + std::to_string(rank) + " of 11";
  c.rank = rank;
  c.free_count = 11;
  for (const std::string cost : {"j1", "j3"})
    for (const std::string method : {"ga", "de"})
      for (std::uint64_t seed : {1u, 2u}) {
        CompareRun r;
        r.method = method;
        r.cost = cost;
        r.seed = seed;
        r.final_cost = method == "de" ? 1e-20 : 1e-3 * static_cast<double>(seed);
        r.geometry[kLa1] += 0.01 * static_cast<double>(seed);
        r.history = {{0, 1.0}, {1000, r.final_cost}};
        c.runs.push_back(r);
      }
  return c;
}

TEST(CompareReport, Table6KeepsTheBestSeedAndThePaperValue) {
  const std::string md = compare_markdown(two_methods(11));
  EXPECT_NE(md.find("|  | GA | DE |\n| --- | --- | --- |\n"), std::string::npos);
  EXPECT_NE(md.find("| J3 | 1.0000e-03 (3.0000e+00) | 1.0000e-20 (4.0000e+00) |"), std::string::npos);
  EXPECT_NE(md.find("Estimates minus actual values, J3"), std::string::npos);
  EXPECT_NE(md.find("- DE on J3: 2 of 2 seeds reach the floating-point floor (J < 1e-16); the estimates of the "
                    "seeds differ by up to 0.01 mm."),
            std::string::npos);
  EXPECT_NE(md.find("The free parameters are identifiable (rank 11 of 11)"), std::string::npos);
}

TEST(CompareReport, RankDeficientIsNotAnIdentification) {
  EXPECT_NE(compare_markdown(two_methods(10)).find("**Not an identification.** rank 10 of 11."), std::string::npos);
}

TEST(CompareReport, OneLinePerRunOfTheCostInTheMethodsColour) {
  const std::string svg = compare_svg(two_methods(11), "j1");
  size_t lines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++lines;
  EXPECT_EQ(lines, 4u);
  EXPECT_NE(svg.find("#1f77b4"), std::string::npos);  // DE
  EXPECT_NE(svg.find("#d62728"), std::string::npos);  // GA
}

}  // namespace
}  // namespace gpm::report
