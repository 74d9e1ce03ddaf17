// Global calibration (paper section 4): GA, PSO or DE on J1, J2 or J3 within a
// search box and a budget of error-function evaluations.
//
//   Problem p{readings, start, free};            // start: fixed values known
//   Box box = default_box(Geometry::gpm2002_nominal(), p.free);   // Table 5
//   Result r = solve_global(p, Cost::kJ3, Method::kDE, box, {.budget = 1'500'000, .seed = 7});
//
// r.geometry holds all 15 parameters, r.history (evaluations, best J), and
// r.rank / r.notes the identifiability diagnosis at the found point.
#pragma once

#include <cstdint>
#include <limits>

#include "calib/global/de.hpp"
#include "calib/global/decision_space.hpp"
#include "calib/global/ga.hpp"
#include "calib/global/objective.hpp"
#include "calib/global/pso.hpp"
#include "calib/problem.hpp"

namespace gpm::calib::global {

struct GlobalOptions {
  long budget = 1'500'000;  // error-function evaluations, never exceeded
  uint64_t seed = 1;
  // Threads evaluating each population: 0 = all cores. Results do not depend
  // on it. Default 1: a generation of 100-150 candidates takes ~10 us, so
  // fork/join only pays on an otherwise idle machine (see bench_global).
  int threads = 1;
  double target = -std::numeric_limits<double>::infinity();  // stop once best J <= target
  GaSettings ga;            // paper section 4.4 defaults
  PsoSettings pso;
  DeSettings de;
  // de+lm only: LM's iteration limit and whether it may solve a rank-deficient
  // free set (otherwise calibrate_lm refuses it with an InputError).
  int lm_max_iterations = 200;
  bool allow_rank_deficient = false;
};

// Minimises J (cost: kJ1, kJ2 or kJ3) over the free parameters of problem
// within box with the given method (kGA, kPSO, kDE, or kDELM: DE, then
// Levenberg-Marquardt, calib/lm.hpp, from DE's best point); fixed parameters
// keep problem.start.
// For de+lm the budget bounds DE; LM's evaluations are added to
// Result.evaluations and its end point to the history, and final_cost is J
// (this library's definition, eq. 37/39/43) at LM's estimate; sigma comes from LM.
// Throws InputError for kLM, an unsupported cost, an empty box or a budget < 1.
Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box,
                    const GlobalOptions& options, const ProgressFn& progress = {});

// The same with default settings, budget and seed.
Result solve_global(const Problem& problem, Cost cost, Method method, const Box& box, long budget,
                    uint64_t seed, const ProgressFn& progress = {});

}  // namespace gpm::calib::global
