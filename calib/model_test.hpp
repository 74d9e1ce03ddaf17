// Goodness-of-fit test of a calibrated model against the encoder noise.
//
// Under the model, every ML residual r_j (calib/residuals.hpp: the closure
// power over the norm of its gradient with respect to the readings, i.e. the
// smallest reading correction that closes the loops) is N(0, sigma^2) to first
// order, with sigma the 1-sigma reading error. At the least-squares solution
// with p free parameters and n samples,
//   chi2 = sum_j r_j^2 / sigma^2  ~  chi-square(n - p),
// and the p-value is Pr(X > chi2). A p-value below alpha says that the
// readings disagree with the rigid kinematic model by more than the encoders
// can explain: an unmodelled effect (transmission compliance under servo
// preload, joint clearance, thermal growth, encoder error) or outlier samples.
// The two are told apart by how the excess is spread over the samples.
//
// A joint that may rest (calib/sample_weights.hpp) holds a twist the reading
// model knows only within +-c F: that sample's residual has the variance
// lambda_j sigma^2, lambda_j = sigma_j^2 / sigma^2 >= 1. The test still sums
// the residuals unweighted, by sigma alone (a weight would let misfit where a
// joint is slow hide in the doubt), but expects what that doubt adds on
// average: chi2 = sum lambda_j z_j^2 has mean dof + D, D = sum (lambda_j - 1),
// and variance 2 (dof + E), E = sum (lambda_j^2 - 1), taken as g
// chi-square(h) of the same mean and variance (Satterthwaite): g = (dof + E)
// / (dof + D), h = (dof + D)^2 / (dof + E). The doubt is the one the model
// states, c the data sheet's compliance and F the drives' friction the
// calibration takes (calib/motion_correction.hpp MotionFit::doubt), not the
// fitted twist c F, which a misfit where the joints are slow inflates.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib {

// What the samples' stated doubts add to the unweighted chi-square under the
// model (above); 0, 0 without weights.
struct SampleDoubt {
  double mean = 0.0;    // D = sum (lambda_j - 1)
  double spread = 0.0;  // E = sum (lambda_j^2 - 1)
};

// The doubt of samples of weights w (each in (0, 1]; none: 0, 0).
SampleDoubt sample_doubt(const Eigen::VectorXd& w);

// Pr(chi2 > x) under the model with dof degrees of freedom and the samples'
// doubt (above; chi2_survival(dof, x) without doubt).
double doubted_chi2_survival(double dof, const SampleDoubt& doubt, double x);

struct ModelTest {
  double chi2 = 0.0;       // sum of squared normalised ML residuals, less carried_chi2
  double carried_chi2 = 0.0;  // what errors carried within their priors explain of that sum
  double doubt_chi2 = 0.0;    // D: what the samples' stated doubts add to it on average (expected, not taken off)
  double dof = 0.0;        // n - p
  double p_value = 1.0;    // Pr(chi-square(dof) > chi2), with the samples' doubt expected
  double sigma_rad = 0.0;  // the reading noise the test assumed
  double rms_ratio = 0.0;  // sqrt(chi2 / dof): residual RMS over the noise (1 under the model)
  double alpha = 0.01;     // significance level
  bool passed = true;      // p_value >= alpha
  // When failed: one sentence naming the likely cause and what to do.
  std::string diagnosis;
  // Sample indices of the largest normalised residuals, largest first (at most 5).
  std::vector<long> worst_samples;
  // When failed on the fly: the reading effects the motion model leaves out
  // that the residuals call for, largest share first (set by the procedure:
  // calib/motion_correction.hpp left_out_effects).
  std::vector<std::string> calls_for;
};

// The chi-square that columns Gp (the fitted columns projected out, one per
// carried value, each value of 1-sigma prior a priori) explain of residuals r
// with noise variance sigma2, the share the marginal test takes off:
//   chi2(r) - min_c (|r - Gp c|^2 / sigma2 + |c|^2 / prior^2)
//     = u' (sigma2 / prior^2 I + Gp' Gp)^-1 u / sigma2,  u = Gp' r.
// Zero without columns; throws InputError for prior or sigma2 <= 0.
double carried_chi2(const Eigen::MatrixXd& Gp, const Eigen::VectorXd& r, double prior, double sigma2);

// Chi-square test of the ML residuals of readings theta_m at geometry g with
// `free` estimated (p = free count), assuming reading noise sigma (rad) and
// significance alpha. Throws InputError for sigma <= 0, alpha outside (0, 1)
// or no degrees of freedom (n <= p). carried_chi2 (>= 0): of the residuals'
// chi-square, what errors carried within their priors explain (the marginal
// test: calib::MotionFit::carried_chi2); the test weighs chi2 less it.
// doubt: the samples' stated doubts (calib::MotionFit::doubt), expected.
ModelTest model_test(const Geometry& g, const FreeMask& free,
                     const std::vector<Eigen::Vector3d>& theta_m, double sigma,
                     double alpha = 0.01, double carried_chi2 = 0.0, const SampleDoubt& doubt = {});

}  // namespace gpm::calib
