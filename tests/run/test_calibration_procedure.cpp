// Tests of run/calibration_procedure.cpp: gpm run's calibration of a short
// on-the-fly scenario made again from its samples.csv alone (the readings,
// times and drive torques, and the robot file's data sheet, as gpm calibrate
// does) gives the same result to the last bit; samples without times or
// torques get the static fit and its model test; missing inputs refused;
// readings of drives polled one after another are carried to joint 1's
// instant by their read times (t_read1..3), which the latch skew otherwise
// takes up; a failed model test names the effect the model leaves out.
#include "run/calibration_procedure.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <limits>
#include <optional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/runner.hpp"
#include "sim/simulate.hpp"

namespace gpm::scenario {
namespace {

const std::string kSmall = std::string(GPM_SOURCE_DIR) + "/tests/fixtures/on_the_fly_small.yaml";

// The fixture's run, made once for every test of this file.
const RunOutcome& small_run() {
  static const RunOutcome o = run_scenario(load_run_spec(kSmall), kSmall);
  return o;
}

// gpm calibrate's procedure for samples s with the GPM2002's robot file,
// xa1, ya1, xa2, ya2 fixed, the model in motion where s allows it (unless static_model).
FileProcedure gpm2002_file_procedure(const Samples& s, bool static_model = false) {
  const Robot robot = load_robot(std::string(GPM_SOURCE_DIR) + "/models/gpm2002.yaml");
  return samples_file_procedure(s, robot, robot.geometry, ~parse_param_list("xa1,ya1,xa2,ya2", "--fix"), {},
                                std::nullopt, static_model);
}

// What gpm calibrate runs on a samples file (app/cmd_calibrate.cpp at its
// The reading model after a calibration in motion: the statement with the
// estimates in place where made (skew and compliance with a positive
// 1-sigma, a value fitted below 0 none, the play where looked for, the
// friction where scaled, the harmonics estimated).
TEST(CalibrationProcedure, EstimatedReadingModelTakesTheEstimatesWhereMade) {
  calib::ReadingModel stated;
  stated.skew_s = {0.0, 7e-6, 8e-6};
  stated.compliance_rad_per_Nm = {1e-4, 1e-4, 1e-4};
  stated.clearance_mm = {0.01, 0.01, 0.01};
  stated.load.coulomb_Nm = {0.3, 0.3, 0.3};
  stated.cyclic_rad = {2e-5, 2e-5, 2e-5};
  calib::MotionFit fit;
  calib::MotionModel motion;
  // No motion corrections fitted (1-sigma 0): the statement.
  fit.nu = {1e-4, 2e-4, 3e-4, 4e-4, 5e-4};
  calib::ReadingModel r = estimated_reading_model(stated, fit, motion, false, false);
  EXPECT_EQ(r.skew_s, stated.skew_s);
  EXPECT_EQ(r.compliance_rad_per_Nm, stated.compliance_rad_per_Nm);
  EXPECT_EQ(r.clearance_mm, stated.clearance_mm);
  // Joint 1 torque-off (its compliance NaN: not estimated) keeps the statement;
  // chain 3's play fitted below 0 is none; the friction is motion's (scaled).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  fit.nu_sigma = {1e-6, 1e-6, nan, 1e-5, 1e-5};
  fit.nu[3] = -6e-6;
  fit.clearance = {0.010, 0.008, -0.001};
  fit.backlash = {nan, 2e-4, -1e-5};
  fit.backlash_sigma = {nan, 1e-5, 1e-5};
  fit.harmonic[1][4] = 3e-5;
  motion.load.coulomb_Nm = {0.15, 0.15, 0.15};
  motion.gear_ratio = 50.0;
  r = estimated_reading_model(stated, fit, motion, true, true);
  EXPECT_EQ(r.skew_s, (std::array<double, 3>{0.0, 1e-4, 2e-4}));
  EXPECT_EQ(r.compliance_rad_per_Nm, (std::array<double, 3>{1e-4, 0.0, 5e-4}));
  EXPECT_EQ(r.clearance_mm, (std::array<double, 3>{0.010, 0.008, 0.0}));
  EXPECT_EQ(r.backlash_rad, (std::array<double, 3>{0.0, 2e-4, 0.0}));
  EXPECT_EQ(r.load.coulomb_Nm, motion.load.coulomb_Nm);
  EXPECT_EQ(r.harmonic[1][4], 3e-5);
  EXPECT_EQ(r.gear_ratio, 50.0);
  EXPECT_EQ(r.cyclic_rad, stated.cyclic_rad);  // not estimated: the statement
  // The play looked for and not found: none (zeros), not the statement's.
  fit.clearance = {};
  EXPECT_EQ(estimated_reading_model(stated, fit, motion, true, true).clearance_mm, (std::array<double, 3>{}));
}

// defaults): the robot file's data sheet, no scenario.
// friction_from_balance false: the data sheet's friction, not the force balance's;
// tension_min_N: the force signs' threshold stated (calibration.tension_min_N); ratio_from_step false:
// the encoders' counts unstated, so the reducer's error once per joint revolution is carried whatever the readings' step;
// crossing_s: calibration.crossing_s (the default 0.02 s); joint_error false: the reducer's error once per joint
// revolution carried, never estimated (calibration.estimate listing the effects without joint_error).
CalibrationOutcome calibrate_file(const Samples& s, bool static_model = false, bool friction_from_balance = true,
                                  std::optional<double> tension_min_N = std::nullopt, bool ratio_from_step = true,
                                  double crossing_s = 0.02, bool joint_error = true) {
  FileProcedure p = gpm2002_file_procedure(s, static_model);
  p.inputs.estimate_joint_error = p.inputs.estimate_joint_error && joint_error;
  p.inputs.drive_friction.from_balance = friction_from_balance;
  p.inputs.crossing_s = crossing_s;
  if (!ratio_from_step) p.inputs.encoder_bits = 0;  // the encoders' counts unknown: the data sheet's gear ratio stands
  if (tension_min_N) {
    p.inputs.tension_min_stated = true;
    p.inputs.motion.tension_min_N = *tension_min_N;
  }
  EXPECT_EQ(p.options.in_motion, !static_model && taken_on_the_fly(s));
  return calibrate_samples(sample_series(s), p.inputs, p.options);
}

TEST(CalibrationProcedure, SamplesFileGivesTheRunsResultBitForBit) {
  const RunOutcome& o = small_run();
  ASSERT_TRUE(o.calibration && o.model_test && o.in_motion);
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  ASSERT_TRUE(taken_on_the_fly(s));
  const CalibrationOutcome c = calibrate_file(s);
  ASSERT_TRUE(c.with_effects && c.model_test);
  for (int i = 0; i < kNumParams; ++i) {
    EXPECT_EQ(c.result.geometry[i], o.calibration->geometry[i]) << param_name(i);
    const double a = c.result.sigma[static_cast<size_t>(i)], b = o.calibration->sigma[static_cast<size_t>(i)];
    EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << param_name(i);
  }
  EXPECT_EQ(c.model_test->chi2, o.model_test->chi2);
  EXPECT_EQ(c.model_test->dof, o.model_test->dof);
  EXPECT_EQ(c.model_test->passed, o.model_test->passed);
  EXPECT_EQ(c.result.notes, o.calibration->notes);
  EXPECT_EQ(c.fit.nu, o.motion_nu);
}

// The realistic twin's encoders read 2^17 counts per joint revolution, not
// the data sheet's 10:1 reducer's 2^17 x 10: the procedure takes them as
// turning with the joints (run/calibration_inputs.hpp encoder_turns_with_joint)
// and says so after the step it found.
TEST(CalibrationProcedure, EncodersOfTheTwinsStepTurnWithTheJoints) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  const CalibrationOutcome c = calibrate_file(s);
  EXPECT_DOUBLE_EQ(c.motion.cyclic_prior_rad, 2e-5 / std::sqrt(2.0));  // the data sheet's encoder accuracy
  const auto step = std::ranges::find_if(c.result.notes, [](const std::string& n) { return n.starts_with("reading resolution"); });
  ASSERT_NE(step, c.result.notes.end());
  ASSERT_NE(std::next(step), c.result.notes.end());
  EXPECT_TRUE(std::next(step)->starts_with("the encoders turn once per joint revolution")) << *std::next(step);
  // The reducer is before them: no backlash, hysteresis or error per motor revolution is estimated.
  EXPECT_FALSE(c.motion.encoder_on_motor);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_FALSE(c.motion.backlash[i] || c.motion.hysteresis[i] || c.motion.motor_harmonic1[i] || c.motion.motor_harmonic2[i])
        << "joint " << i + 1;
}

// The small run on a twin whose drives' friction differs per joint and from
// the data sheet's 0.3 N m (Coulomb; viscous: the model's 0.05 N m s/rad
// plus the effect's), calibrated from its samples.csv as gpm calibrate does:
// the force balance finds each drive's friction, closer than the data sheet
// (on 20 drawn robots it read 0.6 N m as 0.47-0.52: within 25 %), and the
// notes say so.
TEST(CalibrationProcedure, TheForceBalanceFindsEachDrivesFrictionOnTheTwin) {
  std::ifstream file(kSmall);
  std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const std::array<double, 3> coulomb{0.15, 0.3, 0.6}, viscous{0.25, 0.1, 0.15};
  const std::string realistic = "effects: realistic";
  text.replace(text.find(realistic), realistic.size(),
               "effects: {preset: realistic, coulomb_friction_Nm: [0.15, 0.3, 0.6], viscous_friction_Nm_s: [0.2, 0.05, 0.1]}");
  const RunOutcome o = run_scenario(parse_run_spec(text, kSmall, std::string(GPM_SOURCE_DIR) + "/tests/fixtures"), kSmall);
  const CalibrationOutcome c = calibrate_file(parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv"));
  ASSERT_TRUE(c.friction_balance);
  const calib::BalanceFriction& f = *c.friction_balance;
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(f.coulomb_Nm[i], coulomb[i], 0.25 * coulomb[i]) << "joint " << i + 1;
    EXPECT_NEAR(f.viscous_Nm_s[i], viscous[i], 0.1) << "joint " << i + 1;
  }
  EXPECT_LT(std::abs(f.coulomb_Nm[0] - coulomb[0]), 0.3 - coulomb[0]);  // the data sheet's 0.3 N m is farther
  EXPECT_LT(std::abs(f.coulomb_Nm[2] - coulomb[2]), coulomb[2] - 0.3);
  // Joints 1 and 3 contradict the data sheet: their friction is the
  // balance's (times the model test's one factor), joint 2's may stay stated.
  const std::array<double, 3>& used = c.motion.load.coulomb_Nm;
  EXPECT_NEAR(used[0] / f.coulomb_Nm[0], used[2] / f.coulomb_Nm[2], 1e-12);
  const auto note = std::ranges::find_if(c.result.notes, [](const std::string& n) {
    return n.starts_with("drive friction per joint from the hub's force balance");
  });
  ASSERT_NE(note, c.result.notes.end());
  EXPECT_TRUE(note->find("Coulomb of joints 1, 3,") != std::string::npos ||
              note->find("Coulomb of joints 1, 2, 3,") != std::string::npos) << *note;
  // The clearance's force signs are taken as certain beyond twice a link's
  // force 1-sigma as the balance sees it (no threshold stated); the fit's may
  // be lower, to keep a quarter of the samples.
  EXPECT_GT(f.tension_sigma_N, 0.0);
  EXPECT_EQ(c.motion.tension_min_N, 2.0 * f.tension_sigma_N);
  EXPECT_LE(c.fit.tension_min_N, c.motion.tension_min_N);
  EXPECT_NE(note->find(fmt::format("force sign taken as certain above {:.2g} N", c.motion.tension_min_N)), std::string::npos)
      << *note;
}

// A threshold the user states (calibration.tension_min_N) is the one the
// clearance's force signs are judged by, not the balance's.
TEST(CalibrationProcedure, AStatedForceSignThresholdIsKept) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  const CalibrationOutcome c = calibrate_file(s, false, true, 0.5);
  ASSERT_TRUE(c.friction_balance);
  ASSERT_NE(2.0 * c.friction_balance->tension_sigma_N, 0.5);
  EXPECT_EQ(c.motion.tension_min_N, 0.5);
}

