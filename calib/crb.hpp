// Cramer-Rao bound of the free parameters for given sample poses and iid
// encoder noise sigma (rad). Each sample gives one scalar closure constraint
// P(theta*; params) = 0 on its true readings theta*; eliminating the pose, the
// Fisher information is sum_j g_j g_j' / sigma^2 with g_j = (dP/dparams) /
// |dP/dtheta_m| at the truth, i.e. J_ml' J_ml / sigma^2 with J_ml the Jacobian
// of the ML residual (calib/residuals.hpp) at noiseless readings.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib {

// The Fisher information J_ml' J_ml / sigma^2 on the free parameters (ordered
// by index); use it directly rather than inverting the bound (ill-conditioned).
Eigen::MatrixXd fisher_information(const Geometry& truth, const FreeMask& free,
                                   const std::vector<Eigen::Vector3d>& theta_m, double sigma);

// The bound sigma^2 (J_ml' J_ml)^-1 on the free parameters (ordered by index),
// from the noiseless readings theta_m of the true geometry.
Eigen::MatrixXd cramer_rao_bound(const Geometry& truth, const FreeMask& free,
                                 const std::vector<Eigen::Vector3d>& theta_m, double sigma);

// Square roots of the bound's diagonal in the 15 slots (NaN for fixed ones).
std::array<double, kNumParams> crb_sigma(const Geometry& truth, const FreeMask& free,
                                         const std::vector<Eigen::Vector3d>& theta_m, double sigma);

}  // namespace gpm::calib
