// Tests of run/calibration_inputs.cpp: no value of the twin's truth reaches
// the calibration or the monitor (every field of sim::Effects and of
// MjcfOptions changed, the inputs bit-identical), and the robot's data sheet
// does (its values, by independent arithmetic); readings of the encoders'
// own step tell that they turn with the joints; the reducer's error once per
// joint revolution is estimated on the fly by default.
#include "run/calibration_inputs.hpp"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
#include "models/robot_yaml.hpp"

namespace gpm::scenario {
namespace {

const std::string kMain = gpm::models_dir() + "/../scenarios/main.yaml";

// Every double of a plain struct of doubles (sim::Effects, MjcfOptions).
template <class T>
std::vector<double> words(const T& x) {
  static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % sizeof(double) == 0);
  std::vector<double> w(sizeof(T) / sizeof(double));
  std::memcpy(w.data(), &x, sizeof(T));
  return w;
}

// The twin's truth with every value changed: each field of sim::Effects and
// of MjcfOptions (masses, armature, damping, solver, its effects) set to a
// value none of them has by default or in the scenario.
sim::TwinConfig changed_truth(sim::TwinConfig t) {
  sim::Effects& e = t.effects;
  for (MjcfEffects* m : {&e.mjcf, &t.mjcf.effects}) {
    m->compliance_rad_per_Nm = {2e-4, 3e-4, 4e-4};
    m->clearance_m = {7e-6, 8e-6, 9e-6};
    m->coulomb_Nm = {0.7, 0.8, 0.9};
    m->viscous_Nm_s = {0.21, 0.22, 0.23};
    m->rotor_mass_kg = 0.07;
    m->friction_timeconst_s = 0.001;
    m->clearance_stiffness_N_per_m = 333.0;
    m->clearance_damping_N_s_per_m = 3.3;
    m->clearance_solref_s = 0.0007;
    m->clearance_solimp = 0.9991;
    m->hub_pin_m = {{{1e-6, 2e-6}, {3e-6, 4e-6}, {5e-6, 6e-6}}};
  }
  e.thermal = sim::ThermalEffect{11e-6, 5.0, 321.0, 12e-6, 1234.0};
  for (std::size_t i = 0; i < 3; ++i) {
    sim::DriveChain& c = e.drive.chain[i];
    const double k = static_cast<double>(i + 1);
    c = sim::DriveChain{1e-4 * k, {1e4 * k, 2e4 * k, 3e4 * k}, {1.0 * k, 5.0 * k}, 1e-5 * k, 2e-5 * k, 0.4 * k,
                        3e-5 * k, 0.5 * k, 0.05 * k, 0.02 * k, 0.01 * k, 0.03 * k, 0.02 * k, 0.6 * k};
  }
  e.drive.te_motor_order = 3;
  e.drive.cogging_periods_per_motor_rev = 30;
  for (std::size_t h = 0; h < e.encoder_harmonics.size(); ++h) {
    const double k = static_cast<double>(h + 1);
    e.encoder_harmonics[h] = sim::EncoderHarmonic{static_cast<int>(h) + 2, {1e-6 * k, 2e-6 * k, 3e-6 * k},
                                                  {0.1 * k, 0.2 * k, 0.3 * k}};
  }
  e.encoder_jitter_s = {1e-6, 2e-6, 3e-6};
  e.encoder_cyclic_rad = {3e-5, 4e-5, 5e-5};
  e.encoder_phase_rad = {0.1, 0.2, 0.3};
  e.encoder_skew_s = {1e-5, 7e-5, 3e-4};
  e.gear_ratio = 13.0;
  MjcfOptions& m = t.mjcf;
  m.timestep_s = 0.0002;
  m.active_link_mass_kg = 0.47;
  m.passive_link_mass_kg = 0.31;
  m.ee_mass_kg = 0.17;
  m.link_radius_m = 0.013;
  m.active_damping = 0.07;
  m.passive_damping = 0.003;
  m.armature_kg_m2 = 0.0031;
  m.solref_timeconst_s = 0.0011;
  m.solref_dampratio = 0.9;
  m.solimp_dmin = 0.9998;
  m.solimp_dmax = 0.9997;
  m.solimp_width_m = 0.002;
  return t;
}

bool same(double a, double b) { return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b); }