TEST(CalibrationProcedure, WithoutTimesAndTorquesTheStaticFitAndItsModelTest) {
  const RunOutcome& o = small_run();
  Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  s.t.clear(), s.tau.clear(), s.tau_last.clear(), s.tau_between.clear();
  EXPECT_FALSE(taken_on_the_fly(s));
  const CalibrationOutcome c = calibrate_file(s);
  EXPECT_FALSE(c.with_effects);
  ASSERT_TRUE(c.model_test);
  // The static model leaves the twist out: the readings disagree with it.
  EXPECT_FALSE(c.model_test->passed);
  EXPECT_NE(model_test_line(*c.model_test, true).find("the stated 1-sigma understates the error"), std::string::npos);
  EXPECT_NE(model_test_yaml(*c.model_test, 2).find("  model_test_chi2: "), std::string::npos);
}

// The small run's readings (realistic twin: its drives twist by 1e-4 rad/N m
// of their torque) calibrated with the compliance left out of the motion
// model: the model test fails and names the transmission's compliance first
// of the effects the model leaves out; with every effect of the procedure
// in it, the compliance is not among those named; with the encoders' latch
// skew left out instead, the skew is named.
TEST(CalibrationProcedure, AFailedModelTestNamesTheEffectLeftOut) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  FileProcedure p = gpm2002_file_procedure(s);
  const CalibrationOutcome full = calibrate_samples(sample_series(s), p.inputs, p.options);
  p.inputs.motion.compliance = p.inputs.motion.friction = p.inputs.motion.torque_before = false;
  p.inputs.drive_candidates = {};
  const CalibrationOutcome stiff = calibrate_samples(sample_series(s), p.inputs, p.options);
  ASSERT_TRUE(stiff.model_test && full.model_test);
  ASSERT_FALSE(stiff.model_test->passed);
  const std::string& d = stiff.model_test->diagnosis;
  EXPECT_NE(d.find("the residuals call for transmission compliance (chi2 down by"), std::string::npos) << d;
  EXPECT_GT(stiff.model_test->chi2 - stiff.model_test->dof, 3.0 * (full.model_test->chi2 - full.model_test->dof));
  if (!full.model_test->passed) {
    EXPECT_EQ(full.model_test->diagnosis.find("transmission compliance ("), std::string::npos) << full.model_test->diagnosis;
  }
  // The latch skew (50 and 100 us on the twin) left out instead.
  FileProcedure q = gpm2002_file_procedure(s);
  q.inputs.motion.skew = false;
  const CalibrationOutcome unskewed = calibrate_samples(sample_series(s), q.inputs, q.options);
  ASSERT_TRUE(unskewed.model_test);
  ASSERT_FALSE(unskewed.model_test->passed);
  EXPECT_NE(unskewed.model_test->diagnosis.find("the residuals call for the encoders' latch skew (chi2 down by"),
            std::string::npos)
      << unskewed.model_test->diagnosis;
}

