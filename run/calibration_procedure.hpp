// The calibration procedure of every entry point: `gpm run` (on the samples
// it has just taken), `gpm calibrate --data` and Python `gpm.calibrate` (on a
// samples file's readings, times and drive torques). From the readings, the
// times and torques where known, and what the user and the data sheet state
// (run/calibration_inputs.hpp), never the twin's truth:
//   - samples on the fly or a stated effect: the geometry estimated jointly
//     with the motion model (calib/motion_correction.hpp: compliance, latch
//     skew, friction twist, joint clearance, the lag on the torque before,
//     the encoders' cyclic error as a prior), the friction's speed and scale
//     chosen by the model test (calib/friction_profile.hpp), the clearance and
//     the lag dropped again where the data do not show them;
//   - otherwise the static fit of calib/calibrate.hpp;
// then the chi-square model test (calib/model_test.hpp) of the readings the
// fit explains against the stated reading 1-sigma.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/calibrate.hpp"
#include "calib/friction_balance.hpp"
#include "calib/home_reference.hpp"
#include "calib/model_test.hpp"
#include "calib/motion_correction.hpp"
#include "run/calibration_inputs.hpp"

namespace gpm {
struct Samples;
}

namespace gpm::scenario {

// Samples on the fly left out at the start, the drives' start transient (s).
inline constexpr double kStartTransient_s = 0.05;

// What a robot's drives report of each sample.
struct SampleSeries {
  std::vector<Eigen::Vector3d> theta_m;  // encoder readings (rad)
  std::vector<double> t_s;               // when each reading was taken (s); needed on the fly
  // The drive torque the transmission's twist follows (N m), one per sample:
  // on the fly the drive period's just before the reading (tau_last), at rest
  // the sample's; empty: none (no effect can be estimated).
  std::vector<Eigen::Vector3d> tau;
  // On the fly the mean drive torque over the periods since the sample before
  // (N m; tau_between); empty: the lag's regressor is the torque of the sample before.
  std::vector<Eigen::Vector3d> tau_between;
  // On the fly, when joint 1's reading was taken less when each joint's was
  // (s), one per sample, or empty: read at one instant. Each reading is
  // carried to joint 1's instant by its rate: theta_m_i + omega_i lag_i.
  std::vector<Eigen::Vector3d> read_lag_s;
  // The true end-effector positions (mm), where known (simulation): kmrmse only.
  std::vector<Eigen::Vector2d> true_xy;
};

struct ProcedureOptions {
  Geometry start;           // the fit's start and the values of the fixed parameters
  FreeMask free;            // the parameters estimated
  double sigma_rad = 0.0;   // 1-sigma of one reading (rad; 0: ideal encoders, no model test)
  // On the fly: the reading 1-sigma from the step the readings show
  // (calib/reading_step.hpp) with white noise reading_noise_rad, where they
  // show one (else sigma_rad); false: sigma_rad as stated.
  bool sigma_from_step = false;
  double reading_noise_rad = 0.0;
  bool in_motion = false;   // the samples were taken on the fly, consecutive (rates from t_s)
  double skip_first_s = kStartTransient_s;  // on the fly: leading samples within this of the first left out
  bool keep_clearance = false;  // the clearance stays in the model where not detected (stated by the user)
  bool test_any_cost = false;   // the model test for every cost (default: the ML cost only, as gpm run)
  calib::MethodOptions method;  // method, cost, LM iterations, loss; encoder_sigma: the static fit's
  // The robot file's home pose: where the reducer's error is referenced to 0,
  // the encoder offsets stated there (calib/home_reference.hpp); none: not referenced.
  std::optional<calib::HomePose> home;
};

struct CalibrationOutcome {
  calib::Result result;                        // geometry, 1-sigma, diagnostics and the procedure's notes
  std::optional<calib::ModelTest> model_test;  // none: no sigma, not the ML cost, or no degrees of freedom
  std::vector<Eigen::Vector3d> used;           // the readings the fit explains (corrected for the motion model)
  bool with_effects = false;                   // the motion model was estimated with the geometry
  double sigma_rad = 0.0;                      // the reading 1-sigma the fit and its test assumed (rad)
  // With effects, what the Cramer-Rao bound of the joint estimation needs
  // (calib::motion_crb): the final model, the samples' rates and torques.
  calib::MotionFit fit;
  calib::MotionModel motion;
  std::vector<Eigen::Vector3d> omega, tau, alpha;
  // With effects: the monitor's stated reading model (CalibrationInputs::monitor)
  // with the estimates in place of the stated values.
  std::optional<calib::ReadingModel> reading;
  // On the fly: each drive's friction from the hub's force balance, before
  // the model test's scale (none: not made, or the samples did not allow it).
  std::optional<calib::BalanceFriction> friction_balance;
};

// The calibration of samples with inputs (motion model, stated friction) and
// options. Throws InputError for samples it cannot use (sizes that differ,
// no times or torques where the motion model needs them, a rank-deficient
// free set, everything the fits refuse).
CalibrationOutcome calibrate_samples(const SampleSeries& samples, const CalibrationInputs& inputs,
                                     const ProcedureOptions& options);

// The reading model r (stated) with the estimates of fit in place: skew and
// compliance where estimated (a compliance or backlash fitted below 0, within
// its noise of none, is none), the passive links' play where it was looked
// for (play_looked_for), the drives' friction of motion where the data gave
// it (friction_measured: the force balance, or the model test's scale), the drive-train harmonics fit estimated (0
// elsewhere) and the gear ratio of motion.
calib::ReadingModel estimated_reading_model(calib::ReadingModel r, const calib::MotionFit& fit,
                                            const calib::MotionModel& motion, bool play_looked_for,
                                            bool friction_measured);

// The series of a samples file: readings, times, and as the twist's torque
// tau_last where the file has it (samples on the fly), else tau.
SampleSeries sample_series(const Samples& samples);

// True when samples were taken on the fly: times, the torques before each
// reading (tau_last) and the mean since the sample before (tau_between), the
// times evenly spaced (one sample every few drive periods).
bool taken_on_the_fly(const Samples& samples);

// The procedure for a samples file (gpm calibrate, gpm.calibrate): the
// motion model when the samples were taken on the fly (taken_on_the_fly),
// the method is lm with the ml cost and static_model is false, else the
// static fit; the reading 1-sigma method.encoder_sigma where given, else the
// quantisation of 2^encoder_bits counts (default: the data sheet's); the
// inputs from the robot's data sheet (run/calibration_inputs.hpp), the model
// test for every cost.
struct FileProcedure {
  CalibrationInputs inputs;
  ProcedureOptions options;
  bool sigma_stated = false;       // the result's 1-sigma is the one the model test assumes
  bool motion_not_used = false;    // taken on the fly, but the method or cost is not lm with ml
  std::string model;               // "the motion model (...)" or "the static model", for a terminal
};
FileProcedure samples_file_procedure(const Samples& samples, const Robot& robot, const Geometry& start,
                                     const FreeMask& free, const calib::MethodOptions& method,
                                     std::optional<int> encoder_bits, bool static_model);

// The model test's line for a terminal: passed, or what a failure means for
// the stated 1-sigma; stated: the 1-sigma of the result is the one the test
// assumed (false: scaled by the residuals).
std::string model_test_line(const calib::ModelTest& test, bool stated);

// The model test as YAML keys at indent, for the end of a result file's
// diagnostics: model_test_chi2, _dof, _chi2_per_dof, _p_value, _sigma_rad,
// _passed and, when it fails, _diagnosis; each number exact.
std::string model_test_yaml(const calib::ModelTest& test, int indent);

}  // namespace gpm::scenario
