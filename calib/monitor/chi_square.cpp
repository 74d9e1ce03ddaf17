#include "calib/monitor/chi_square.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace gpm::calib::monitor {
namespace {

constexpr double kEps = 1e-16;
constexpr int kMaxTerms = 100000;

// log of the common prefactor x^a e^-x / Gamma(a).
double log_prefactor(double a, double x) { return a * std::log(x) - x - std::lgamma(a); }

// P(a, x) by the series x^a e^-x / Gamma(a + 1) * sum_n x^n / ((a + 1) ... (a + n));
// converges quickly for x < a + 1.
double p_series(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < kMaxTerms; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEps) break;
  }
  return sum * std::exp(log_prefactor(a, x));
}

// Q(a, x) by Legendre's continued fraction
//   Q = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - 2 (2 - a) / (x + 5 - a - ...))),
// evaluated with the modified Lentz method; converges for x > a + 1.
double q_fraction(double a, double x) {
  constexpr double tiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / tiny;
  double d = 1.0 / b;
  double f = d;
  for (int n = 1; n < kMaxTerms; ++n) {
    const double an = -n * (n - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    f *= delta;
    if (std::abs(delta - 1.0) < kEps) break;
  }
  return std::exp(log_prefactor(a, x)) * f;
}

void check_args(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) throw std::invalid_argument("incomplete gamma: need a > 0 and x >= 0");
}

}  // namespace

double gamma_p(double a, double x) {
  check_args(a, x);
  if (x == 0.0) return 0.0;
  return x < a + 1.0 ? p_series(a, x) : 1.0 - q_fraction(a, x);
}

double gamma_q(double a, double x) {
  check_args(a, x);
  if (x == 0.0) return 1.0;
  return x < a + 1.0 ? 1.0 - p_series(a, x) : q_fraction(a, x);
}

double chi2_survival(double dof, double x) { return gamma_q(0.5 * dof, 0.5 * std::max(x, 0.0)); }

double chi2_upper_quantile(double dof, double p) {
  if (!(dof > 0.0) || !(p > 0.0 && p < 1.0))
    throw std::invalid_argument("chi2_upper_quantile: need dof > 0 and 0 < p < 1");
  // Bracket: the survival function falls monotonically from 1 at 0.
  double lo = 0.0, hi = std::max(1.0, dof);
  while (chi2_survival(dof, hi) > p) lo = hi, hi *= 2.0;
  // Bisection on log Q (smooth and monotone), then it is exact to the bracket.
  const double log_p = std::log(p);
  for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (std::log(chi2_survival(dof, mid)) > log_p) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace gpm::calib::monitor
