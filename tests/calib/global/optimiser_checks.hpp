// Checks shared by the GA, PSO and DE tests: a run on a test function stays
// within its budget, reaches a tolerance, and repeats exactly for one seed.
#pragma once

#include <gtest/gtest.h>

#include "tests/calib/global/test_functions.hpp"

namespace gpm::calib::global::testing {

// Runs minimise(obj, stop, seed) twice and checks budget, tolerance, the
// history and reproducibility.
template <class Minimise, class F>
void expect_minimises(Minimise minimise, F f, double lo, double hi, long budget, double tol,
                      uint64_t seed) {
  auto counter = std::make_shared<long>(0);
  const BatchObjective obj = make_objective(f, lo, hi, counter);
  const RunRecord a = minimise(obj, StopRule{budget}, seed);
  EXPECT_LE(*counter, budget);                    // counted by the objective itself
  EXPECT_EQ(a.evaluations, *counter);             // the run's own count is honest
  EXPECT_GE(a.evaluations, budget - 200);         // and the budget was used
  EXPECT_LT(a.best_f, tol) << "seed " << seed;
  ASSERT_EQ(static_cast<int>(a.best_x.size()), kDim);
  EXPECT_EQ(f(a.best_x.data()), a.best_f);        // best_x is the point of best_f
  for (int k = 0; k < kDim; ++k) {
    EXPECT_GE(a.best_x[k], lo);
    EXPECT_LE(a.best_x[k], hi);
  }
  ASSERT_FALSE(a.history.empty());
  EXPECT_EQ(a.history.back().first, a.evaluations);
  EXPECT_EQ(a.history.back().second, a.best_f);
  for (size_t i = 1; i < a.history.size(); ++i) {
    EXPECT_GT(a.history[i].first, a.history[i - 1].first);
    EXPECT_LE(a.history[i].second, a.history[i - 1].second);
  }
  const RunRecord b = minimise(obj, StopRule{budget}, seed);
  EXPECT_EQ(a.best_x, b.best_x);
  EXPECT_EQ(a.best_f, b.best_f);
  EXPECT_EQ(a.history, b.history);
}

// A budget that ends in the middle of a generation (and one smaller than
// the population) is honoured exactly; a different seed gives a different run.
template <class Minimise>
void expect_budget_and_seed(Minimise minimise) {
  for (long budget : {1L, 37L, 1234L}) {
    auto counter = std::make_shared<long>(0);
    const BatchObjective obj = make_objective(sphere, -5, 5, counter);
    const RunRecord r = minimise(obj, StopRule{budget}, 7);
    EXPECT_EQ(*counter, budget);
    EXPECT_EQ(r.evaluations, budget);
  }
  auto counter = std::make_shared<long>(0);
  const BatchObjective obj = make_objective(sphere, -5, 5, counter);
  EXPECT_NE(minimise(obj, StopRule{5000}, 1).best_x, minimise(obj, StopRule{5000}, 2).best_x);
  // A target stops the run early.
  const RunRecord t = minimise(obj, StopRule{1'000'000, 1e-6}, 3);
  EXPECT_LE(t.best_f, 1e-6);
  EXPECT_LT(t.evaluations, 1'000'000);
}

}  // namespace gpm::calib::global::testing
