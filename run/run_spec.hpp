// The run part of a scenario file (scenarios/SCHEMA.md, sections
// `calibration`, `compensation`, `expect`, `outputs`): what `gpm run` does
// after simulating, and what counts as success.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/friction_profile.hpp"
#include "calib/monitor/monitor.hpp"
#include "calib/problem.hpp"
#include "calib/robust_loss.hpp"
#include "models/data_sheet.hpp"
#include "run/compensation.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {

// What the calibration assumes of each drive's friction, motor side, per
// joint (calibration.drive_friction): the passive links' force signs of the
// joint clearance are reckoned from the drive torque less this friction
// (calib/passive_tension.hpp). A statement of the user, as of a real robot:
// the twin's `effects:` (the simulated machine's truth) are never read for it.
struct DriveFriction {
  std::array<double, 3> coulomb_Nm{};    // Coulomb friction F_i (N m)
  std::array<double, 3> viscous_Nm_s{};  // viscous friction b_i, all of it (N m s/rad)
  // Both times a common factor k (0, or 0.25..4) chosen by the model test
  // (calib/friction_profile.hpp): the stated values give the shape, the data
  // the scale (told 0.5x, 1x or 2x the twin's friction, the main job ends at
  // the same 0.87x the floor; with the stated values as they are, 1.14x,
  // 0.98x, 3.74x).
  bool fit_scale = true;
  // Each drive's Coulomb and viscous friction estimated before the fit from
  // the hub's force balance on the drives' torques (calib/friction_balance.hpp;
  // on the fly, where the samples carry torques and times): the stated values
  // are then only the fallback, and fit_scale walks from the estimates.
  bool from_balance = true;
  // On the fly, samples the friction leaves uncertain may weigh less in the
  // fit (calib/sample_weights.hpp; the model test and the misfit's sandwich
  // judge the residuals unweighted, by the encoders' noise alone): with
  // weigh_rest (on by default), where a joint turns slower than a reading
  // step per sample (it may be at rest, its friction twist known within
  // +-c F only); with weigh_signs (off by default), where a passive link's
  // force sign may be wrong (its force known within the force balance's
  // 1-sigma and, where its joint may be at rest, the friction it may hold),
  // and only where the model fits the readings within chi2/dof 2 (elsewhere
  // it would weigh the misfit away): with an effect left out the play it
  // inflates can weigh that effect's misfit away too (docs/PROCEDURES.md
  // "Samples the friction leaves uncertain").
  bool weigh_rest = true;
  bool weigh_signs = false;
  // On the fly, the speeds over which the friction may build up that are
  // tried: those whose twist tanh(omega / v) correlates with the joint speed
  // (the latch skew's column) at most this much over the samples
  // (calib::speeds_told_from_skew); 1: every speed of the grid.
  double max_skew_correlation = calib::kMaxSkewCorrelation;
};

// The drives' friction a data sheet states (the default of
// calibration.drive_friction): its nominal Coulomb and viscous friction at
// each joint (the GPM2002's: 0.3 N m, 0.15 N m s/rad), its scale fitted.
DriveFriction stated_drive_friction(const DataSheet& sheet);

// What the drift monitor assumes of the robot's readings (scenario
// `monitor:`, scenarios/SCHEMA.md): the reading errors it models or corrects
// (calib/monitor/monitor.hpp MonitorSettings). A statement of the user, as of
// a real robot, like calibration.drive_friction: the twin's `effects:` (the
// simulated machine's truth) are never read for it. gpm run replaces a value
// by the calibration's estimate where the calibration made one
// (run/monitor_run.hpp reading_model_after_calibration).
struct MonitorReadingModel {
  // The reading errors (calib/reading_model.hpp; its encoder is the
  // scenario's encoder:, the run's). The YAML states the radial clearance c of
  // each pin (clearance_mm); the model holds the play of the link, d = 2 c.
  calib::ReadingModel reading = calib::monitor::MonitorSettings{}.reading;
  // Time constant of the slow drift the monitor tracks (s); ideal: the monitor's own default.
  double thermal_time_constant_s = calib::monitor::MonitorSettings{}.thermal_tau_s;
  // Learning phase (calib/monitor/learning.hpp): seconds of operation the
  // monitor learns the scale, bias and correlation of its innovations before
  // it may raise an alarm (0: none, the statement taken as exact).
  double learning_s = calib::monitor::MonitorSettings{}.learning_s;
  // Least scale of the innovations, in units of what this statement gives
  // (>= 1; gpm run: the calibration's sqrt(chi2 / dof) when above 1).
  double scale_floor = 1.0;
  // The learning phase's configuration map (calib/monitor/config_map.hpp):
  // its match radius in link angles (rad); 0: no map.
  double map_radius_rad = calib::monitor::MonitorSettings{}.map_radius_rad;
};

// `monitor: ideal`: no reading error modelled; drift tracked on the
// monitor's own 60 s time constant (calib/monitor MonitorSettings).
MonitorReadingModel ideal_reading_model();

// `monitor: data_sheet` (the default): the nominal values of the robot's
// data sheet (encoder accuracy as the cyclic error, pin clearance, latch
// skew of drives 2 and 3, compliance 1 / stiffness, warm-up time constant)
// and the drives' friction of stated_drive_friction(sheet).
MonitorReadingModel data_sheet_reading_model(const DataSheet& sheet);

// Parses the scenario's `monitor:` section (node n, absent: the default), the
// `data_sheet` preset from sheet (the robot's); throws InputError naming the
// file, line and key.
MonitorReadingModel parse_monitor_reading_model(const YAML::Node& n, const std::string& file, const DataSheet& sheet);