template <std::size_t N>
bool same(const std::array<double, N>& a, const std::array<double, N>& b) {
  for (std::size_t i = 0; i < N; ++i)
    if (!same(a[i], b[i])) return false;
  return true;
}

// Field by field, every double compared bit for bit.
void expect_identical(const CalibrationInputs& a, const CalibrationInputs& b) {
  const calib::MotionModel &m = a.motion, &n = b.motion;
  EXPECT_EQ(m.skew, n.skew);
  EXPECT_EQ(m.compliance, n.compliance);
  EXPECT_EQ(m.friction, n.friction);
  EXPECT_EQ(m.clearance, n.clearance);
  EXPECT_TRUE(same(m.load.coulomb_Nm, n.load.coulomb_Nm));
  EXPECT_TRUE(same(m.load.viscous_Nm_s, n.load.viscous_Nm_s));
  EXPECT_TRUE(same(m.load.inertia_kg_m2, n.load.inertia_kg_m2));
  EXPECT_TRUE(same(m.load.friction_speed_rad_s, n.load.friction_speed_rad_s));
  EXPECT_TRUE(same(m.tension_min_N, n.tension_min_N));
  EXPECT_EQ(m.drop_uncertain, n.drop_uncertain);
  EXPECT_TRUE(same(m.min_kept_share, n.min_kept_share));
  EXPECT_EQ(m.torque_before, n.torque_before);
  EXPECT_EQ(m.torque_between, n.torque_between);
  EXPECT_TRUE(same(m.cyclic_prior_rad, n.cyclic_prior_rad));
  EXPECT_EQ(m.estimate_cyclic, n.estimate_cyclic);
  EXPECT_EQ(m.skip_first, n.skip_first);
  EXPECT_EQ(m.max_passes, n.max_passes);
  EXPECT_TRUE(same(a.drive_friction.coulomb_Nm, b.drive_friction.coulomb_Nm));
  EXPECT_TRUE(same(a.drive_friction.viscous_Nm_s, b.drive_friction.viscous_Nm_s));
  EXPECT_EQ(a.drive_friction.fit_scale, b.drive_friction.fit_scale);
  const MonitorReadingModel &r = a.monitor, &s = b.monitor;
  const calib::ReadingModel &x = r.reading, &y = s.reading;
  EXPECT_TRUE(same(x.cyclic_rad, y.cyclic_rad));
  EXPECT_TRUE(same(x.clearance_mm, y.clearance_mm));
  EXPECT_TRUE(same(x.load.coulomb_Nm, y.load.coulomb_Nm));
  EXPECT_TRUE(same(x.load.viscous_Nm_s, y.load.viscous_Nm_s));
  EXPECT_TRUE(same(x.skew_s, y.skew_s));
  EXPECT_TRUE(same(x.compliance_rad_per_Nm, y.compliance_rad_per_Nm));
  EXPECT_TRUE(same(x.backlash_rad, y.backlash_rad));
  EXPECT_TRUE(same(x.gear_ratio, y.gear_ratio));
  EXPECT_TRUE(same(r.thermal_time_constant_s, s.thermal_time_constant_s));
}

// The Goal of the issue: change every truth value the data sheet does not
// state and the calibration's and the monitor's inputs stay bit-identical.
TEST(CalibrationInputs, NoValueOfTheTwinsTruthReachesThem) {
  const RunSpec spec = load_run_spec(kMain);
  RunSpec other = spec;
  other.sim.twin = changed_truth(spec.sim.twin);
  // Every double of the truth changed (a field added later and left out of
  // changed_truth fails here).
  const std::vector<double> e0 = words(spec.sim.twin.effects), e1 = words(other.sim.twin.effects);
  for (std::size_t k = 0; k < e0.size(); ++k) EXPECT_FALSE(same(e0[k], e1[k])) << "sim::Effects word " << k << " unchanged";
  const std::vector<double> m0 = words(spec.sim.twin.mjcf), m1 = words(other.sim.twin.mjcf);
  for (std::size_t k = 0; k < m0.size(); ++k) EXPECT_FALSE(same(m0[k], m1[k])) << "MjcfOptions word " << k << " unchanged";
  expect_identical(calibration_inputs(spec, spec.sim.controller), calibration_inputs(other, other.sim.controller));
  // And the ideal twin (no effects) gives them the same too.
  RunSpec ideal = spec;
  ideal.sim.twin.effects = sim::Effects{};
  ideal.sim.twin.mjcf = MjcfOptions{};
  expect_identical(calibration_inputs(spec, spec.sim.controller), calibration_inputs(ideal, ideal.sim.controller));
}