// The model test's two adjustments each leave a note with the result: the
// share of chi2 the error once per joint revolution carried within its prior
// explains (here carried: calibration.estimate without encoder_error), taken
// off; and the doubt where a joint may rest, expected. Neither without its value.
TEST(CalibrationProcedure, TheModelTestsNotesSayWhatItTakesOffAndWhatItExpects) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  FileProcedure p = gpm2002_file_procedure(s);
  p.inputs.estimate_encoder_error = false;
  const CalibrationOutcome c = calibrate_samples(sample_series(s), p.inputs, p.options);
  ASSERT_TRUE(c.model_test);
  ASSERT_GT(c.model_test->carried_chi2, 0.0);
  ASSERT_GT(c.model_test->doubt_chi2, 0.0);
  const auto has = [&](const std::string& start) {
    return std::ranges::any_of(c.result.notes, [&](const std::string& n) { return n.starts_with(start); });
  };
  EXPECT_TRUE(has(fmt::format("the model test weighs chi2 less {:.3g} of it", c.model_test->carried_chi2)));
  EXPECT_TRUE(has(fmt::format("the model test expects {:.3g} more of chi2", c.model_test->doubt_chi2)));
  const CalibrationOutcome estimated = calibrate_file(s);  // the error estimated: nothing carried
  ASSERT_TRUE(estimated.model_test);
  EXPECT_EQ(estimated.model_test->carried_chi2, 0.0);
  EXPECT_FALSE(std::ranges::any_of(estimated.result.notes,
                                   [](const std::string& n) { return n.starts_with("the model test weighs chi2 less"); }));
}

