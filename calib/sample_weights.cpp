// Weights of the samples the friction leaves uncertain (calib/sample_weights.hpp).
#include "calib/sample_weights.hpp"

#include <cmath>

namespace gpm::calib {

double stick_speed(double q_rad, double dt_s) { return q_rad > 0.0 && dt_s > 0.0 ? q_rad / dt_s : 0.0; }

double rest_twist_variance(double omega, double twist_rad, double v_s) {
  if (!(v_s > 0.0)) return 0.0;
  const double t = std::tanh(omega / v_s);
  return twist_rad * twist_rad * (1.0 - t * t) / 3.0;
}

double sign_flip_variance(double T_N, double sigma_N, double k_rad_per_mm) {
  if (!(sigma_N > 0.0)) return 0.0;
  const double p = 0.5 * std::erfc(std::abs(T_N) / (sigma_N * std::sqrt(2.0)));
  return 4.0 * k_rad_per_mm * k_rad_per_mm * p * (1.0 - p);
}

double sample_weight(const Eigen::Vector3d& u, const Eigen::Vector3d& v, double sigma) {
  const double u2 = u.squaredNorm();
  if (!(sigma > 0.0) || !(u2 > 0.0)) return 1.0;
  return 1.0 / std::sqrt(1.0 + u.cwiseProduct(u).dot(v) / u2 / (sigma * sigma));
}

}  // namespace gpm::calib
