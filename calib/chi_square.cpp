// Chi-square tails (calib/chi_square.hpp) through Boost.Math.
#include "calib/chi_square.hpp"

#include <cmath>
#include <stdexcept>

#include <boost/math/special_functions/gamma.hpp>

namespace gpm::calib {

double chi2_survival(double dof, double x) {
  if (!(dof > 0.0) || !(x >= 0.0)) throw std::invalid_argument("chi-square survival: need dof > 0 and x >= 0");
  if (std::isinf(x)) return 0.0;
  return boost::math::gamma_q(0.5 * dof, 0.5 * x);
}

double chi2_upper_quantile(double dof, double p) {
  if (!(dof > 0.0) || !(p > 0.0 && p < 1.0))
    throw std::invalid_argument("chi-square quantile: need dof > 0 and 0 < p < 1");
  return 2.0 * boost::math::gamma_q_inv(0.5 * dof, p);
}

double misfit_share(double chi2_before, double dof_before, double chi2_after) {
  const double excess = chi2_before - dof_before;
  return excess > 0.0 ? (chi2_before - chi2_after) / excess : 0.0;
}

}  // namespace gpm::calib
