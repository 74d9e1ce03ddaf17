#include "calib/monitor/learning.hpp"

#include <algorithm>
#include <cmath>

namespace gpm::calib::monitor {
namespace {

double median_of(double* v, int n) {
  double* mid = v + n / 2;
  std::nth_element(v, mid, v + n);
  const double hi = *mid;
  if (n % 2) return hi;
  const double lo = *std::max_element(v, mid);
  return 0.5 * (lo + hi);
}

// A variance factor estimated from `batches` batch statistics, widened to the
// upper end of its uncertainty, one standard error up (relative standard
// error of a variance from k batches: sqrt(2 / (k - 1))), never below 1.
double widened(double factor, int batches) {
  if (batches < 2) return std::max(1.0, factor);
  return std::max(1.0, factor * (1.0 + std::sqrt(2.0 / (batches - 1))));
}

}  // namespace

LearnedScale learn_innovation_scale(const double* z, int n, int batch, double scale_floor, double* scratch) {
  LearnedScale out;
  if (n < 2) {
    out.scale = std::max(1.0, scale_floor);
    return out;
  }
  out.samples = n;
  std::copy(z, z + n, scratch);
  out.median = median_of(scratch, n);
  for (int j = 0; j < n; ++j) scratch[j] = std::abs(z[j] - out.median);
  out.mad_scale = 1.4826 * median_of(scratch, n);
  const double s = std::max(out.mad_scale, 1e-12);

  // Batch means and batch sums of squares of z' = (z - median) / s.
  batch = std::clamp(batch, 1, n);
  const int batches = n / batch;
  double sum_m = 0.0, sum_m2 = 0.0, sum_q = 0.0, sum_q2 = 0.0;
  for (int b = 0; b < batches; ++b) {
    double m = 0.0, q = 0.0;
    for (int j = b * batch; j < (b + 1) * batch; ++j) {
      const double u = (z[j] - out.median) / s;
      m += u;
      q += u * u;
    }
    m /= batch;
    sum_m += m, sum_m2 += m * m;
    sum_q += q, sum_q2 += q * q;
  }
  double step = 1.0, var_q = 2.0 * batch, mean_q = 1.0;
  if (batches >= 2) {
    const double var_m = (sum_m2 - sum_m * sum_m / batches) / (batches - 1);
    var_q = (sum_q2 - sum_q * sum_q / batches) / (batches - 1);
    step = batch * var_m;          // 1 for independent unit samples
    mean_q = sum_q / (batches * static_cast<double>(batch));  // 1 for standard normal samples
  }
  out.effective_samples = n / std::max(step, 1.0);
  // The scale the tests use: the upper end of the MAD's uncertainty (relative
  // standard error 1.1 / sqrt(n_eff)), never below the stated model.
  const double upper = out.mad_scale * (1.0 + 2.0 * 1.1 / std::sqrt(std::max(out.effective_samples, 1.0)));
  out.scale = std::max({upper, scale_floor, 1.0});
  // The factors were measured in units of the MAD scale; the tests divide by
  // `scale` instead, which is larger: rescale (a factor never below 1).
  const double r2 = (s / out.scale) * (s / out.scale);
  out.step_factor = widened(step * r2, batches);
  // Satterthwaite: a window sum of W z''^2 (z'' = z' s / scale) has mean
  // W mu and variance (W / B) var_q r2^2; as kappa chi2_nu, kappa = var /
  // (2 mean), nu = mean / kappa. mu is widened by two standard errors.
  const double mu = r2 * (mean_q + (batches >= 2 ? 2.0 * std::sqrt(var_q / batches) / batch : 0.0));
  out.chi_mean = mu;
  out.chi_factor = widened(r2 * r2 * var_q / (2.0 * batch * std::max(mu, 1e-12)), batches);
  return out;
}

double chi2_quantile_wilson_hilferty(double dof, double z_p) {
  const double c = 2.0 / (9.0 * dof);
  const double b = 1.0 - c + z_p * std::sqrt(c);
  return dof * b * b * b;
}

double wilson_hilferty_normal_quantile(double dof, double threshold) {
  const double c = 2.0 / (9.0 * dof);
  return (std::cbrt(threshold / dof) - 1.0 + c) / std::sqrt(c);
}

}  // namespace gpm::calib::monitor
