// Weights of the samples whose reading model the drives' friction leaves
// uncertain: a rotor that may be at rest, a passive link whose force sign
// may be wrong.
//
// A rotor at rest. The reading model's friction twist, c_i F_i tanh(omega_i / v)
// (calib/reading_model.hpp), is that of a sliding rotor. A rotor at rest
// holds any friction torque within +-F_i, so the twist its transmission
// carries is only known within +-c_i F_i: a variance (c_i F_i)^2 / 3 were it
// uniform there. A rotor may rest where its reading moves less than a step
// per sample, |omega_i| below the stick speed v_s = q / dt (q the reading
// step, dt the sample period); the share of that variance a sample carries
// is 1 - tanh^2(omega_i / v_s) (1 at rest, 0.07 at 2 v_s).
//
// A force sign. Passive link i acts as lb_i + d_i sgn(T_i) (its play d_i;
// calib/passive_tension.hpp), its force T_i known within a 1-sigma sigma_T
// (the hub's force balance, calib/friction_balance.hpp, and where its joint
// may be at rest the friction it may hold): the sign is wrong
// with probability p_i = Phi(-|T_i| / sigma_T), and a wrong sign moves the
// reading by 2 d_i k_i (k_i the reading per mm of length): a variance
// (2 d_i k_i)^2 p_i (1 - p_i).
//
// Through the sample's reading sensitivities u (dr / dtheta_m of its ML
// residual, calib/residuals.hpp, normalised) its residual's variance is
//   sigma_j^2 = sigma^2 + sum_i u_i^2 v_i,
// v_i the two variances of joint i, and the fit weighs it by w_j = sigma /
// sigma_j (the model test judges the residuals unweighted, by sigma alone:
// calib/motion_correction.hpp).
#pragma once

#include <vector>

#include <Eigen/Core>

namespace gpm::calib {

// The speed (rad/s) below which a reading of step q_rad taken every dt_s
// seconds may stand for a rotor at rest: q / dt (0 when either is not positive).
double stick_speed(double q_rad, double dt_s);

// The variance (rad^2) of the friction twist of a rotor turning at omega
// (rad/s) whose twist c F is twist_rad, at stick speed v_s (rad/s; 0: none):
// (c F)^2 (1 - tanh^2(omega / v_s)) / 3.
double rest_twist_variance(double omega, double twist_rad, double v_s);

// The variance (rad^2 per mm^2 of play) a passive link's force sign adds to
// its chain's reading at force T_N (N) known within sigma_N (N; 0: certain),
// k_rad_per_mm the reading per mm of its length: (2 k)^2 p (1 - p), p = Phi(-|T| / sigma).
double sign_flip_variance(double T_N, double sigma_N, double k_rad_per_mm);

// The weight sigma / sigma_j of one sample (above) with reading
// sensitivities u, variances v (rad^2) added to its three readings and
// reading 1-sigma sigma (rad); 1 when sigma or u is zero.
double sample_weight(const Eigen::Vector3d& u, const Eigen::Vector3d& v, double sigma);

}  // namespace gpm::calib