// The small run's passive links cross their play (5 um on the realistic
// twin) wherever their force changes sign: with calibration.crossing_s the
// samples of the 20 ms after each change are left out and the fits made
// again, so fewer samples are used and their chi-square per degree of
// freedom falls (the crossings were misfit); without it (0) no note and
// every such sample kept; where the model misses the readings by more than
// the gates allow, with the crossings and without them, they are kept.
TEST(CalibrationProcedure, ThePlaysCrossingsAreLeftOutWhereTheModelFits) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  FileProcedure p = gpm2002_file_procedure(s);
  ASSERT_EQ(p.inputs.crossing_s, 0.02);  // the default of calibration.crossing_s
  const CalibrationOutcome guarded = calibrate_samples(sample_series(s), p.inputs, p.options);
  p.inputs.crossing_s = 0.0;
  const CalibrationOutcome all = calibrate_samples(sample_series(s), p.inputs, p.options);
  const auto note = [](const CalibrationOutcome& c, const std::string& what) {
    return std::any_of(c.result.notes.begin(), c.result.notes.end(),
                       [&](const std::string& n) { return n.find(what) != std::string::npos; });
  };
  ASSERT_TRUE(guarded.model_test && all.model_test);
  EXPECT_TRUE(note(guarded, "may be crossing its play left out (0.02 s after its force changed sign)"));
  EXPECT_FALSE(note(all, "crossing its play"));
  EXPECT_LT(guarded.used.size(), all.used.size());
  EXPECT_LT(guarded.model_test->chi2 / guarded.model_test->dof, all.model_test->chi2 / all.model_test->dof);
  // A reading 1-sigma stated 5x too small: chi2/dof 25x, beyond both gates
  // with the crossings and without them; they are kept.
  p.inputs.crossing_s = 0.02;
  p.options.sigma_from_step = false;
  p.options.sigma_rad = guarded.sigma_rad / 5.0;
  const CalibrationOutcome misfit = calibrate_samples(sample_series(s), p.inputs, p.options);
  EXPECT_TRUE(note(misfit, "the samples of a passive link crossing its play kept: chi2/dof"));
  EXPECT_FALSE(note(misfit, "crossing its play left out"));
  // Windows of 0.2 s cover most samples whose signs are certain (of 8655,
  // 3189 would be left): the geometry's 1-sigma without them would grow
  // beyond 1.5x; they are kept.
  p.options = gpm2002_file_procedure(s).options;
  p.inputs.crossing_s = 0.2;
  const CalibrationOutcome wide = calibrate_samples(sample_series(s), p.inputs, p.options);
  EXPECT_TRUE(note(wide, "the samples of a passive link crossing its play kept: without them"));
  EXPECT_TRUE(note(wide, "x (above 1.5x), more than the fit gains"));
  EXPECT_EQ(wide.used.size(), all.used.size());
}

