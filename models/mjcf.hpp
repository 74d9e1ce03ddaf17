// MJCF (MuJoCo XML) of a 3-RRR planar manipulator from any parameter set.
// Pure text generation: no MuJoCo dependency (sim/ loads the text).
//
// Layout (names are a contract for sim/, render/ and hw/):
//   body link_a{i}  hinge joint_a{i} about +Z at A_i   (active link, motor)
//   body link_b{i}  hinge joint_b{i} at the elbow B_i  (passive link)
//   body ee         welded to the tip of link_b1, site ee at the end-effector O
//   site tip_b{i}   at the free end of link_b{i} (tip_b1 coincides with ee)
//   equality close_b2, close_b3: <connect> tip of link_b2 / link_b3 to ee
//   actuator motor_a{i}: torque motor on joint_a{i} (gear 1, N m)
// Bodies are laid out already assembled at the actual inverse kinematics of
// robot.home (paper eq. 29-31), so <connect>, which takes its second anchor at
// qpos0, closes the loops exactly (DESIGN.md, MuJoCo facts). Joint qpos are
// absolute for joint_a (qpos = theta_a) and relative for joint_b
// (qpos = theta_b - theta_a). Metres inside MuJoCo; millimetres outside.
#pragma once

#include <string>

#include "models/robot.hpp"

namespace gpm {

// The one place where millimetres become metres for MuJoCo.
inline constexpr double kMetresPerMm = 1e-3;

// Mass, drive and solver properties of the MJCF (GPM2002-sized defaults; the
// reasoning behind each number is in mjcf.cpp).
struct MjcfOptions {
  double timestep_s = 0.0005;          // physics step; servo loops run at a multiple
  double active_link_mass_kg = 0.40;   // aluminium bar 244 x 40 x 15 mm
  double passive_link_mass_kg = 0.25;  // aluminium bar 244 x 30 x 12 mm
  double ee_mass_kg = 0.10;            // end-effector hub and tool
  double link_radius_m = 0.012;        // capsule radius (visual only; contacts are off)
  double active_damping = 0.05;        // N m s/rad, gearbox viscous friction (output side)
  double passive_damping = 0.002;      // N m s/rad, ball-bearing elbow and end-effector joints
  double armature_kg_m2 = 0.0026;      // reflected rotor inertia, 0.26e-4 kg m^2 x 10^2
  double solref_timeconst_s = 0.001;   // equality constraint time constant (>= 2 timesteps)
  double solref_dampratio = 1.0;
  double solimp_dmin = 0.9999;         // equality constraint impedance at zero violation
  double solimp_dmax = 0.9999;         // ... and beyond solimp_width_m
  double solimp_width_m = 0.001;
};

// MJCF text of the mechanism with the given (actual) parameters, assembled at
// robot.home. Throws InputError if the parameters cannot assemble there.
std::string mjcf_from_robot(const Robot& actual, const MjcfOptions& options = {});

}  // namespace gpm
