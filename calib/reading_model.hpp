// The reading model: what lies between a link's angle and the number its
// drive reports, joint by joint. One statement and one convention for the
// calibration in motion (calib/motion_correction.hpp, which estimates it),
// the drift monitor (calib/monitor/monitor.hpp, which corrects by it) and
// run/ (the scenario's `monitor:` and `calibration.drive_friction`).
//
// The link angle a reading theta_m of joint i stands for is
//   theta_a_i = theta_m_i + s_i omega_i - c_i tau_t_i - beta_i sgn(tau_mesh_i)
//               - sum_o (a_oi sin(k_o theta_m_i) + b_oi cos(k_o theta_m_i))
//               (the order 2N less its value at the home reading where one is given)
// (latch skew s, compliance c under the transmitted torque tau_t, backlash
// beta on the flank the mesh torque presses, drive-train harmonics of orders
// k_o = 1, N, 2N per joint revolution, N the gear ratio), and passive link i
// acts as lb_i + d_i sgn(T_i) under its axial force T_i (calib/passive_tension.hpp).
#pragma once

#include <array>
#include <limits>
#include <string>

#include "calib/passive_tension.hpp"

namespace gpm::calib {

// Orders of the drive-train harmonics: once per joint revolution, once and
// twice per motor revolution, and the motor's cogging (P per motor revolution).
inline constexpr int kHarmonicOrders = 4;

// The order that is the motor's cogging: its torque ripple, P periods per
// motor revolution (the data sheet's), twists the transmission by
// c A sin(P N theta_m + phi).
inline constexpr int kCoggingHarmonic = 3;

// The order that is the reducer's error (a harmonic drive's wave generator
// flexes the spline twice a motor turn): twice per motor revolution.
inline constexpr int kReducerHarmonic = 2;

// The order once per joint revolution: on motor encoders the reducer's
// transmission error per output revolution (its gears' run-out).
inline constexpr int kJointHarmonic = 0;

// True for the orders that are the reducer's errors, 0 at the robot's home
// where ReadingModel::reducer_home_rad is set: once per joint revolution and
// twice per motor revolution.
constexpr bool referenced_at_home(int order) { return order == kJointHarmonic || order == kReducerHarmonic; }

// ReadingModel::reducer_home_rad of a harmonic of mean 0.
inline constexpr double kNotReferenced = std::numeric_limits<double>::quiet_NaN();

// Mesh torque (N m) below which the flank a reducer's backlash sits on is
// unknown (the link crossing its gap).
inline constexpr double kFlankTorqueMinNm = 0.1;

struct ReadingModel {
  int encoder_bits = 17;   // counts per revolution 2^bits; 0 = ideal (no quantisation)
  double noise_rad = 0.0;  // additive Gaussian reading noise (1-sigma)
  std::array<double, 3> skew_s{};                 // latch skew s_i of each encoder (s; encoder 1 the reference)
  std::array<double, 3> compliance_rad_per_Nm{};  // transmission compliance c_i
  TransmissionLoad load;                          // what the transmission takes off the drive torque
  std::array<double, 3> clearance_mm{};           // d_i: passive link i acts as lb_i + d_i sgn(T_i) (both pins' play)
  std::array<double, 3> cyclic_rad{};             // amplitude of each encoder's once-per-revolution error
  std::array<double, 3> backlash_rad{};           // beta_i: half the lost motion of joint i's reducer
  // a_o1 a_o2 a_o3 b_o1 b_o2 b_o3 (rad) of each harmonic order o.
  std::array<std::array<double, 6>, kHarmonicOrders> harmonic{};
  double gear_ratio = 1.0;  // N: motor revolutions per joint revolution
  double cogging_periods = 0.0;  // P: the motor's cogging periods per revolution (0: none; kCoggingHarmonic)
  // The readings at home (rad) where the reducer's errors, the harmonics once
  // per joint and twice per motor revolution (referenced_at_home), are 0 (the
  // offsets are the links' at home: calib/home_reference.hpp): each such term
  // is e(theta_m) - e(this); NaN: e(theta_m).
  std::array<double, 3> reducer_home_rad{kNotReferenced, kNotReferenced, kNotReferenced};
};

// Throws InputError naming the first value of m out of its range (each
// prefixed by `where`, e.g. "monitor: ").
void check_reading_model(const ReadingModel& m, const std::string& where);

// The radial clearance (mm) of each pin of m's passive links: half the link's play.
std::array<double, 3> pin_clearance_mm(const ReadingModel& m);

// The quantisation step (rad) of an encoder of 2^bits counts per revolution; 0 for bits 0.
double encoder_step_rad(int bits);

// 1-sigma (rad) of a mean of n_avg readings of quantisation step step_rad
// and Gaussian noise noise_rad: sqrt(step^2 / 12 + noise^2 / n_avg).
double reading_sigma(double step_rad, double noise_rad, double n_avg = 1.0);

// reading_sigma of one reading of model m's encoder.
double reading_sigma(const ReadingModel& m);

// The angle of harmonic order o (0..3) of reading theta_m (rad): theta_m, N theta_m, 2 N theta_m, P N theta_m
// (gear ratio N, cogging periods P).
double harmonic_angle(int o, double theta_m, double gear_ratio, double cogging_periods);

// The link angle reading theta_m of joint i (0..2) stands for under m, at joint
// speed omega (rad/s), transmitted torque tau_t (N m) and the sign of the
// mesh torque flank (+-1; 0 where the flank is unknown).
double link_angle(const ReadingModel& m, int i, double theta_m, double omega, double tau_t, double flank);

// The reading (rad) at which joint i's link stands at theta (rad, the link
// angle less the offset dth_i) under m's drive-train harmonics alone (no
// speed, torque or flank: what a reading's own angle decides), solved by
// fixed-point steps (the harmonics change by far less than 1 rad per rad).
double reading_at(const ReadingModel& m, int i, double theta);

}  // namespace gpm::calib