// The same through the scenario file: the twin's effects: and physics: keys
// changed, the parsed spec gives the same inputs.
TEST(CalibrationInputs, TheScenariosTwinKeysDoNotReachThem) {
  const std::string head =
      "robot: models/gpm2002.yaml\nsampling: {pattern: trajectory, count: 40}\nservo: {rate_hz: 4000}\n";
  const std::string base = gpm::models_dir() + "/..";
  const RunSpec a = parse_run_spec(head + "physics: {timestep_s: 0.00025}\neffects: realistic\n", "a.yaml", base);
  const RunSpec b = parse_run_spec(
      head + "physics: {timestep_s: 0.000125}\neffects: {preset: realistic, transmission_compliance_rad_per_Nm: 3.0e-4, "
             "passive_clearance_mm: 0.02, coulomb_friction_Nm: 2, viscous_friction_Nm_s: 1, encoder_cyclic_rad: 5.0e-5, "
             "encoder_skew_s: 0.0003, gear_ratio: 7, thermal: {expansion_per_K: 1.0e-5, rise_K: 9, time_constant_s: 30}}\n",
      "b.yaml", base);
  ASSERT_NE(a.sim.twin.effects.mjcf.coulomb_Nm, b.sim.twin.effects.mjcf.coulomb_Nm);
  expect_identical(calibration_inputs(a, a.sim.controller), calibration_inputs(b, b.sim.controller));
}

// The data sheet does reach them: the GPM2002's values by independent
// arithmetic, and another robot's data sheet changes them.
TEST(CalibrationInputs, TheRobotsDataSheetReachesThem) {
  const RunSpec spec = load_run_spec(kMain);
  const CalibrationInputs in = calibration_inputs(spec, spec.sim.controller);
  // Rotor 0.26e-4 kg m^2 x 10^2 + (0.40 / 3 + 0.25 / 2) kg x 0.244^2 m^2 = 0.0026 + 0.0153801 kg m^2.
  for (double j : in.motion.load.inertia_kg_m2) EXPECT_NEAR(j, 0.0179801, 1e-7);
  for (double f : in.motion.load.coulomb_Nm) EXPECT_EQ(f, 0.3);
  for (double b : in.motion.load.viscous_Nm_s) EXPECT_EQ(b, 0.15);
  EXPECT_DOUBLE_EQ(in.motion.cyclic_prior_rad, 4.3633e-4 / std::sqrt(2.0));  // the reducer's 1.5 arcmin / sqrt 2 (N = 10)
  EXPECT_EQ(in.monitor.reading.compliance_rad_per_Nm, (std::array<double, 3>{1e-4, 1e-4, 1e-4}));

  Robot other = spec.sim.controller;
  other.data_sheet.rotor_inertia_kg_m2.nominal = 5.2e-5;  // twice the rotor: + 0.0026 kg m^2
  other.data_sheet.transmission_error_rad.nominal *= 2.0;
  other.data_sheet.coulomb_Nm.nominal = 0.6;  // the friction the spec resolved is the spec's, not re-read
  const CalibrationInputs o = calibration_inputs(spec, other);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(o.motion.load.inertia_kg_m2[i] - in.motion.load.inertia_kg_m2[i], 0.0026, 1e-12);
  EXPECT_DOUBLE_EQ(o.motion.cyclic_prior_rad, 2.0 * in.motion.cyclic_prior_rad);
  EXPECT_EQ(o.drive_friction.coulomb_Nm, in.drive_friction.coulomb_Nm);
  // The motor's cogging periods (12 slots, 8 poles): a candidate of every joint; none where not stated.
  EXPECT_EQ(in.motion.cogging_periods, 24.0);
  EXPECT_EQ(in.drive_candidates.cogging, (std::array<bool, 3>{true, true, true}));
  other.data_sheet.cogging_periods = 0;
  EXPECT_EQ(calibration_inputs(spec, other).drive_candidates.cogging, (std::array<bool, 3>{}));
}

