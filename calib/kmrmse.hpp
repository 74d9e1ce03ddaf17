// Kinematics model root mean square error (paper eq. 40): how far the
// end-effector computed from the readings with an estimated geometry lies from
// the true end-effector, over the samples. Millimetres.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib {

// sqrt(1/n sum_j |xy_j - FK(g, theta_m_j + dth)|^2) (eq. 40), FK by the radical
// centre (eq. 32-33, docs/EQUATIONS.md). Infinity if some sample has no forward kinematics.
double kmrmse(const Geometry& g, const std::vector<Eigen::Vector3d>& theta_m,
              const std::vector<Eigen::Vector2d>& xy);

}  // namespace gpm::calib
