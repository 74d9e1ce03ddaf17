// Differential evolution DE/rand/1/bin as the paper sets it (section 4.3).
#pragma once

#include <cstdint>

#include "calib/global/objective.hpp"

namespace gpm::calib::global {

// Paper section 4.4: N = 150, F = 0.5, CR = 0.8.
struct DeSettings {
  int population = 150;
  double f = 0.5;   // differential weight F (eq. 46)
  double cr = 0.8;  // crossover constant CR (eq. 47)
};

// Minimises obj with DE/rand/1/bin: V = X_r1 + F (X_r2 - X_r3) with r1, r2, r3
// distinct and != i (eq. 46); binomial crossover taking V_j when randb(j) <= CR
// or j = rnbr(i), else X_j (eq. 47, "and" per docs/EQUATIONS.md); components outside the
// box redrawn uniformly in it; U replaces X when f(U) <= f(X) (eq. 48, ties go
// to the trial as in Storn and Price). Generations are synchronous (all trials
// from generation G), so the whole population is evaluated at once. Never
// exceeds stop.budget evaluations; the same seed gives the same run.
RunRecord minimise_de(const BatchObjective& obj, const DeSettings& settings, const StopRule& stop,
                      uint64_t seed, const ProgressFn& progress = {});

}  // namespace gpm::calib::global
