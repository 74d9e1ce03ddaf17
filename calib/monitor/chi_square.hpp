// Chi-square tail probabilities and quantiles for the change detector's
// threshold (calib/monitor/README.md): the regularised incomplete gamma
// functions P(a, x) + Q(a, x) = 1, with chi2_k's survival function
// Q(k/2, x/2). Series for x < a + 1, Legendre's continued fraction otherwise,
// both to double precision; no dependency beyond <cmath>.
#pragma once

namespace gpm::calib::monitor {

// Regularised lower incomplete gamma P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0.
double gamma_p(double a, double x);

// Regularised upper incomplete gamma Q(a, x) = 1 - P(a, x), accurate in the far
// tail (computed directly, not as 1 - P).
double gamma_q(double a, double x);

// Pr(X > x) for X ~ chi-square with dof degrees of freedom (dof > 0).
double chi2_survival(double dof, double x);

// The x with Pr(X > x) = p for X ~ chi-square(dof), 0 < p < 1 (relative
// accuracy ~1e-12): the threshold of a test whose false-alarm probability is p.
double chi2_upper_quantile(double dof, double p);

}  // namespace gpm::calib::monitor
