// Initial values of the encoder zero offsets by the paper's reference-point
// procedure (section 3.2, step 3): move the end-effector by hand to a known
// reference point (e.g. home), read the encoders there, and take
// dth_i = theta_a0_i - theta_m0_i with theta_a0 the inverse kinematics of the
// reference point (eq. 35 solved for dth).
#pragma once

#include <Eigen/Core>

#include "models/robot.hpp"

namespace gpm::calib {

// model.geometry with its three offsets replaced by IK(reference) - readings,
// wrapped to (-pi, pi]. Throws InputError when the reference point is out of
// reach of the model.
Geometry offsets_from_reference(const Robot& model, const Eigen::Vector3d& theta_m_ref,
                                const Eigen::Vector2d& reference_xy);

}  // namespace gpm::calib
