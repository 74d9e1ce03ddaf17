// Chi-square tail probabilities and quantiles (Boost.Math's regularised
// incomplete gamma: Pr(chi2_k > x) = Q(k/2, x/2)), for the model test after a
// calibration (calib/model_test.hpp) and the drift monitor's thresholds
// (calib/monitor/README.md).
#pragma once

namespace gpm::calib {

// Pr(X > x) for X ~ chi-square with dof degrees of freedom (dof > 0, x >= 0).
double chi2_survival(double dof, double x);

// The x with Pr(X > x) = p for X ~ chi-square(dof), 0 < p < 1: the threshold
// of a test whose false-alarm probability is p.
double chi2_upper_quantile(double dof, double p);

// The share of a fit's misfit above the noise (its chi-square chi2_before
// less its degrees of freedom dof_before) that a larger model, fitted to the
// same residuals, takes away: (chi2_before - chi2_after) / (chi2_before -
// dof_before); 0 where the fit before has none (chi2_before <= dof_before).
double misfit_share(double chi2_before, double dof_before, double chi2_after);

}  // namespace gpm::calib
