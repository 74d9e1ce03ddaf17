// Axial force of a passive link, and what a change of its length does to a reading.
//
// The passive link B_i C of chain i is a two-force member (pinned at both
// ends, its own inertia neglected), so the force it puts on the active link at
// B_i lies along the unit vector u_i = (cos theta_b_i, sin theta_b_i) from B_i
// to C: T_i u_i, T_i > 0 in tension. The quasi-static moment balance of the
// active link about A_i, with tau_t_i the torque the transmission passes to it
// (drive torque less the motor-side friction), is
//   tau_t_i + la_i T_i (cos theta_a_i, sin theta_a_i) x u_i = 0
//   =>  T_i = -tau_t_i / (la_i sin(theta_b_i - theta_a_i)),
// so chain i alone gives the sign of its force: with radial clearance in both
// pins, the link sits at the end of its axial play in that direction.
//
// A passive length lb_i + d read at theta_a_i closes the loop exactly as
// length lb_i read at theta_a_i + d / (la_i sin(theta_b_i - theta_a_i)): moving
// B_i by la_i dtheta (-sin theta_a_i, cos theta_a_i) moves it away from C by
// la_i sin(theta_b_i - theta_a_i) dtheta (first order in d; the clearance is
// microns against a 244 mm link).
//
// The torque transmitted to the active link, as far as the moment balance
// needs it: the drive torque tau_i less the motor-side Coulomb friction
// F_i sign(omega_i) (smoothed over the speed v_F, TransmissionLoad::
// friction_speed_rad_s; v_F = 0: a sign step), the viscous friction b_i omega_i
// and the inertia I_i alpha_i of rotor and link about A_i:
//   tau_t_i = tau_i - F_i tanh(omega_i / v_F) - b_i omega_i - I_i alpha_i.
// One formula for the calibration (calib/motion_correction.hpp: v_F chosen by
// the model test) and the drift monitor (calib/monitor/monitor.hpp: v_F =
// 0.1 rad/s, no inertia).
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"

namespace gpm::calib {

// Joint speed below which Coulomb friction is treated as static (rad/s): the
// default of TransmissionLoad::friction_speed_rad_s.
inline constexpr double kFrictionSpeed = 0.01;

// What a transmission takes off the drive torque before it reaches the
// active link, per joint (stated: from the drive's data and the CAD model).
struct TransmissionLoad {
  std::array<double, 3> coulomb_Nm{};     // motor-side Coulomb friction F_i
  std::array<double, 3> viscous_Nm_s{};   // viscous friction b_i (per rad/s)
  std::array<double, 3> inertia_kg_m2{};  // rotor (reflected) plus active link about A_i
  std::array<double, 3> rotor_inertia_kg_m2{};  // the rotor alone, reflected to the joint (the mesh's load)
  double friction_speed_rad_s = kFrictionSpeed;  // v_F: the friction reaches tanh(1) = 76 % of F_i at this
                                                 // speed (a drive's friction builds up over a speed range:
                                                 // lubricant film, the seal's and the reducer's compliance);
                                                 // 0: F_i sign(omega_i)
};

// The friction's direction at joint speed omega (rad/s): tanh(omega / v_F)
// with load's friction speed v_F, or sign(omega) where v_F is 0.
double friction_sign(const TransmissionLoad& load, double omega);

// The torque transmitted to active link i (N m) at drive torque tau (N m),
// joint speed omega (rad/s) and acceleration alpha (rad/s^2).
double transmitted_torque(const TransmissionLoad& load, int i, double tau, double omega, double alpha);

// The torque the reducer's mesh of joint i carries (N m): the drive torque
// tau less the motor-side friction and the rotor's inertia,
// tau - F_i tanh(omega / v_F) - b_i omega - J_r_i alpha (the flank in contact is its sign).
double mesh_torque(const TransmissionLoad& load, int i, double tau, double omega, double alpha);

// mesh_torque of each joint of each sample (omega, tau, alpha per sample;
// alpha empty: 0).
std::vector<Eigen::Vector3d> mesh_torques(const TransmissionLoad& load, const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau,
                                          const std::vector<Eigen::Vector3d>& alpha);

// Axial force T_i (N, > 0 in tension) of passive link i (0..2) of geometry g
// (mm) at active angle theta_a and passive angle theta_b (rad), from the
// torque transmitted to the active link tau_t (N m).
double passive_link_tension(const Geometry& g, int i, double theta_a, double theta_b, double tau_t);

// The reading change (rad per mm) equivalent to lengthening passive link i
// by 1 mm at these angles: 1 / (la_i sin(theta_b - theta_a)).
double reading_per_passive_length(const Geometry& g, int i, double theta_a, double theta_b);

}  // namespace gpm::calib
