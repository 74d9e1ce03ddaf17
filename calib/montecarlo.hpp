// Monte-Carlo study of calibration accuracy against the Cramer-Rao bound
// (calib/crb.hpp): fixed sample poses, many trials of iid encoder noise, an LM
// calibration per trial and cost, and the empirical RMS error of each
// parameter over its bound.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"

namespace gpm::calib {

struct MonteCarloOptions {
  Geometry actual;                  // the true geometry (default: paper Table 5)
  Geometry start;                   // the start of every LM run (nominal, fixed ones true)
  FreeMask free;                    // default: all but xa1, ya1, xa2, ya2
  int trials = 50;
  int samples = 50;
  double radius_mm = 80.0;          // sample poses uniform in this disc around home
  double sigma = 1e-4;              // encoder noise (rad)
  std::uint64_t seed = 1;
  std::vector<Cost> costs{Cost::kML, Cost::kJ3};
};

// The defaults above, filled in (Table 5 actual values, nominal start).
MonteCarloOptions default_montecarlo_options();

struct MonteCarloRow {
  Cost cost = Cost::kML;
  std::array<double, kNumParams> rms_error{};  // empirical RMS error per parameter (NaN if fixed)
  std::array<double, kNumParams> bound{};      // sqrt of the CRB diagonal
  std::array<double, kNumParams> ratio{};      // rms_error / bound
  std::array<double, kNumParams> mean_reported_sigma{};  // average 1-sigma the solver reported
  double max_ratio = 0.0;
  // sqrt(mean over parameters of ratio^2): the per-parameter goal with the
  // sampling noise of 50 trials (about 10% per parameter) averaged down.
  double rms_ratio = 0.0;
  // sqrt(mean over trials of e' CRB^-1 e / p): 1 for an efficient estimator,
  // the whole-vector counterpart of the per-parameter ratio (less noisy).
  double normalised_ratio = 0.0;
  int failures = 0;  // trials that did not converge
};

// Runs the study; one row per cost, in options.costs order.
std::vector<MonteCarloRow> run_montecarlo(const MonteCarloOptions& options);

}  // namespace gpm::calib