// m as a top-level `monitor:` section of YAML text, every key explicit, each
// number in its shortest exact form: parse_monitor_reading_model reads it
// back to the last bit. gpm run appends it to DIR/calibration.yaml (the
// reading model its own monitor used), so that `gpm monitor --model
// DIR/calibration.yaml` starts from the calibration's estimates too.
std::string monitor_reading_model_yaml(const MonitorReadingModel& m);

struct CalibrationSpec {
  calib::Cost cost = calib::Cost::kML;
  calib::Method method = calib::Method::kLM;
  FreeMask fixed;                       // default xa1 ya1 xa2 ya2
  long budget = 200000;                 // evaluations (global methods)
  std::optional<int> lm_iterations;     // method lm: calibration.budget, the LM iterations (default 200)
  std::uint64_t seed = 1;
  std::optional<double> sigma;          // encoder sigma for the covariance; default: encoder noise if > 0
  bool allow_rank_deficient = false;
  bool start_reference = false;         // initial offsets from the reference-point procedure (sec. 3.2)
  // Where the robot really stands when those readings are taken (default: at
  // home exactly; the paper's section 3.3: the rough guess (210, 245)).
  std::optional<Eigen::Vector2d> reference_at;
  // Reading effects estimated with the geometry (calib/motion_correction.hpp):
  // unset = both for samples taken on the fly, none otherwise.
  std::optional<bool> estimate_compliance, estimate_skew;
  // The twist of the motor-side Coulomb friction (with the compliance);
  // unset = with the compliance on the fly.
  std::optional<bool> estimate_friction;
  // The axial play of the passive links (joint clearance), by the sign of each
  // link's force; unset = on the fly.
  std::optional<bool> estimate_clearance;
  // The encoders' own error once per joint revolution, under the data sheet's
  // prior, where the encoders turn with the joints (else carried in the
  // 1-sigma); unset = on the fly.
  std::optional<bool> estimate_encoder_error;
  // The reducer's error once per joint revolution on motor encoders, under
  // the data sheet's prior, where the fit with it explains the readings and
  // they show it (else carried in the 1-sigma); unset = on the fly
  // (docs/MOTION_MODEL.md "The reducer's error once per joint revolution").
  std::optional<bool> estimate_joint_error;
  // The drives' friction the procedure assumes (for the force signs);
  // default: the robot's data sheet (stated_drive_friction).
  DriveFriction drive_friction = stated_drive_friction(DataSheet{});
  // With the clearance: samples where some passive link's axial force is
  // below this (N) are left out (its sign is uncertain); unset = MotionModel's.
  std::optional<double> tension_min_N;
  // With the clearance, where the reading model fits: a sample within this
  // long (s) after a passive link's force changed sign is left out, the link
  // may still be crossing its play (calib/play_crossing.hpp); 0: none.
  double crossing_s = 0.02;
  calib::RobustLoss loss;               // `loss: cauchy|huber[:SCALE]` (calib/robust_loss.hpp)
};

// Expectations; an unset one is not checked.
struct Expectations {
  std::optional<bool> converged;
  std::optional<double> base_mm, link_mm, offset_rad;     // |error| per parameter kind
  std::array<std::optional<double>, kNumParams> param;    // |error| per named parameter
  std::optional<double> cost_max;
  std::optional<double> kmrmse_mm_max;
  std::optional<double> crb_ratio_max;                    // |error| / CRB sigma, every free parameter
  std::optional<double> sigma_ratio_max;                  // |error| / the stated 1-sigma, every free parameter
  std::optional<double> static_rms_um_max;                // after compensation
  std::optional<double> path_rms_um_max;
  std::optional<double> improvement_min;                  // static RMS nominal / calibrated
  std::optional<std::string> refused_contains;            // calibration refused with this diagnosis
  std::vector<std::string> note_contains;                // each in some warning/diagnosis note
  std::optional<double> floor_ratio_max;                  // static RMS calibrated / with the actual parameters
  std::optional<double> robot_time_s_max;                 // robot time of the sampling
  std::optional<bool> model_test_passes;                  // the chi-square model test passes (true) or fails (false)
  std::optional<double> positioning_rms_um_max;           // the calibrated model's positioning error over the workspace
};

struct Outputs {
  bool report = true;
  bool compensation = true;  // run the before/after twin evaluation
};

// A whole scenario: the simulation part (sim/scenario.hpp) and the run part.
struct RunSpec {
  sim::Scenario sim;
  // Hardware file (hw/hardware_config.hpp): the samples are taken through the
  // robot interface (twin or modbus backend) instead of the in-process
  // simulation. Relative to the scenario file; `gpm run --hardware` overrides.
  std::optional<std::string> hardware;
  bool hardware_resume = false;  // continue DIR/samples.csv (`gpm run --hardware ... --resume`)
  CalibrationSpec calibration;
  MonitorReadingModel monitor = data_sheet_reading_model(DataSheet{});  // what the monitor of `operation:` assumes
  std::optional<CompensationPlan> compensation;  // set when outputs.compensation
  Expectations expect;
  Outputs outputs;
};

// Loads and validates a scenario for `gpm run`; throws InputError naming the
// file, the line and the key path (e.g. calibration.fix[2]).
RunSpec load_run_spec(const std::string& path);

// Parses scenario text (base_dir resolves relative paths).
RunSpec parse_run_spec(const std::string& text, const std::string& file, const std::string& base_dir);

}  // namespace gpm::scenario