TEST(CalibrationProcedure, MotionModelWithoutTimesOrTorquesRefused) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  const FileProcedure p = gpm2002_file_procedure(s);
  const CalibrationInputs& in = p.inputs;
  const ProcedureOptions& po = p.options;
  SampleSeries no_t = sample_series(s), no_tau = sample_series(s), short_t = sample_series(s);
  no_t.t_s.clear();
  no_tau.tau.clear();
  short_t.t_s.pop_back();
  EXPECT_THROW(calibrate_samples(no_t, in, po), InputError);
  EXPECT_THROW(calibrate_samples(no_tau, in, po), InputError);
  EXPECT_THROW(calibrate_samples(short_t, in, po), InputError);
}

// The fixture's readings as drives polled in turn would give them: joints 2
// and 3 read lag_2 and lag_3 after joint 1 (linear between the samples, a
// fraction of the sample interval). With the read times the calibration
// carries them back (the skew estimates as before, the geometry within its
// 1-sigma: interpolated readings no longer show the encoders' step, so their
// noise differs); without, the skew s_i takes up -lag_i.
TEST(CalibrationProcedure, ReadingsPolledInTurnAreCarriedToJointOnesInstant) {
  const RunOutcome& o = small_run();
  const Samples s = parse_samples_csv(sim::samples_csv(o.sim.samples), "samples.csv");
  ASSERT_TRUE(taken_on_the_fly(s));
  const double dt = s.t[1] - s.t[0];
  const Eigen::Vector3d lag(0.0, 0.3 * dt, 0.6 * dt);
  Samples polled = s;
  for (std::size_t j = 0; j + 1 < s.size(); ++j) {
    for (int i = 1; i < 3; ++i) {
      const double f = lag[i] / dt;
      polled.theta_m[j][i] = (1 - f) * s.theta_m[j][i] + f * s.theta_m[j + 1][i];
    }
    polled.t_read.push_back(Eigen::Vector3d::Constant(s.t[j]) + lag);
  }
  // The last sample has no reading after it.
  polled.theta_m.pop_back(), polled.id.pop_back(), polled.t.pop_back(), polled.tau.pop_back();
  polled.tau_last.pop_back(), polled.tau_between.pop_back();
  if (polled.has_xy) polled.xy.pop_back();
  // The friction as the data sheet states it in all three: the force balance
  // of readings interpolated between samples comes out a little different
  // (its residuals no longer show the encoders' step), which on this robot
  // tips the choice of the friction's speed and of a drive-train harmonic,
  // and those move the skew; this test is about the read times.
  // Nor do they tell that the encoders turn with the joints: each fit
  // carries the reducer's error once per joint revolution (the default
  // estimates it where a fit's chi2/dof and misfit allow, which the
  // interpolation moves too). And the samples of the passive links'
  // crossings are kept: whether they are left out is decided by the fit's
  // chi2/dof likewise.
  const CalibrationOutcome base = calibrate_file(s, false, false, std::nullopt, false, 0.0, false),
                           carried = calibrate_file(polled, false, false, std::nullopt, false, 0.0, false);
  Samples unlabelled = polled;
  unlabelled.t_read.clear();
  const CalibrationOutcome skewed = calibrate_file(unlabelled, false, false, std::nullopt, false, 0.0, false);
  ASSERT_TRUE(base.with_effects && carried.with_effects && skewed.with_effects);
  // The readings interpolated between samples carry the error of a straight
  // line through the path's curvature: the skews carried back land within
  // 0.12 lag_3 (measured 30 and 58 us of 600 us through the twin backend).
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(carried.fit.nu[k], base.fit.nu[k], 0.12 * lag[2]) << "s" << k + 2;
    EXPECT_NEAR(skewed.fit.nu[k], base.fit.nu[k] - lag[k + 1], 0.2 * lag[k + 1]) << "s" << k + 2;
  }
  for (int i = 0; i < kNumParams; ++i) {
    const double sigma = base.result.sigma[static_cast<size_t>(i)];
    if (std::isnan(sigma)) continue;
    EXPECT_NEAR(carried.result.geometry[i], base.result.geometry[i], sigma) << param_name(i);
  }
}

}  // namespace
}  // namespace gpm::scenario
