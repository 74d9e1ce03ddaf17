// DE (paper section 4.3, N = 150, F = 0.5, CR = 0.8) on 12-D test functions.
#include "calib/global/de.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "tests/calib/global/optimiser_checks.hpp"

namespace gpm::calib::global::testing {
namespace {

const auto de = [](const BatchObjective& o, const StopRule& s, uint64_t seed) {
  return minimise_de(o, DeSettings{}, s, seed);
};

TEST(De, SphereTo1e15Within1e5) {
  for (uint64_t seed : {1, 2}) expect_minimises(de, sphere, -5, 5, 100'000, 1e-15, seed);
}

TEST(De, RosenbrockTo1e10Within3e5) {
  for (uint64_t seed : {1, 2}) expect_minimises(de, rosenbrock, -2.048, 2.048, 300'000, 1e-10, seed);
}

// DE/rand/1/bin with CR = 0.8 is known to be weak on separable multimodal
// Rastrigin; the paper's setting still gets from about 200 (random points)
// to below 15.
TEST(De, RastriginBelow15Within1e6) {
  expect_minimises(de, rastrigin, -5.12, 5.12, 1'000'000, 15.0, 1);
}

TEST(De, BudgetExactAndSeedsDiffer) { expect_budget_and_seed(de); }

// Eq. 47 with "and" (the printed "or j != rnbr(i)" would take every
// coordinate from the mutant): with CR = 0 a trial takes exactly one
// coordinate, j = rnbr(i), from the mutant; with CR = 1 all of them. A flat
// objective makes every trial win (ties go to the trial, eq. 48), so member
// i's next trial is compared with its previous one.
TEST(De, CrossoverTakesTheMutantWhereRandbIsAtMostCrAndAtRnbr) {
  for (double cr : {0.0, 1.0}) {
    const int n = 6;
    const long np = 10;
    std::vector<std::vector<double>> trials;  // in evaluation order
    BatchObjective o;
    o.lower.assign(n, -1.0);
    o.upper.assign(n, 1.0);
    o.evaluate = [&](const double* x, long stride, long count, double* f) {
      for (long c = 0; c < count; ++c) {
        std::vector<double> v(n);
        for (int k = 0; k < n; ++k) v[static_cast<size_t>(k)] = x[k * stride + c];
        trials.push_back(v);
        f[c] = 1.0;
      }
    };
    minimise_de(o, DeSettings{static_cast<int>(np), 0.5, cr}, StopRule{np * 5}, 3);
    ASSERT_EQ(trials.size(), static_cast<size_t>(np * 5));
    for (size_t t = static_cast<size_t>(np); t < trials.size(); ++t) {
      int changed = 0;
      for (int k = 0; k < n; ++k) changed += trials[t][static_cast<size_t>(k)] != trials[t - np][static_cast<size_t>(k)];
      if (cr == 0.0) EXPECT_EQ(changed, 1) << "trial " << t;
      else EXPECT_EQ(changed, n) << "trial " << t;
    }
  }
}

TEST(De, RejectsTinyPopulation) {
  auto counter = std::make_shared<long>(0);
  EXPECT_THROW(minimise_de(make_objective(sphere, -1, 1, counter), DeSettings{3, 0.5, 0.8},
                           StopRule{100}, 1),
               gpm::InputError);
}

}  // namespace
}  // namespace gpm::calib::global::testing
