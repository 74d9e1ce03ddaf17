#include "calib/kmrmse.hpp"

#include <cmath>
#include <limits>

#include "models/kinematics.hpp"

namespace gpm::calib {

double kmrmse(const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m,
              const std::vector<Eigen::Vector2d>& xy) {
  if (theta_m.empty() || theta_m.size() != xy.size()) return std::numeric_limits<double>::quiet_NaN();
  double sum = 0.0;
  for (size_t j = 0; j < theta_m.size(); ++j) {
    const auto f = forward_kinematics(g, active_from_readings(g, theta_m[j]));
    if (!f) return std::numeric_limits<double>::infinity();
    sum += (xy[j] - f->p).squaredNorm();
  }
  return std::sqrt(sum / static_cast<double>(theta_m.size()));
}

}  // namespace gpm::calib
