// A box-bounded objective evaluated over a whole population at once, and the
// record of one optimiser run (paper section 4: budgets in evaluations).
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace gpm::calib::global {

// Called now and then during a run with (evaluations so far, budget, best J).
using ProgressFn = std::function<void(long evaluations, long budget, double best)>;

// f(x) for `count` candidates stored parameter-major: coordinate k of
// candidate c is x[k * stride + c]; writes f[c]. Must not depend on how the
// population is split (each f[c] a function of candidate c alone).
using BatchFn = std::function<void(const double* x, long stride, long count, double* f)>;

// The objective an optimiser minimises over the box lower <= x <= upper.
struct BatchObjective {
  std::vector<double> lower;
  std::vector<double> upper;
  BatchFn evaluate;

  int dim() const { return static_cast<int>(lower.size()); }
};

// When to stop: the budget of evaluations is never exceeded; target stops
// early once the best value is <= target.
struct StopRule {
  long budget = 1'000'000;
  double target = -std::numeric_limits<double>::infinity();
};

// Outcome of one run of GA, PSO or DE.
struct RunRecord {
  std::vector<double> best_x;
  double best_f = std::numeric_limits<double>::infinity();
  long evaluations = 0;
  long generations = 0;
  std::vector<std::pair<long, double>> history;  // (evaluations, best f), log-spaced
};

}  // namespace gpm::calib::global
