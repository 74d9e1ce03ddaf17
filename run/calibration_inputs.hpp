// What the calibration and the drift monitor of `gpm run` are given besides
// the readings: the scenario's statements (calibration:, monitor:) and the
// robot's data sheet (models/data_sheet.hpp), never the twin's truth
// (sim::Effects, MjcfOptions). A pure function, so that a test can change
// every truth value and see the inputs stay bit-identical.
#pragma once

#include <optional>
#include <string>

#include "calib/motion_correction.hpp"
#include "models/robot.hpp"
#include "run/run_spec.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {

struct CalibrationInputs {
  // The reading effects estimated with the geometry and the transmission
  // load of the force signs (friction, inertia), before the data.
  calib::MotionModel motion;
  // The drive-train effects the data may call for (backlash, harmonic errors
  // per joint and motor revolution; calib/reading_model_selection.hpp): every
  // one on the fly, none otherwise.
  calib::MotionModel drive_candidates;
  DriveFriction drive_friction;  // calibration.drive_friction (default: the data sheet's)
  double hub_mass_kg = 0.0;      // what the hub's force balance moves: the end effector and half of each passive link
  double crossing_s = 0.0;          // calibration.crossing_s: a passive link crossing its play, in seconds
  bool tension_min_stated = false;  // calibration.tension_min_N given: else the force balance sets the threshold
  int encoder_bits = 0;                   // 2^bits counts per encoder revolution (0: ideal encoders)
  double encoder_cyclic_prior_rad = 0.0;  // the encoder's own error once per revolution, per component (data sheet)
  bool estimate_encoder_error = false;    // calibration.estimate's encoder_error: estimated where the encoders turn
                                          // with the joints (encoder_turns_with_joint)
  bool estimate_joint_error = false;      // calibration.estimate's joint_error: the reducer's error once per joint
                                          // revolution estimated where the readings hold it (on motor encoders)
  MonitorReadingModel monitor;   // the monitor's reading model before calibration (monitor:)
};

// Encoder noise of one averaged sample (rad): white reading noise over the
// averaging window (one reading per drive period) plus quantisation (step^2
// / 12), from the scenario's encoder: and servo: (what the drives report).
double effective_sigma(const sim::Scenario& s);

// The inputs of spec's calibration and monitor for robot (the controller's
// robot, whose data_sheet states rotor inertia, link masses and encoder
// accuracy); reads no field of spec.sim.twin.effects or spec.sim.twin.mjcf.
CalibrationInputs calibration_inputs(const RunSpec& spec, const Robot& robot);

// The calibration's inputs (monitor left at its default) from calibration c
// and robot's data sheet for samples taken on the fly or not, by encoders of
// 2^encoder_bits counts (0: ideal) read with 1-sigma sigma_rad: what gpm
// calibrate states of a samples file; calibration_inputs(spec, robot) is this
// at the scenario's values.
CalibrationInputs calibration_inputs(const CalibrationSpec& c, const Robot& robot, bool in_motion, int encoder_bits,
                                     double sigma_rad);

// in for readings whose step (rad) shows the encoder turning once per joint
// revolution (2^bits counts, where the data sheet's gear ratio N > 1 would
// give 2^bits N): the error once per joint revolution carried in the 1-sigma
// is the encoder's own (its accuracy), not the reducer's transmission error,
// which acts before it, and the reducer's backlash, hysteresis and errors per
// motor revolution are no drive-train candidates (nor left-out effects the
// model test names). Returns the note saying so; nullopt (in unchanged)
// when the step agrees with the data sheet, no encoder is stated or no such
// error is carried.
std::optional<std::string> encoder_turns_with_joint(CalibrationInputs& in, double step_rad);

// The transmission load the force signs subtract from each drive torque
// (calib/passive_tension.hpp): the stated friction and, from the data sheet,
// the inertia about A_i of rotor (reflected, J_r N^2), active link (a bar,
// m_a la^2 / 3) and the passive link's half carried at B_i (m_b la^2 / 2).
calib::TransmissionLoad transmission_load(const DriveFriction& friction, const DataSheet& sheet, const Geometry& g);

}  // namespace gpm::scenario
