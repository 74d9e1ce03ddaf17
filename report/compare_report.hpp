// The report of `gpm compare` (paper section 4.4): the Markdown table6.md and
// the convergence figures, from the plain numbers of a comparison of global
// methods at equal budget.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "models/parameters.hpp"

namespace gpm::report {

// One run of one method on one error function from one seed.
struct CompareRun {
  std::string method, cost;  // lower-case names: "ga", "j3"
  std::uint64_t seed = 0;
  double final_cost = 0.0, seconds = 0.0;
  long evaluations = 0;
  int rank = 0;
  double max_error_mm = 0.0, max_error_rad = 0.0, kmrmse_mm = 0.0;
  Geometry geometry;                             // the estimate
  std::vector<std::pair<long, double>> history;  // (evaluations, best J)
};

// Everything the comparison report shows.
struct CompareReport {
  std::size_t samples = 0;
  std::uint64_t data_seed = 0;
  FreeMask free;
  long budget = 0;
  std::vector<std::uint64_t> seeds;
  double seconds = 0.0;
  std::vector<std::string> methods, costs;  // lower-case names, in the table's order
  std::vector<std::vector<double>> paper_j;  // the paper's Table 6: [cost][method]
  std::string diagnosis;                     // identifiability at the actual parameters
  int rank = 0, free_count = 0;              // at the actual parameters
  Geometry actual;
  std::vector<CompareRun> runs;
};

// Markdown report: settings, a Table 6 (best J per algorithm and cost, paper
// values beside), the identifiability diagnosis, parameter errors of every
// run against Table 5, the spread across seeds and a verdict.
std::string compare_markdown(const CompareReport& c);

// SVG figure of log10(J) against evaluations for one cost (Figs. 3-5).
std::string compare_svg(const CompareReport& c, const std::string& cost);

}  // namespace gpm::report
