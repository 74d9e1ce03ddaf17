#include "run/calibration_inputs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

namespace gpm::scenario {

double effective_sigma(const sim::Scenario& s) {
  // On the fly every sample is one instantaneous reading.
  const double n_avg = s.sampling->pattern == sim::PosePattern::kTrajectory
                           ? 1.0
                           : std::max(1.0, std::round(s.sampling->options.average_s * s.twin.servo_rate_hz));
  return calib::reading_sigma(calib::encoder_step_rad(s.twin.encoder.bits), s.twin.encoder.noise_rad, n_avg);
}

calib::TransmissionLoad transmission_load(const DriveFriction& friction, const DataSheet& sheet, const Geometry& g) {
  calib::TransmissionLoad load;
  for (std::size_t i = 0; i < 3; ++i) {
    const double la_m = 1e-3 * g.la_(static_cast<int>(i));
    load.coulomb_Nm[i] = friction.coulomb_Nm[i];
    load.viscous_Nm_s[i] = friction.viscous_Nm_s[i];
    load.rotor_inertia_kg_m2[i] = sheet.reflected_inertia_kg_m2();
    load.inertia_kg_m2[i] =
        sheet.reflected_inertia_kg_m2() +
        (sheet.active_link_mass_kg.nominal / 3.0 + sheet.passive_link_mass_kg.nominal / 2.0) * la_m * la_m;
  }
  return load;
}

CalibrationInputs calibration_inputs(const RunSpec& spec, const Robot& robot) {
  const bool in_motion = spec.sim.sampling && spec.sim.sampling->pattern == sim::PosePattern::kTrajectory;
  // (effective_sigma needs the sampling: only on the fly, where the sigma matters.)
  const double sigma = in_motion ? spec.calibration.sigma.value_or(effective_sigma(spec.sim)) : 0.0;
  CalibrationInputs in = calibration_inputs(spec.calibration, robot, in_motion, spec.sim.twin.encoder.bits, sigma);
  in.monitor = spec.monitor;
  return in;
}

CalibrationInputs calibration_inputs(const CalibrationSpec& c, const Robot& robot, bool in_motion, int encoder_bits,
                                     double sigma_rad) {
  CalibrationInputs in;
  calib::MotionModel& motion = in.motion;
  motion.compliance = c.estimate_compliance.value_or(in_motion);
  motion.skew = c.estimate_skew.value_or(in_motion);
  motion.friction = motion.compliance && c.estimate_friction.value_or(in_motion);
  // On the fly the samples are consecutive: the transmission's ringing twist
  // is a response to the torques of the periods since the sample before too
  // (calib/motion_correction.hpp). Only with a reading noise to judge it by:
  // from noiseless readings (ideal encoders) the twin's soft loop closure,
  // which follows the forces, showed as h at 30 sigma and moved dth3 by 4e-5 rad.
  motion.torque_before = in_motion && motion.compliance && sigma_rad > 0.0;
  // On the fly the error once per joint revolution (the reducer's
  // transmission error, and the encoder's own on a direct drive) is carried
  // in the 1-sigma and the bound with the data sheet's largest amplitude A as
  // its prior, A / sqrt 2 per component (the spread of A cos(phase) over a
  // phase unknown; calib/motion_correction.hpp: considered, not estimated:
  // over the joints' range of motion it is nearly the geometry's own
  // directions, docs/PROCEDURES.md). Ideal encoders (bits 0: no noise to
  // weigh a prior against) have none.
  if (in_motion && encoder_bits > 0) {
    motion.cyclic_prior_rad = robot.data_sheet.joint_harmonic_max_rad() / std::sqrt(2.0);
    in.encoder_cyclic_prior_rad = robot.data_sheet.encoder_accuracy_rad.max() / std::sqrt(2.0);
  }
  in.encoder_bits = encoder_bits;
  in.estimate_encoder_error = c.estimate_encoder_error.value_or(in_motion);
  in.estimate_joint_error = in_motion && c.estimate_joint_error.value_or(true);
  if (c.tension_min_N) motion.tension_min_N = *c.tension_min_N;
  // On the fly the joint clearance is estimated (a play whose force sign
  // never changes is left to lb_i).
  motion.clearance = c.estimate_clearance.value_or(in_motion);
  motion.load = transmission_load(c.drive_friction, robot.data_sheet, robot.geometry);
  motion.gear_ratio = robot.data_sheet.gear_ratio;
  motion.cogging_periods = robot.data_sheet.cogging_periods;
  motion.hysteresis_compliance_rad_per_Nm = robot.data_sheet.compliance_rad_per_Nm();
  // On the fly the data choose, per joint, a backlash, the errors once and
  // twice per motor revolution, the motor's cogging (where the data sheet
  // states its periods) and a hysteresis (calib/reading_model_selection.hpp).
  if (in_motion && motion.compliance) {
    in.drive_candidates.backlash = {true, true, true};
    in.drive_candidates.hysteresis = {true, true, true};
    in.drive_candidates.motor_harmonic1 = {true, true, true};
    in.drive_candidates.motor_harmonic2 = {true, true, true};
    if (motion.cogging_periods > 0.0) in.drive_candidates.cogging = {true, true, true};
  }
  in.drive_friction = c.drive_friction;
  in.tension_min_stated = c.tension_min_N.has_value();
  in.crossing_s = c.crossing_s;
  in.hub_mass_kg = robot.data_sheet.end_effector_mass_kg.nominal + 1.5 * robot.data_sheet.passive_link_mass_kg.nominal;
  return in;
}

std::optional<std::string> encoder_turns_with_joint(CalibrationInputs& in, double step_rad) {
  const double ratio = in.motion.gear_ratio;
  if (in.encoder_bits <= 0 || !(ratio > 1.0) || !(step_rad > 0.0) || !(in.motion.cyclic_prior_rad > 0.0))
    return std::nullopt;
  const double counts = 2.0 * std::numbers::pi / step_rad, encoder = std::ldexp(1.0, in.encoder_bits);
  // The step is a lattice's gap, exact to the 2 % reading_step checks it to.
  if (std::abs(counts / encoder - 1.0) > 0.02) return std::nullopt;
  in.motion.cyclic_prior_rad = in.encoder_cyclic_prior_rad;
  // Small beside the reading noise and seen by nothing else the model
  // misses, the encoders' own error is estimated under its prior: poses
  // designed for it tell it from the geometry (calib/excitation/
  // positioning_design.hpp). The reducers' error, 20 times larger, stays
  // carried: where the model misses a drive train it would take up the misfit.
  in.motion.estimate_cyclic = in.estimate_encoder_error;
  // The reducer is before the encoder: its backlash, hysteresis and errors
  // per motor revolution move the reading with the link, not between them.
  in.motion.encoder_on_motor = false;
  in.drive_candidates.backlash = in.drive_candidates.hysteresis = {false, false, false};
  in.drive_candidates.motor_harmonic1 = in.drive_candidates.motor_harmonic2 = {false, false, false};
  in.drive_candidates.cogging = {false, false, false};
  return fmt::format(
      "the encoders turn once per joint revolution ({:.0f} counts per joint revolution, their 2^{}; behind the data "
      "sheet's {:g}:1 reducer they would read {:g} times finer): the error once per joint revolution is theirs "
      "(data sheet +-{:.2g} rad, {} under that prior), not the reducer's, and the reducer's backlash, hysteresis "
      "and errors per motor revolution, before the encoders, are no candidates of the reading model",
      counts, in.encoder_bits, ratio, ratio, in.encoder_cyclic_prior_rad * std::sqrt(2.0),
      in.estimate_encoder_error ? "estimated with the geometry" : "carried in the 1-sigma");
}

}  // namespace gpm::scenario
