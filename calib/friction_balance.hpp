// Each drive's friction from the closed chain's force balance at the hub.
//
// The passive links are two-force members (calib/passive_tension.hpp): link
// i pulls the hub C towards B_i with its tension T_i, so the hub (its own
// mass and half of each passive link's, m_C) moves by
//   sum_i T_i u_i = -m_C a_C,      u_i = (C - B_i) / |C - B_i|,
// and each active link's moment balance gives its tension from the torque
// the transmission passes on,
//   T_i = -tau_t_i / (la_i S_i),   S_i = sin(theta_b_i - theta_a_i),
//   tau_t_i = tau_i + q_i - F_i s_i - b_i omega_i - I_i alpha_i,   s_i = tanh(omega_i / v_F),
// q_i = A_i sin(P N theta_m_i) + B_i cos(P N theta_m_i) the motor's cogging
// (P periods per motor revolution, N the gear ratio; where P is given).
// Put together, two equations per sample, linear in the six frictions (and
// the six cogging coefficients):
//   sum_i u_i (F_i s_i + b_i omega_i - q_i) / (la_i S_i)
//       = sum_i u_i (tau_i - I_i alpha_i) / (la_i S_i) - m_C a_C.
// A torque-off drive (tau_i = 0) still has its friction seen: it is what
// moves its link against the other two chains. The drives' torques are the
// measurement; the geometry is the controller's (a millimetre of error in a
// 244 mm link is 0.4 % of a moment arm), a_C the second difference of the hub
// position over the readings. Rows are weighted by Huber's rule (stiction,
// cogging and the drives' start are outliers of this model, not its noise).
// With an error of 1-sigma sigma_T in each link's force, independent of the
// other links', the residual's two components have the variance
// sigma_T^2 sum_i |u_i|^2 / 2 = 1.5 sigma_T^2 (u_i unit vectors), so one
// link's force is known to sigma_T = residual_rms sqrt(2/3): what the
// clearance's force signs are judged by (run/calibration_procedure.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "calib/passive_tension.hpp"
#include "models/parameters.hpp"

namespace gpm::calib {

// What the balance estimated: each drive's Coulomb and viscous friction with 1-sigma.
struct BalanceFriction {
  std::array<double, 3> coulomb_Nm{};        // F_i (>= 0: a negative estimate is clipped to 0)
  std::array<double, 3> viscous_Nm_s{};      // b_i (>= 0, likewise)
  std::array<double, 3> coulomb_sigma_Nm{};  // their 1-sigma, from the rows' scatter
  std::array<double, 3> viscous_sigma_Nm_s{};
  // The cogging torque A_i sin(P N theta_m) + B_i cos(P N theta_m) (N m), A1 A2 A3 B1 B2 B3, and their
  // 1-sigma; 0 and NaN where the periods were not given.
  std::array<double, 6> cogging_Nm{};
  std::array<double, 6> cogging_sigma_Nm{};
  double residual_rms_N = 0.0;  // RMS of the balance's residual force (N) over the rows used
  double tension_sigma_N = 0.0; // 1-sigma of one passive link's force as the balance sees it (N):
                                // residual_rms_N sqrt(2/3) (below)
  std::size_t samples = 0;      // samples used (each two rows)
};

// The samples' share of what goes into the balance: readings theta_m (rad),
// joint speeds omega (rad/s) and accelerations alpha (rad/s^2), drive torques
// tau (N m) and the hub's acceleration a_C (m/s^2), one per sample.
struct BalanceSamples {
  const std::vector<Eigen::Vector3d>& theta_m;
  const std::vector<Eigen::Vector3d>& omega;
  const std::vector<Eigen::Vector3d>& alpha;
  const std::vector<Eigen::Vector3d>& tau;
  const std::vector<Eigen::Vector2d>& hub_accel_m_s2;
  double cogging_per_rad = 0.0;  // P N: the cogging's periods per joint radian (0: no cogging estimated)
};

// The cogging torque (N m) of joint i (0..2) that f estimated at reading theta_m (rad), with P N cogging_per_rad.
double cogging_torque(const BalanceFriction& f, int i, double theta_m, double cogging_per_rad);

// The hub's acceleration a_C (m/s^2) at each sample: forward kinematics of
// geometry g from the readings theta_m taken at times t_s, differenced as the
// joints' rates are (calib/reading_rates.hpp, acceleration span alpha_span).
std::vector<Eigen::Vector2d> hub_accelerations(const Geometry& g, const std::vector<double>& t_s,
                                               const std::vector<Eigen::Vector3d>& theta_m, int alpha_span);

// Estimates each drive's friction from samples s of geometry g (mm), with
// the inertias I_i and friction speed v_F of load (its frictions are not
// read), the hub's mass m_C (kg), the first skip_first samples left out and
// those where some |S_i| < min_sin (near a singularity the moment arm is
// lost). Throws InputError when the sizes differ or fewer than 20 samples remain.
BalanceFriction friction_from_force_balance(const Geometry& g, const BalanceSamples& s, const TransmissionLoad& load,
                                            double hub_mass_kg, int skip_first, double min_sin = 0.2);

}  // namespace gpm::calib
