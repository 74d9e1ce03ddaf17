// Levenberg-Marquardt calibration (Ceres) of the free parameters of a Problem
// with one of the error functions J1, J2, J3, ML (calib/residuals.hpp):
// identifiability first (calib/identifiability.hpp), then the solve, then the
// 1-sigma of every estimated parameter (ceres::Covariance) and diagnostics.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "calib/problem.hpp"
#include "calib/robust_loss.hpp"

namespace gpm::calib {

struct LmOptions {
  Cost cost = Cost::kML;
  // Encoder noise (rad, 1-sigma, iid). Given: the covariance is the sandwich
  // (J'J)^-1 J' S J (J'J)^-1 with S the residuals' covariance under that noise
  // (for ML exactly sigma^2 (J'J)^-1, the Cramer-Rao bound at the solution).
  // Not given: sigma^2 is estimated from the residuals (sum r^2 / (n - p)).
  std::optional<double> encoder_sigma;
  // Solve a rank-deficient free set anyway with a minimum-norm (truncated-SVD)
  // Levenberg-Marquardt step, instead of refusing it.
  bool allow_rank_deficient = false;
  int max_iterations = 200;
  // Relative decrease of the cost below which LM stops (Ceres'
  // function_tolerance): the default polishes to the rounding floor.
  double function_tolerance = 1e-15;
  // Compute the covariance (a few ms); off for speed in benchmarks.
  bool compute_covariance = true;
  // Check the samples, analyse the free set's identifiability at the start
  // (refusing or noting rank deficiency, noting poor conditioning) and
  // compute kmrmse. Off: the free set is taken as identifiable and the
  // samples as checked, with no notes and no kmrmse (the inner passes of a
  // fit whose first and last solves make these checks).
  bool checks = true;
  // Differentiate the residuals with Ceres autodiff (the reference) instead
  // of the analytic Jacobians of calib/analytic_residuals.hpp; same result,
  // slower (for benchmarks and cross-checks).
  bool autodiff = false;
  // Robust loss per sample (calib/robust_loss.hpp; its scale must be set);
  // the covariance is then that of the robust problem.
  RobustLoss loss;
};

// Estimates problem.free from problem.theta_m starting at problem.start.
// Throws InputError for bad input: fewer samples than free parameters, a
// sample whose circles do not meet, J3 with only one of la_i/dth_i free, or a
// rank-deficient free set (one line naming the unobservable direction and
// what to fix) unless allow_rank_deficient. Result.converged is false when LM
// stops without meeting its tolerances. Result.notes carries warnings (poor
// conditioning, rank deficiency) for the caller to print. Result.kmrmse_mm
// (eq. 40) where problem.true_xy has one position per reading.
Result calibrate_lm(const Problem& problem, const LmOptions& options);

}  // namespace gpm::calib
