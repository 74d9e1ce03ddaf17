// Nonlinear drive train of each chain (scenarios/SCHEMA.md, section effects,
// "Drive train"): what a geared servo axis adds to the linear transmission
// spring. All off by default (every field 0), and off = the ideal twin.
// Pure functions of constants and a small state, no MuJoCo (the twin applies
// them in sim/drive_train_step.hpp). Angles are output (link) side, rad; the
// motor shaft turns gear_ratio times the output-referred rotor angle theta_m.
//
//   mesh twist      delta = theta_m - theta_a - (TE(theta_m) - TE(theta_m0))
//   transmission error
//                   TE(theta_m) = A_j sin(theta_m + phi_j) + A_m sin(n_m N theta_m + phi_m)
//                   (once per joint revolution; n_m times per motor revolution)
//   backlash        e = delta - sgn(delta) b/2 for |delta| > b/2, else 0 (no contact)
//   stiffness bands f(e) = K1 e                        |e| <= e1 = T1/K1
//                        = sgn(e) (T1 + K2 (|e| - e1)) |e| <= e2 = e1 + (T2 - T1)/K2
//                        = sgn(e) (T2 + K3 (|e| - e2)) beyond
//   hysteresis      a Prandtl element (spring K1 in series with a slider of
//                   strength T_h = K1 H/2) in parallel: slip s follows
//                   s = clamp(s, e - H/2, e + H/2), tau_h = K1 (e - s); after
//                   loading to +-T >> T_h the twist at zero torque is +-H/2:
//                   the hysteresis loss H (Harmonic Drive catalogue definition)
//   transmitted     tau_t = f(e) + tau_h; with backlash (b > 0) a flank can
//                   only push: tau_t = 0 unless it has the sign of e, and s = 0
//                   out of contact
//   friction bound  F = F_c + mu |tau_t| + F_x exp(-(omega_m / v_s)^2)
//                   (Coulomb, load, Stribeck; F_x the breakaway excess)
//   applied torque  tau = (1 + delta_k) tau_reported + A_c sin(P N theta_m + phi_c)
#pragma once

#include <array>

#include "models/rng.hpp"

namespace gpm::sim {

struct Effects;

// Drive-train constants of one chain (0 = that effect off).
struct DriveChain {
  double backlash_rad = 0.0;                   // b: lost motion of the mesh, total (rad)
  std::array<double, 3> stiffness_Nm_per_rad{};  // K1 <= K2 <= K3 (N m/rad); K1 = 0: off
  std::array<double, 2> band_Nm{};             // T1 < T2: torques where K2 and K3 take over (N m)
  double hysteresis_rad = 0.0;                 // H: hysteresis loss (rad)
  double te_joint_rad = 0.0;                   // A_j (rad)
  double te_joint_phase_rad = 0.0;             // phi_j
  double te_motor_rad = 0.0;                   // A_m (rad)
  double te_motor_phase_rad = 0.0;             // phi_m
  double stiction_excess_Nm = 0.0;             // F_x: breakaway above the Coulomb level (N m)
  double stribeck_speed_rad_s = 0.01;          // v_s (output side, rad/s)
  double load_friction = 0.0;                  // mu: friction per N m transmitted
  double torque_constant_delta = 0.0;          // delta_k: applied = (1 + delta_k) x reported
  double cogging_Nm = 0.0;                     // A_c at the output (N m)
  double cogging_phase_rad = 0.0;              // phi_c

  // True if the mesh (twist to torque) or the rotor friction differs from the linear spring.
  bool mesh_on() const;
  // True if the applied torque differs from the reported one.
  bool motor_on() const;
};

// Every chain's drive train and the orders shared by all drives.
struct DriveTrain {
  std::array<DriveChain, 3> chain{};
  int te_motor_order = 2;               // n_m: TE periods per motor revolution (harmonic drive: 2)
  int cogging_periods_per_motor_rev = 24;  // P: cogging periods per motor revolution

  // True if any chain has any drive-train effect.
  bool any() const;
};

// f(e): elastic torque (N m) of twist e (rad) on chain c's stiffness bands.
double band_torque(const DriveChain& c, double e);

// f^-1(tau): twist (rad) at elastic torque tau (N m).
double band_twist(const DriveChain& c, double tau);

// e: twist beyond the dead band b (total width) of twist delta.
double dead_band(double delta, double b);

// TE(theta_m) (rad) of chain c with N = gear_ratio and n_m = order.
double transmission_error(const DriveChain& c, double theta_m, double gear_ratio, int order);

// tau_t (N m) at mesh twist delta; updates the hysteresis slip s (rad).
double transmission_torque(const DriveChain& c, double delta, double& s);

// F (N m): friction bound at rotor speed omega_m with transmitted torque tau_t and Coulomb level F_c.
double friction_bound(const DriveChain& c, double coulomb_Nm, double omega_m, double tau_t);

// Torque (N m) the drive applies when it reports tau_reported, at rotor angle theta_m.
double applied_torque(const DriveChain& c, double tau_reported, double theta_m, double gear_ratio, int periods);

// Largest incremental stiffness (N m/rad) of the mesh: max K + K1 with hysteresis.
double stiffest(const DriveChain& c);

// Draws every drive-train effect of each chain independently from the
// plausible ranges of scenarios/SCHEMA.md (kPlausible below), phases uniform.
void draw_drive_train(Rng& rng, Effects& e);

// Plausible ranges (SCHEMA.md, "Drive train"): what draw_drive_train draws from.
struct PlausibleDriveTrain {
  double backlash_rad[2] = {0.3 * 2.908882e-4, 10.0 * 2.908882e-4};   // 0.3-10 arcmin (log-uniform)
  double k1_Nm_per_rad[2] = {0.7e4, 1.3e4};                           // K1
  double k_step[2] = {1.0, 1.4};                                      // K2 / K1 and K3 / K2
  double t1_Nm[2] = {2.0, 7.0};                                       // T1
  double t2_Nm[2] = {15.0, 25.0};                                     // T2
  double hysteresis_rad[2] = {0.1 * 2.908882e-4, 1.0 * 2.908882e-4};  // 0.1-1 arcmin
  double te_joint_rad[2] = {0.2 * 2.908882e-4, 1.5 * 2.908882e-4};    // amplitude 0.2-1.5 arcmin
  double te_motor_rad[2] = {0.05 * 2.908882e-4, 0.5 * 2.908882e-4};   // amplitude 0.05-0.5 arcmin
  double stiction_excess_Nm[2] = {0.05, 0.3};
  double stribeck_speed_rad_s[2] = {0.002, 0.05};                     // log-uniform
  double load_friction[2] = {0.02, 0.2};
  double torque_constant_delta[2] = {-0.1, 0.1};
  double cogging_Nm[2] = {0.03, 0.25};
};
inline constexpr PlausibleDriveTrain kPlausible{};

}  // namespace gpm::sim
