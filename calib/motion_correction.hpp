// Calibration from readings taken in motion (sampling on the fly): the
// geometry estimated jointly with the reading model's nuisance values
// (latch skew, transmission compliance and its lag, friction twist, joint
// clearance, backlash, hysteresis, cyclic errors and harmonics) by Gauss-Newton passes
// of an LM fit on corrected readings and a joint linearisation step; the
// geometry's covariance from the joint Jacobian [J_g, J_nu]. The model, its
// columns and why each is there: docs/MOTION_MODEL.md.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/lm.hpp"
#include "calib/model_test.hpp"
#include "calib/passive_tension.hpp"
#include "calib/reading_model.hpp"
#include "calib/problem.hpp"

namespace gpm::calib {

// What the readings are corrected for.
struct MotionModel {
  bool skew = true;        // estimate s2, s3 (s)
  bool compliance = true;  // estimate c1, c2, c3 (rad/N m)
  bool friction = true;    // with compliance: the twist c_i F_i sign(omega_i) that the motor-side
                           // Coulomb friction F_i takes off the drive torque
  bool clearance = false;  // estimate the axial play d_i of each passive link (mm): its length is
                           // lb_i + d_i sign(T_i), T_i its axial force (calib/passive_tension.hpp)
  TransmissionLoad load;       // for the force signs: the friction and inertia the transmissions take off
  double tension_min_N = 1.5;  // |T_i| below this: the sign is uncertain (on the realistic twin 5 % of the
                               // signs were wrong above 0.3 N, 1 % above 1 N, 0.3 % above 1.5 N); on the
                               // fly set from BalanceFriction::tension_sigma_N (calib/friction_balance.hpp)
  bool drop_uncertain = true;  // with clearance: a sample where some chain's force sign is uncertain is left
                               // out (false: only that chain's play is left out of it)
  double min_kept_share = 0.25;  // with drop_uncertain: when fewer samples than this share have every
                                 // |T_i| >= tension_min_N, the threshold is lowered to keep this share
                                 // (a robot of little friction: its links carry small forces)
  bool torque_before = false;  // with compliance: the twist responds to the torque of the sample before too
                               // (h_i tau_i(j-1); consecutive samples, on the fly)
  std::vector<Eigen::Vector3d> torque_between;  // with torque_before, the samples' record of the drives (N m, one per
                                                // sample, or empty): the mean drive torque over the periods since the
                                                // sample before; the lag's regressor is then torque_between(j) - tau(j)
                                                // (tau: the last period's), else tau(j-1) - tau(j)
  double cyclic_prior_rad = 0.0;  // > 0: each encoder's once-per-turn error a_i sin(theta_m_i) + b_i cos(theta_m_i),
                                  // a_i and b_i ~ N(0, this^2) a priori (the data sheet's accuracy), carried in the
                                  // covariance and the bound (considered) or estimated (estimate_cyclic)
  bool estimate_cyclic = false;   // with cyclic_prior_rad: estimate a_i, b_i under the prior (needs
                                  // LmOptions::encoder_sigma; without it they are not estimated)
  // A geared drive between its motor encoder and its link (each per joint;
  // which ones a robot needs is chosen by the data, calib/reading_model_selection.hpp):
  std::array<bool, 3> backlash{};  // half the lost motion beta_i: theta_a = theta_m - beta_i sgn(tau_mesh_i)
  double backlash_torque_min_Nm = kFlankTorqueMinNm;  // |tau_mesh_i| below this: the flank in contact uncertain, the
                                        // sample left out (the link crosses the gap)
  std::array<bool, 3> joint_harmonic{};   // once per joint revolution, a_i sin(theta_m) + b_i cos(theta_m),
                                          // estimated without a prior (the reducer's transmission error)
  std::array<bool, 3> motor_harmonic1{};  // once per motor revolution: a sin(N theta_m) + b cos(N theta_m)
  std::array<bool, 3> motor_harmonic2{};  // twice per motor revolution: a sin(2 N theta_m) + b cos(2 N theta_m)
  std::array<bool, 3> cogging{};          // the motor's cogging, P per motor revolution: a sin(P N theta_m) + b cos(..)
  double gear_ratio = 1.0;                // N: motor revolutions per joint revolution (the data sheet's)
  double cogging_periods = 0.0;           // P: the motor's cogging periods per revolution (the data sheet's)
  bool encoder_on_motor = true;  // the encoders read the motors: the reducers' backlash and errors per motor
                                 // revolution lie between reading and link (left_out_effects names them);
                                 // false where the encoders turn with the joints, after the reducers
  // The reducer's hysteresis, per joint: half its loss eta_i = H_i / 2, theta_a = theta_m + eta_i g_i, g_i in
  // [-1, 1] the state of the mesh's friction element (hysteresis_state) under the mesh torque at the threshold
  // T_i = eta_i / c_i (c_i the compliance); T_i moves with the estimates (Gauss-Newton through dg/dT).
  std::array<bool, 3> hysteresis{};
  double hysteresis_start_rad = 7.3e-5;            // eta where the fit starts (0.25 arcmin: a loss of 0.5 arcmin)
  double hysteresis_compliance_rad_per_Nm = 1e-4;  // c_i where the fit starts, and where it does not estimate it
                                                   // (the data sheet's)
  bool sandwich = true;  // when the fit's residuals, unweighted, exceed the noise (the model test's chi-square at 1 %,
                         // less what the carried error explains), the
                         // covariance is the autocorrelation-robust sandwich of the residuals (Newey-West), not
                         // sigma^2 (J'J)^-1
  // Samples the friction leaves uncertain weigh less (calib/sample_weights.hpp; needs LmOptions::encoder_sigma):
  double stick_speed_rad_s = 0.0;  // > 0: below about this speed a rotor may be at rest, its friction twist
                                   // known within +-c_i F_i only (with the friction twist); 0: no such doubt
  double tension_sigma_N = 0.0;    // > 0: a passive link's force known within this 1-sigma (N; where its joint
                                   // may be at rest, also within the friction F_i it may hold), its sign (with
                                   // the clearance) wrong with Phi(-|T| / that); 0: the signs used are certain
  int crossing_samples = 0;    // with the clearance: after a passive link's force changes sign, this many samples
                               // (from the first of the new sign) have its sign uncertain (dropped with
                               // drop_uncertain): the link may still be crossing its play (calib/play_crossing.hpp)
  int skip_first = 0;          // leading samples left out (the drives' start transient)
  int max_passes = 6;      // Gauss-Newton passes (each one LM fit)
};

// True where model estimates the reducer's error once per joint revolution:
// the error under the data sheet's prior (cyclic_prior_rad with
// estimate_cyclic) read by motor encoders behind a reducer, where it is the
// reducer's transmission error, not the encoder's own (MotionFit::cyclic).
inline bool estimates_reducer_joint_error(const MotionModel& m) {
  return m.estimate_cyclic && m.cyclic_prior_rad > 0.0 && m.encoder_on_motor && m.gear_ratio > 1.0;
}

struct MotionFit {
  Result result;                            // geometry, 1-sigma (joint), diagnostics of the last pass
  std::array<double, 5> nu{};               // s2, s3 (s), c1, c2, c3 (rad/N m); 0 where not estimated
  std::array<double, 5> nu_sigma{};         // their 1-sigma (NaN where not estimated, e.g. the
                                            // compliance of a torque-off joint, which no sample excites)
  std::array<double, 3> friction{};         // c_i F_i (rad), i = 1..3; 0 where not estimated
  std::array<double, 3> friction_sigma{};   // their 1-sigma (NaN where not estimated)
  std::array<double, 3> clearance{};        // axial play d_i of each passive link (mm); 0 where not estimated
  std::array<double, 3> clearance_sigma{};  // their 1-sigma (NaN where not estimated)
  std::array<double, 3> torque_before{};    // h1 h2 h3 (rad/N m; response to tau(j-1) - tau(j)); 0 where not estimated
  std::array<double, 3> torque_before_sigma{};  // their 1-sigma (NaN where not estimated)
  std::array<double, 6> cyclic{};           // a1 a2 a3 b1 b2 b3 (rad); 0 where not estimated
  std::array<double, 6> cyclic_sigma{};     // their 1-sigma, prior included (NaN where not estimated)
  std::array<double, 3> backlash{};         // beta_i (rad); 0 where not estimated
  std::array<double, 3> backlash_sigma{};   // their 1-sigma (NaN where not estimated)
  // Harmonics a1 a2 a3 b1 b2 b3 (rad) of each order: once per joint revolution, once and twice per motor
  // revolution, the cogging; 0 where not estimated, sigma NaN.
  std::array<std::array<double, 6>, kHarmonicOrders> harmonic{};
  std::array<std::array<double, 6>, kHarmonicOrders> harmonic_sigma{};
  std::array<double, 3> hysteresis{};        // eta_i (rad): half the hysteresis loss; 0 where not estimated
  std::array<double, 3> hysteresis_sigma{};  // their 1-sigma (NaN where not estimated)
  // The 1-sigma of the noise model alone (sigma^2 (J'J)^-1: neither the
  // considered cyclic error nor the sandwich), which the tests of "is this
  // effect there" weigh the estimates by (NaN where not estimated).
  struct NoiseSigma {
    std::array<double, 3> clearance{}, torque_before{}, backlash{}, hysteresis{};
    std::array<std::array<double, 6>, kHarmonicOrders> harmonic{};
  } noise_sigma;
  double chi2 = 0.0;                        // r'r / sigma^2 of the fit, its residuals weighted (0 without sigma)
  double chi2_per_dof = 0.0;                // chi2 / (n - columns)
  // Of the residuals' unweighted chi-square (the model test's), what an error carried within its prior
  // (MotionModel::cyclic_prior_rad, not estimated) explains: r' Gp (sigma^2 / prior^2 + Gp' Gp)^-1 Gp' r / sigma^2,
  // Gp its columns with the fit's projected out (0 without a carried error).
  double carried_chi2 = 0.0;
  // What the twist of a joint that may rest adds to that chi-square on average, as the model test expects it
  // (calib/model_test.hpp SampleDoubt): within +-c F, c the data sheet's compliance
  // (hysteresis_compliance_rad_per_Nm) and F the drives' friction (load); 0, 0 without a stick speed or sigma.
  SampleDoubt doubt;
  bool sandwich_used = false;               // the covariance is the misfit's sandwich (MotionModel::sandwich)
  double sandwich_inflation = 1.0;          // RMS over the geometry of its 1-sigma over the noise-model 1-sigma
  double tension_min_N = 0.0;               // the force threshold used (MotionModel::tension_min_N or lower)
  std::array<double, 3> clearance_used{};   // fraction of the samples whose force sign was certain, per chain
  int passes = 0;
  std::vector<std::size_t> kept;            // the samples the fit used (indices into the readings)
  std::vector<Eigen::Vector3d> corrected;   // those readings corrected with nu (rad)
  std::vector<double> weight;               // their residuals' weights (calib/sample_weights.hpp); empty: all 1
};

// Estimates problem.free and the nuisance values of model from readings
// problem.theta_m taken with joint speeds omega (rad/s) and drive torques tau
// (N m), one per sample, and (for the clearance's force signs; empty: 0) joint
// accelerations alpha (rad/s^2). options.cost must be ML. Throws InputError when
// the sizes differ or the cost is not ML (and for everything calibrate_lm refuses).
MotionFit calibrate_in_motion(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                              const std::vector<Eigen::Vector3d>& tau, const LmOptions& options,
                              const MotionModel& model = {}, const std::vector<Eigen::Vector3d>& alpha = {});

// Cramer-Rao 1-sigma (15 slots, NaN for fixed ones) of the free parameters of
// truth estimated jointly with the nuisance values of model, as
// calibrate_in_motion does, from the noiseless readings theta_m of truth (rad)
// with speeds omega, torques tau and accelerations alpha (empty: 0), each
// reading with noise sigma (rad): sigma sqrt(diag((J' J)^-1)) of [J_g, J_nu]
// at the truth, the force signs at the truth, the same samples left out (with
// the cyclic error's prior rows, which make the bound depend on sigma not
// only as a factor).
// Throws InputError when the sizes differ.
std::array<double, kNumParams> motion_crb(const Geometry& truth, const FreeMask& free,
                                          const std::vector<Eigen::Vector3d>& theta_m,
                                          const std::vector<Eigen::Vector3d>& omega,
                                          const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
                                          const std::vector<Eigen::Vector3d>& alpha, double sigma);

// The covariance (15 x 15, zero rows and columns for fixed parameters) whose
// diagonal's square roots motion_crb gives; same inputs, same throws.
Eigen::Matrix<double, kNumParams, kNumParams> motion_crb_covariance(
    const Geometry& truth, const FreeMask& free, const std::vector<Eigen::Vector3d>& theta_m,
    const std::vector<Eigen::Vector3d>& omega, const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
    const std::vector<Eigen::Vector3d>& alpha, double sigma);

// The readings corrected for nuisance values nu (as in MotionFit::nu):
// theta_m + s omega - c tau per joint.
std::vector<Eigen::Vector3d> correct_readings(const std::vector<Eigen::Vector3d>& theta_m,
                                              const std::vector<Eigen::Vector3d>& omega,
                                              const std::vector<Eigen::Vector3d>& tau,
                                              const std::array<double, 5>& nu);

// The normalised state g_k in [-1, 1] of a mesh's friction element (a
// Prandtl element in parallel with its spring) under mesh torques tau_k (N m)
// of threshold T (N m): g_k = clamp(g_(k-1) + (tau_k - tau_(k-1)) / (2 T), -1, 1),
// g_0 = 0 (stuck, the element takes half of each torque change; sliding at
// +-T). T <= 0: the sign of the last torque change.
std::vector<double> hysteresis_state(const std::vector<double>& tau, double threshold_Nm);

// The threshold T = eta / c (N m) where a hysteresis fit starts
// (MotionModel::hysteresis_start_rad over hysteresis_compliance_rad_per_Nm).
double starting_hysteresis_threshold(const MotionModel& model);

// The largest threshold (N m) a mesh torque spanning `torque_range_Nm` can
// tell: a quarter of it, over which the element slides from one end to the
// other (at a larger T it never does, and g is the torque's own shape).
double largest_hysteresis_threshold(double torque_range_Nm);

// True if some estimated play d_i of fit lies at least k 1-sigma (of the noise model) from 0 (the
// test of "no joint clearance", d_i = 0, two-sided at k sigma per chain); a
// play not estimated (sigma NaN) does not count.
bool clearance_detected(const MotionFit& fit, double k = 3.0);

// True if some estimated response h_i of fit to the torque before lies at
// least k 1-sigma (of the noise model) from 0 (the test of "the twist follows the torque of its
// instant", two-sided at k sigma per joint); one not estimated does not count.
bool torque_before_detected(const MotionFit& fit, double k = 3.0);

// A reading effect the model leaves out, as the residuals of a fit ask for
// it (left_out_effects): its name and the chi-square its columns would take
// out of the fit's.
struct LeftOutEffect {
  std::string name;     // e.g. "transmission compliance", "backlash of joint 2"
  double chi2_drop = 0.0;
  int columns = 0;      // its values (the score test's degrees of freedom)
};

// The reading effects model leaves out that fit's residuals call for, the
// model test's diagnosis (readings problem.theta_m, speeds omega, torques
// tau, accelerations alpha, reading 1-sigma sigma): each candidate's
// chi-square drop were its columns added to the fit at its estimate (a score
// test: the residuals projected on the candidate's columns, the geometry's
// and the model's own projected out), on the samples the fit kept; those
// significant at p < 0.001 for their count of values, largest first. With
// accelerations and the friction twist in model, the drives' friction
// dynamics are one candidate: the twist of a friction that acts on the speed
// a time ahead or behind (docs/PROCEDURES.md "What the model test names").
std::vector<LeftOutEffect> left_out_effects(const Problem& problem, const std::vector<Eigen::Vector3d>& omega,
                                            const std::vector<Eigen::Vector3d>& tau, const MotionModel& model,
                                            const MotionFit& fit, double sigma,
                                            const std::vector<Eigen::Vector3d>& alpha = {});

}  // namespace gpm::calib