// Readings whose step is one of the encoder's 2^17 counts per joint
// revolution, where the data sheet's 10:1 reducer would make it ten times
// finer: the encoders turn with the joints, so the error once per joint
// revolution is carried with the encoder's accuracy (+-2e-5 rad: 2e-5 / sqrt 2
// per component) instead of the reducer's 1.5 arcmin; the drive train's
// candidates stay. A step that fits the reducer, or neither, or no stated
// encoder, changes nothing.
TEST(CalibrationInputs, ReadingsOfTheEncodersOwnStepMeanTheyTurnWithTheJoints) {
  const RunSpec spec = load_run_spec(kMain);
  const CalibrationInputs stated = calibration_inputs(spec, spec.sim.controller);
  ASSERT_EQ(stated.encoder_bits, 17);
  ASSERT_EQ(stated.motion.gear_ratio, 10.0);
  ASSERT_EQ(stated.drive_candidates.backlash, (std::array<bool, 3>{true, true, true}));
  ASSERT_TRUE(stated.motion.encoder_on_motor);
  const double turn = 2.0 * std::numbers::pi;
  CalibrationInputs direct = stated;
  const std::optional<std::string> note = encoder_turns_with_joint(direct, turn / 131072.0);
  ASSERT_TRUE(note);
  EXPECT_NE(note->find("131072 counts per joint revolution"), std::string::npos) << *note;
  EXPECT_DOUBLE_EQ(direct.motion.cyclic_prior_rad, 2e-5 / std::sqrt(2.0));
  EXPECT_EQ(direct.motion.gear_ratio, 10.0);
  // Their own error is estimated under that prior on the fly (the main job),
  // carried where calibration.estimate leaves encoder_error out.
  EXPECT_FALSE(stated.motion.estimate_cyclic);
  EXPECT_TRUE(direct.motion.estimate_cyclic);
  EXPECT_NE(note->find("estimated with the geometry under that prior"), std::string::npos) << *note;
  RunSpec listed = spec;
  listed.calibration.estimate_encoder_error = false;
  CalibrationInputs carried = calibration_inputs(listed, listed.sim.controller);
  const std::optional<std::string> carried_note = encoder_turns_with_joint(carried, turn / 131072.0);
  ASSERT_TRUE(carried_note);
  EXPECT_FALSE(carried.motion.estimate_cyclic);
  EXPECT_NE(carried_note->find("carried in the 1-sigma under that prior"), std::string::npos) << *carried_note;
  // The reducer acts before such an encoder: none of its drive-train effects is a candidate.
  const std::array<bool, 3> none{};
  EXPECT_FALSE(direct.motion.encoder_on_motor);
  EXPECT_EQ(direct.drive_candidates.backlash, none);
  EXPECT_EQ(direct.drive_candidates.hysteresis, none);
  EXPECT_EQ(direct.drive_candidates.motor_harmonic1, none);
  EXPECT_EQ(direct.drive_candidates.motor_harmonic2, none);
  EXPECT_EQ(direct.drive_candidates.cogging, none);  // it twists the transmission, not what such an encoder reads
  for (const double step : {turn / 1310720.0, turn / (131072.0 * 1.05)}) {
    CalibrationInputs geared = stated;
    EXPECT_FALSE(encoder_turns_with_joint(geared, step)) << step;
    EXPECT_EQ(geared.motion.gear_ratio, 10.0);
    EXPECT_EQ(geared.motion.cyclic_prior_rad, stated.motion.cyclic_prior_rad);
    EXPECT_EQ(geared.drive_candidates.motor_harmonic1, stated.drive_candidates.motor_harmonic1);
    EXPECT_EQ(geared.drive_candidates.backlash, stated.drive_candidates.backlash);
    EXPECT_TRUE(geared.motion.encoder_on_motor);
  }
  CalibrationInputs ideal = stated;
  ideal.encoder_bits = 0;
  EXPECT_FALSE(encoder_turns_with_joint(ideal, turn / 131072.0));
  EXPECT_EQ(ideal.motion.gear_ratio, 10.0);
}

