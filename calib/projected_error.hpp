// The projected tracking error of paper section 2 (eq. 12-19): calibration of
// the encoder zero offsets from a tracked path. At desired end-effector points
// p_j the desired active angles are theta_a_hat_j = IK(p_j); the estimated actual
// angles are theta_m_j + dth (eq. 1). The tracking error d theta_a = theta_m + dth -
// theta_a_hat has a feasible part (an end-effector error, in the range of the
// eq. 11 Jacobian J_j) and an infeasible part P_j d theta_a, with
// P_j = I - J_j (J_j' J_j)^-1 J_j' (eq. 15). Only offset errors produce an
// infeasible part (eq. 18), so E(dth) = 1/n sum_j |P_j d theta_a_j|^2 (eq. 19) is
// minimal at the true offsets.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "models/robot.hpp"

namespace gpm::calib {

// P = I - J (J'J)^-1 J' (eq. 15) at the desired point p of the model, with J the
// eq. 11 Jacobian d theta_a / d(x, y). Throws InputError when p is out of reach.
Eigen::Matrix3d infeasible_projection(const Robot& model, const Eigen::Vector2d& p);

// E(dth) of eq. 19 for desired points and measured readings along a path
// (same length); model gives the geometry (its own offsets are ignored).
double projected_error(const Robot& model, const Eigen::Vector3d& dth,
                       const std::vector<Eigen::Vector2d>& desired,
                       const std::vector<Eigen::Vector3d>& theta_m);

// The offsets minimising E: E is quadratic in dth, so this is the linear least
// squares solution of P_j dth = -P_j (theta_m_j - theta_a_hat_j) over j (the
// section-2.4 search converges to the same point).
Eigen::Vector3d minimise_projected_error(const Robot& model, const std::vector<Eigen::Vector2d>& desired,
                                         const std::vector<Eigen::Vector3d>& theta_m);

}  // namespace gpm::calib
