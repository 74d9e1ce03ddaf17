// The equal-budget comparison of paper section 4.4: GA, PSO and DE on J1, J2
// and J3 with simulated Table 5 data, several seeds, and what the results
// mean for identifiability: the numbers (the report and figures are written
// by app/compare_report.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "calib/global/global.hpp"
#include "calib/global/identifiability.hpp"
#include "models/samples.hpp"

namespace gpm::calib::global {

struct ComparisonSettings {
  long budget = 1'500'000;             // per run, evaluations of the error function
  std::vector<uint64_t> seeds{1, 2, 3};
  int samples = 50;                    // random workspace points (section 4.4)
  uint64_t data_seed = 42;
  FreeMask free;                       // 12 free (paper) or 11 (xa1, ya1, xa2, ya2 fixed)
  std::vector<Method> methods{Method::kGa, Method::kPso, Method::kDe};
  std::vector<Cost> costs{Cost::kJ1, Cost::kJ2, Cost::kJ3};
  int parallel_runs = 0;               // runs executed at once (0 = all cores); each run is serial
};

struct ComparisonRun {
  Method method;
  Cost cost;
  uint64_t seed;
  Result result;
  double kmrmse_mm = 0.0;       // eq. 40 against the true end-effector points
  double max_error_mm = 0.0;    // largest |estimate - actual| over free lengths and coordinates
  double max_error_rad = 0.0;   // largest |estimate - actual| over free offsets
};

struct Comparison {
  ComparisonSettings settings;
  Geometry actual;
  Samples samples;
  Identifiability at_actual;    // rank at the true parameters
  std::vector<ComparisonRun> runs;  // methods x costs x seeds, in that nesting order
  double seconds = 0.0;
};

// Called from the calling thread about twice a second: (evaluations done,
// evaluations in total, runs finished, runs in total).
using ComparisonProgress = std::function<void(long done, long total, int runs_done, int runs)>;

// Runs every method on every cost for every seed with the same budget.
// Deterministic: the same settings give the same numbers whatever the number
// of parallel runs. Throws InputError for empty seeds, methods or costs.
Comparison run_comparison(const ComparisonSettings& settings,
                          const ComparisonProgress& progress = {});

// CSV, one row per run: method, cost, seed, J, evaluations, seconds, rank,
// errors, kmrmse and the 15 estimated parameters.
std::string comparison_runs_csv(const Comparison& c);

// CSV of all convergence histories: method, cost, seed, evaluations, best J.
std::string comparison_history_csv(const Comparison& c);

// Paper Table 6: best J after 5e7 evaluations with 12 free parameters, for
// GA, PSO, DE on J1, J2, J3 (NaN for another cost).
double paper_table6(Method m, Cost c);

}  // namespace gpm::calib::global
