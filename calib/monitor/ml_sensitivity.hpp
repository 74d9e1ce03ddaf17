// The ML residual of one set of readings and its gradient with respect to the
// 15 parameters, for the monitor's per-cycle use: the project's MlResidual
// functor (calib/residuals.hpp: r = P / |dP/d theta_m|, the closure power of
// calib/closure.hpp divided by the norm of its gradient with respect to the
// readings) evaluated on forward-mode dual numbers (ceres::Jet), so no
// allocation and no second copy of the closure mathematics.
#pragma once

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib::monitor {

using ParamRow = Eigen::Matrix<double, 1, kNumParams>;

// r = P / |dP/d theta_m| (rad) at geometry g and readings theta_m, and
// dr/dparams (rad per mm or rad per rad). False (outputs untouched) when the
// elbows are collinear or the gradient vanishes (no ML residual).
bool ml_residual_and_gradient(const Geometry& g, const Eigen::Vector3d& theta_m, double& r,
                              ParamRow& dr_dparams);

}  // namespace gpm::calib::monitor