// On the fly the reducer's error once per joint revolution is estimated where
// the readings hold it unless calibration.estimate lists the effects without
// it; static samples carry it (no motion model to estimate it in).
TEST(CalibrationInputs, TheReducersErrorOncePerJointRevolutionIsEstimatedOnTheFly) {
  const RunSpec spec = load_run_spec(kMain);
  EXPECT_TRUE(calibration_inputs(spec, spec.sim.controller).estimate_joint_error);
  RunSpec listed = spec;
  listed.calibration.estimate_joint_error = false;
  EXPECT_FALSE(calibration_inputs(listed, listed.sim.controller).estimate_joint_error);
  RunSpec still = spec;
  still.sim.sampling->pattern = sim::PosePattern::kDesigned;
  EXPECT_FALSE(calibration_inputs(still, still.sim.controller).estimate_joint_error);
}

// A robot file's data sheet sets the scenario's defaults (calibration.drive_friction,
// monitor: data_sheet); the scenario's own keys still override them.
TEST(CalibrationInputs, DataSheetOfTheScenariosRobotSetsTheDefaults) {
  const std::string robot = "robot: {name: R, geometry: {xa1: 0, ya1: 250, xa2: 433, ya2: 0, xa3: 433, ya3: 500, "
                            "la1: 244, la2: 244, la3: 244, lb1: 244, lb2: 244, lb3: 244, dth1: 0, dth2: 0, dth3: 0}, "
                            "data_sheet: {coulomb_Nm: 0.5, viscous_Nm_s: {nominal: 0.2, factor: [0.5, 2]}, "
                            "stiffness_Nm_per_rad: 2.0e+4, latch_skew_s: 1.0e-5, clearance_mm: 0.01}}\n"
                            "sampling: {pattern: trajectory, count: 40}\n";
  const std::string base = gpm::models_dir() + "/..";
  const RunSpec s = parse_run_spec(robot, "r.yaml", base);
  const CalibrationInputs in = calibration_inputs(s, s.sim.controller);
  using Three = std::array<double, 3>;
  EXPECT_EQ(in.drive_friction.coulomb_Nm, (Three{0.5, 0.5, 0.5}));
  EXPECT_EQ(in.motion.load.viscous_Nm_s, (Three{0.2, 0.2, 0.2}));
  EXPECT_EQ(in.monitor.reading.load.coulomb_Nm, (Three{0.5, 0.5, 0.5}));
  EXPECT_EQ(in.monitor.reading.compliance_rad_per_Nm, (Three{5e-5, 5e-5, 5e-5}));
  EXPECT_EQ(in.monitor.reading.skew_s, (Three{0.0, 1e-5, 2e-5}));
  EXPECT_EQ(in.monitor.reading.clearance_mm, (Three{0.02, 0.02, 0.02}));  // both pins
  const RunSpec told = parse_run_spec(robot + "calibration: {drive_friction: {coulomb_Nm: 0.1}}\nmonitor: {skew_s: 0}\n",
                                      "r.yaml", base);
  const CalibrationInputs t = calibration_inputs(told, told.sim.controller);
  EXPECT_EQ(t.drive_friction.coulomb_Nm, (Three{0.1, 0.1, 0.1}));
  EXPECT_EQ(t.drive_friction.viscous_Nm_s, (Three{0.2, 0.2, 0.2}));  // a key left out: the data sheet's
  EXPECT_EQ(t.monitor.reading.skew_s, (Three{0.0, 0.0, 0.0}));
  EXPECT_EQ(t.monitor.reading.clearance_mm, (Three{0.02, 0.02, 0.02}));
}

}  // namespace
}  // namespace gpm::scenario
