// The calibration entry point of `gpm calibrate` and `gpm run`: one call for
// every method, Ceres LM (calib/lm.hpp), GA, PSO, DE (calib/global) and DE
// followed by LM.
//
//   MethodOptions o;  o.method = parse_method("de+lm");  o.cost = Cost::kML;
//   Result r = calibrate(problem, o);
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "calib/global/objective.hpp"
#include "calib/problem.hpp"
#include "calib/robust_loss.hpp"

namespace gpm::calib {

struct MethodOptions {
  Method method = Method::kLM;
  Cost cost = Cost::kML;
  long budget = 1500000;      // error-function evaluations of the global stage
  int lm_max_iterations = 200;
  std::uint64_t seed = 1;
  std::optional<double> encoder_sigma;
  bool allow_rank_deficient = false;
  // Robust loss of the LM stage (lm, de+lm). Without a scale: 2.385 sigma
  // (Cauchy) or 1.345 sigma (Huber), the 95 %-efficiency tunings under
  // Gaussian noise, with sigma = encoder_sigma or, when not given, 1.4826 x
  // the median absolute residual of a plain fit (which also starts the robust one).
  RobustLoss loss;
  // Called as the global stage spends its budget (evaluations, budget, best J); empty: none.
  global::ProgressFn progress;
};

// Solves problem with the chosen method. Global stages use J1/J2/J3 (ML is
// LM only: for `de+lm` with cost ml, DE runs on J3 and LM refines on ML).
// Throws InputError for a cost the method cannot use, a robust loss with
// ga, pso or de (and whatever the solver throws for bad input).
Result calibrate(const Problem& problem, const MethodOptions& options);

}  // namespace gpm::calib
