// Hub pin offsets: the three passive links' distal pins on the end-effector
// hub are not one point but each offset by a small vector p_i (hub frame) from
// the hub centre O, the end-effector point. The hub is then a small plate
// with a rotation phi of its own: pin i sits at O + R(phi) p_i. The 15
// kinematic parameters cannot hold this (they have one common pin), so it is
// a model error a calibration must live with.
// MJCF (models/mjcf.cpp, only when an offset is non-zero): body ee at the tip
// of link_b1 is pin 1, with a hinge hub_r (the plate's rotation, at rest
// world-aligned at home), site ee at -p_1 (the hub centre) and sites pin_b2,
// pin_b3 at p_i - p_1 where chains 2 and 3 close (connect or clearance tendon).
// Zero offsets: the layout of mjcf.hpp byte for byte.
#pragma once

#include <string>

#include "models/kinematics.hpp"
#include "models/mjcf.hpp"

namespace gpm {

// Joint angles that assemble the mechanism with its hub centre at p (mm) and
// the hub world-aligned: chain i reaches p + p_i (eq. 29-31 per chain); the
// plain inverse kinematics when no offset is set. Throws ReachError.
JointAngles hub_assembly_ik(const Geometry& g, const Eigen::Vector2d& p, const Branches& branch,
                            const MjcfEffects& fx);

// MJCF text of body ee with offset pins, inside link_b1 (indent in), at the
// link's tip lb_m (m); theta_b1 the passive link's absolute angle at home (rad).
std::string hub_pin_body(const std::string& in, double lb_m, double theta_b1, const MjcfOptions& o);

// Name of the hub site where chain i (1, 2) closes: pin_b{i+1} with offsets, else ee.
std::string hub_site(const MjcfEffects& fx, int i);

}  // namespace gpm
