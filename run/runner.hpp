// `gpm run`: sample a scenario's robot through the hardware interface (the
// in-process twin as a twin backend, or the backend of --hardware: one loop,
// run/twin_hardware.hpp), calibrate from its encoder samples, compensate (the
// controller takes the calibrated model), evaluate before and after on the
// twin, check the expectations, write the outputs.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "calib/friction_balance.hpp"
#include "calib/model_test.hpp"
#include "calib/positioning_error.hpp"
#include "calib/problem.hpp"
#include "models/robot.hpp"
#include "run/compensation.hpp"
#include "run/monitor_run.hpp"
#include "run/run_spec.hpp"
#include "sim/simulate.hpp"

namespace gpm {
class MeasuredFolder;
}

namespace gpm::scenario {

struct Check {
  std::string name;    // e.g. "error.la1"
  bool passed = true;
  std::string detail;  // measured against limit
};

// A first pass of the excitation path that ended early (the robot left its
// plan): its kept samples fixed the encoder offsets the second pass was
// planned with (run/offsets_first.hpp).
struct FirstPass {
  std::string why;                 // the stop's line, or the offsets stage's
  bool planned = false;            // the offsets stage (sampling.offsets_first_s), not an early end
  std::size_t samples = 0;         // samples it kept
  double robot_time_s = 0.0;       // its robot time (in sim.sampling_s too)
  std::array<double, 3> offsets_change_rad{};  // dth fitted less dth stated
  std::array<double, 3> offsets_sigma_rad{};   // their 1-sigma from the residuals
};

struct RunOutcome {
  std::string scenario_file;
  RunSpec spec;
  std::string hardware_description;  // empty: in-process simulation
  sim::SimulationResult sim;
  Robot nominal;     // the controller's model before calibration
  Robot calibrated;  // nominal with the estimated geometry (= nominal if refused)
  std::optional<calib::Result> calibration;
  std::optional<std::string> refused;          // calibration refused: the diagnosis
  double crb_sigma_rad = 0.0;                  // encoder sigma assumed for the bound
  std::array<double, kNumParams> crb{};        // CRB 1-sigma at the truth (NaN: fixed)
  std::vector<double> residual_urad;           // ML residual per sample after calibration
  std::optional<Accuracy> before, after;
  // The floor: the controller given the actual parameters and the twin's
  // transmission and encoder errors (an oracle; run/compensation.hpp).
  std::optional<Accuracy> floor;
  // The 95 % interval of the calibrated static RMS over the floor's (the
  // bootstrap over the test poses, rms_ratio_interval); none without both.
  std::optional<std::array<double, 2>> floor_ratio_ci95;
  // What a user gets: the calibrated model's noise-free positioning error
  // over an 80 mm disc round home, with the 1-sigma its covariance states
  // (calib/positioning_error.hpp; simulation only: the truth is known).
  std::optional<calib::PositioningError> positioning;
  // Through hardware (no truth): the 1-sigma the calibration states over the
  // same disc, by the calibrated model's own sensitivities (its error and
  // normalised_rms 0: not known).
  std::optional<calib::PositioningError> stated_positioning;
  // The least positioning error the readings allow (um, RMS over the same
  // disc of sqrt(trace(J C J')), C the Cramer-Rao covariance at the truth of
  // the calibration's reading model with its carried error estimated under
  // its prior); on the fly in simulation only, else none.
  std::optional<double> positioning_bound_um;
  // Chi-square test of the ML residuals against the encoder noise (ML cost).
  std::optional<calib::ModelTest> model_test;
  // Samples taken on the fly: compliance and skew estimated with the geometry.
  bool in_motion = false;
  std::array<double, 5> motion_nu{}, motion_nu_sigma{};  // s2, s3 (s), c1..c3 (rad/N m)
  // The reading model the calibration estimated (the monitor's statement
  // with the estimates in place; run/calibration_procedure.hpp).
  std::optional<calib::ReadingModel> reading_estimated;
  // Each drive's friction the calibration found from the hub's force balance (on the fly).
  std::optional<calib::BalanceFriction> friction_balance;
  std::optional<FirstPass> first_pass;     // the path ended early once and was sampled again
  // The twin's truth (in process only, else NaN): the farthest its end-effector
  // went from the plan over the sampling, every pass and retreat (mm).
  double plan_deviation_mm = NAN;
  std::optional<MonitorOutcome> monitor;  // the calibrated model monitoring `operation:` (run/monitor_run.hpp)
  std::vector<Check> checks;
  double seconds = 0.0;

  // True when every expectation holds.
  bool passed() const;
};

using Progress = std::function<void(const std::string& stage)>;

// Runs the scenario. Throws InputError for bad input (including a
// calibration refused as rank-deficient unless the scenario expects it).
// With spec.hardware, the samples are taken through the robot interface and
// appended, flushed, to samples_path as they are taken (a new file, or with
// spec.hardware_resume the stopped session's, continued);
// the errors are then reported against the scenario's actual robot, which is
// the truth only when that hardware simulates this scenario (twin, emulator).
RunOutcome run_scenario(const RunSpec& spec, const std::string& scenario_file,
                        const Progress& progress = {}, const std::string& samples_path = "");

// What a sampling session through the hardware gave (gpm sample).
struct HardwareSampling {
  std::string description;            // the backend and its hardware file
  std::size_t samples = 0;            // samples in the samples file (resumed ones too)
  double robot_time_s = 0.0;          // robot time of this session's passes
  std::optional<FirstPass> first_pass;  // the path ended early once and was sampled again
};

// Samples spec through spec.hardware as run_scenario does (the poses designed
// for the hardware's limits, a path on the fly that ends early sampled a
// second time from the offsets of its samples) into samples_path, without
// calibrating: gpm sample of a scenario whose poses are designed. Throws
// InputError before anything moves, hw errors as run_scenario's sampling.
HardwareSampling sample_through_hardware(const RunSpec& spec, const std::string& samples_path,
                                         const Progress& progress = {});

// Samples spec (its sampling designed: run/sampling_design.hpp) on the
// in-process twin as run_scenario does, through the hardware interface;
// throws sim::TrackingStop with the samples and the trajectory so far when
// the robot leaves its plan (the twin's truth in both: for studies and tests).
sim::SimulationResult sample_in_process(const RunSpec& spec);

// Where a hardware session keeps the samples of a first pass of its path
// that ended early: DIR/samples_first_pass.csv for DIR/samples.csv.
std::string first_pass_samples_path(const std::string& samples_path);

// The files write_run may write into DIR (for the check of the output
// folder against every input before the run: check_output_folder).
const std::vector<std::string>& run_output_names();

// Writes DIR/samples.csv, trajectory.csv, actual.yaml, model.xml,
// calibration.yaml, summary.json, report.md, report.html and the figures,
// all or nothing. With hardware the samples file is the session's (not
// written here) and measured is the hardware session holding DIR
// (models/measured_data.hpp), the only one that may write there.
void write_run(const RunOutcome& outcome, const std::string& dir, const MeasuredFolder* measured = nullptr);

}  // namespace gpm::scenario
