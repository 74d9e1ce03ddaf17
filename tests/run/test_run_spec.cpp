// Tests of run/run_spec.cpp: defaults, and schema errors that name the
// key path (gpm run exits 2 with that one line).
#include "run/run_spec.hpp"
#include "models/data_dir.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"

namespace gpm::scenario {
namespace {

const std::string kBase = (gpm::models_dir() + "/..");
const std::string kHead =
    "robot: models/gpm2002.yaml\n"
    "sampling: {pattern: disc, radius: 50, count: 12}\n";

std::string error_of(const std::string& text) {
  try {
    parse_run_spec(text, "s.yaml", kBase);
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos);
    return m;
  }
  return "";
}

TEST(RunSpec, Defaults) {
  const RunSpec s = parse_run_spec(kHead, "s.yaml", kBase);
  EXPECT_EQ(s.calibration.cost, calib::Cost::kML);
  EXPECT_EQ(s.calibration.method, calib::Method::kLM);
  EXPECT_EQ(s.calibration.fixed, ~default_free_mask());
  ASSERT_TRUE(s.compensation);
  EXPECT_EQ(s.compensation->poses.size(), 12u);
  for (const auto& p : s.compensation->poses) EXPECT_LE((p - s.sim.controller.home).norm(), 80.0 + 1e-9);
  EXPECT_TRUE(s.outputs.report);
  EXPECT_FALSE(s.expect.crb_ratio_max);
}

TEST(RunSpec, PositioningExpectationIsAPositiveNumberInMicrons) {
  EXPECT_EQ(parse_run_spec(kHead + "expect: {positioning_rms_um_max: 4}\n", "s.yaml", kBase).expect.positioning_rms_um_max,
            4.0);
  EXPECT_NE(error_of(kHead + "expect: {positioning_rms_um_max: 0}\n").find("expect.positioning_rms_um_max"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "expect: {positioning_um_max: 4}\n").find("did you mean positioning_rms_um_max?"),
            std::string::npos);
}

TEST(RunSpec, NoteExpectationIsATextOrAListOfTexts) {
  EXPECT_EQ(parse_run_spec(kHead + "expect: {note_contains: a b}\n", "s.yaml", kBase).expect.note_contains,
            (std::vector<std::string>{"a b"}));
  EXPECT_EQ(parse_run_spec(kHead + "expect: {note_contains: [a, 'b: c']}\n", "s.yaml", kBase).expect.note_contains,
            (std::vector<std::string>{"a", "b: c"}));
  EXPECT_TRUE(parse_run_spec(kHead, "s.yaml", kBase).expect.note_contains.empty());
  EXPECT_EQ(error_of(kHead + "expect: {note_contains: []}\n"),
            "s.yaml:3: expect.note_contains: expected a text or a list of texts, each a note must contain");
  EXPECT_NE(error_of(kHead + "expect: {note_contains: [a, [b]]}\n").find("expect.note_contains[1]"), std::string::npos);
}

TEST(RunSpec, FixListUnknownNameNamesKeyPathAndSuggestion) {
  EXPECT_EQ(error_of(kHead + "calibration:\n  fix: [xa1, ya1, xb1]\n"),
            "s.yaml:4: calibration.fix[2]: unknown parameter 'xb1' (did you mean xa1?)");
}

TEST(RunSpec, OtherSchemaErrors) {
  EXPECT_NE(error_of(kHead + "calibration: {cost: j4}\n").find("calibration.cost: unknown cost 'j4' (valid: j1, j2, j3, ml)"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {method: cmaes}\n").find("calibration.method: unknown method"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "expect: {error: {la9: 1}}\n").find("expect.error.la9: unknown tolerance"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "expect: {crb_ratio_max: -1}\n").find("expect.crb_ratio_max"), std::string::npos);
  EXPECT_NE(error_of(kHead + "expect: {improvment_min: 3}\n").find("did you mean improvement_min?"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "compensation: {path: {shape: spiral}}\n").find("compensation.path.shape: 'spiral'"),
            std::string::npos);
  EXPECT_NE(error_of("robot: models/gpm2002.yaml\npath: {shape: circle, radius: 20, period_s: 2}\n").find("needs a sampling plan"),
            std::string::npos);
  EXPECT_EQ(error_of(kHead + "calibration: {loss: tukey}\n").rfind("s.yaml:3: calibration.loss: unknown loss 'tukey' (valid: ", 0),
            0u);
  EXPECT_NE(error_of(kHead + "calibration: {loss: 'huber:-2'}\n").find("calibration.loss: 'huber:-2' has no valid scale"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {estimate: [drag]}\n").find("(valid: compliance, skew, friction, clearance, encoder_error, joint_error)"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {tension_min_N: 0}\n").find("calibration.tension_min_N"), std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {tension_min_N: 1000}\n").find("calibration.tension_min_N: 1000 N leaves no sample"),
            std::string::npos);
}

TEST(RunSpec, CalibrationNumbersHaveDocumentedBoundsAndListsNoRepeats) {
  // Issue 36.1 and 36.8: checked when the scenario is read, before any work.
  EXPECT_EQ(error_of(kHead + "calibration: {method: de, budget: 1e12}\n"),
            "s.yaml:3: calibration.budget: must be a whole number from 1 to 1e10 evaluations, got 1e12");
  EXPECT_EQ(error_of(kHead + "calibration: {budget: 2000000}\n"),
            "s.yaml:3: calibration.budget: must be a whole number from 1 to 1e6 iterations, got 2000000");
  EXPECT_EQ(error_of(kHead + "calibration: {sigma: 1e-300, loss: cauchy}\n"),
            "s.yaml:3: calibration.sigma: must be a number from 1e-12 to 1 rad, got 1e-300");
  EXPECT_NE(error_of(kHead + "calibration: {loss: 'cauchy:1e-200'}\n")
                .find("calibration.loss: scale of 'cauchy:1e-200': must be a number from 1e-12 to 1e6"),
            std::string::npos);
  EXPECT_EQ(error_of(kHead + "calibration: {seed: -1}\n"),
            "s.yaml:3: calibration.seed: must be a whole number from 0 to 9007199254740992, got -1");
  // Issue 36.12: a list names each item once.
  EXPECT_EQ(error_of(kHead + "calibration:\n  fix: [xa1, ya1, xa2, ya2, xa1]\n"),
            "s.yaml:4: calibration.fix[4]: 'xa1' is listed twice; list each parameter once");
  EXPECT_EQ(error_of(kHead + "calibration:\n  estimate: [skew, compliance, skew]\n"),
            "s.yaml:4: calibration.estimate[2]: 'skew' is listed twice (also calibration.estimate[0]); list each "
            "effect once");
  EXPECT_EQ(error_of(kHead + "calibration: {method: de, budget: 1e10}\n"), "");
}

TEST(RunSpec, LossAndEstimatedEffects) {
  const RunSpec s = parse_run_spec(kHead + "calibration: {loss: 'cauchy:2e-4', estimate: [compliance, friction]}\n",
                                   "s.yaml", kBase);
  EXPECT_EQ(s.calibration.loss.kind, calib::LossKind::kCauchy);
  EXPECT_EQ(s.calibration.loss.scale, 2e-4);
  EXPECT_EQ(s.calibration.estimate_compliance, true);
  EXPECT_EQ(s.calibration.estimate_skew, false);
  EXPECT_EQ(s.calibration.estimate_friction, true);
  EXPECT_EQ(s.calibration.estimate_clearance, false);  // a list names every estimated effect
  EXPECT_EQ(s.calibration.estimate_encoder_error, false);
  EXPECT_FALSE(parse_run_spec(kHead, "s.yaml", kBase).calibration.estimate_encoder_error);  // unset: on the fly
  EXPECT_EQ(parse_run_spec(kHead + "calibration: {estimate: [encoder_error]}\n", "s.yaml", kBase)
                .calibration.estimate_encoder_error,
            true);
  EXPECT_EQ(s.calibration.estimate_joint_error, false);
  EXPECT_FALSE(parse_run_spec(kHead, "s.yaml", kBase).calibration.estimate_joint_error);  // unset: on the fly
  const RunSpec j = parse_run_spec(kHead + "calibration: {estimate: [joint_error]}\n", "s.yaml", kBase);
  EXPECT_EQ(j.calibration.estimate_joint_error, true);
  EXPECT_EQ(j.calibration.estimate_encoder_error, false);
  EXPECT_FALSE(parse_run_spec(kHead, "s.yaml", kBase).calibration.loss.active());
  EXPECT_FALSE(parse_run_spec(kHead, "s.yaml", kBase).calibration.estimate_clearance);  // unset: the runner decides
  const RunSpec c = parse_run_spec(kHead + "calibration: {estimate: [clearance], tension_min_N: 0.5}\n", "s.yaml", kBase);
  EXPECT_EQ(c.calibration.estimate_clearance, true);
  EXPECT_EQ(c.calibration.estimate_compliance, false);
  EXPECT_EQ(c.calibration.tension_min_N, 0.5);
  // The crossing of a passive link's play: 20 ms unless stated, 0 none, at most 1 s.
  EXPECT_EQ(parse_run_spec(kHead, "s.yaml", kBase).calibration.crossing_s, 0.02);
  EXPECT_EQ(parse_run_spec(kHead + "calibration: {crossing_s: 0}\n", "s.yaml", kBase).calibration.crossing_s, 0.0);
  EXPECT_EQ(parse_run_spec(kHead + "calibration: {crossing_s: 0.05}\n", "s.yaml", kBase).calibration.crossing_s, 0.05);
  const std::string e = error_of(kHead + "calibration: {crossing_s: 2}\n");
  EXPECT_EQ(e.rfind("s.yaml:3: calibration.crossing_s: ", 0), 0u) << e;
  EXPECT_NE(e.find("1"), std::string::npos) << e;
}

// calibration.drive_friction: what the procedure assumes, independent of the
// twin's effects; default the robot's data sheet (models/gpm2002.yaml: 0.3 N
// m, 0.15 N m s/rad), its scale fitted; a number or one per joint; a key
// left out keeps its default.
TEST(RunSpec, DriveFrictionStatedByTheCalibration) {
  const RunSpec d = parse_run_spec(kHead, "s.yaml", kBase);
  EXPECT_EQ(d.calibration.drive_friction.coulomb_Nm, (std::array<double, 3>{0.3, 0.3, 0.3}));
  EXPECT_EQ(d.calibration.drive_friction.viscous_Nm_s, (std::array<double, 3>{0.15, 0.15, 0.15}));
  // The twin's effects are the simulated machine: they do not change what the calibration assumes.
  const RunSpec ideal = parse_run_spec(kHead + "effects: {coulomb_friction_Nm: 2, viscous_friction_Nm_s: 1}\n",
                                       "s.yaml", kBase);
  EXPECT_EQ(ideal.calibration.drive_friction.coulomb_Nm, d.calibration.drive_friction.coulomb_Nm);
  EXPECT_EQ(ideal.calibration.drive_friction.viscous_Nm_s, d.calibration.drive_friction.viscous_Nm_s);
  const RunSpec s = parse_run_spec(kHead + "calibration: {drive_friction: {coulomb_Nm: [0.1, 0.2, 0.4]}}\n", "s.yaml", kBase);
  EXPECT_EQ(s.calibration.drive_friction.coulomb_Nm, (std::array<double, 3>{0.1, 0.2, 0.4}));
  EXPECT_EQ(s.calibration.drive_friction.viscous_Nm_s, d.calibration.drive_friction.viscous_Nm_s);
  const RunSpec v = parse_run_spec(kHead + "calibration: {drive_friction: {viscous_Nm_s: 0, coulomb_Nm: 0.6}}\n", "s.yaml", kBase);
  EXPECT_EQ(v.calibration.drive_friction.viscous_Nm_s, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(v.calibration.drive_friction.coulomb_Nm, (std::array<double, 3>{0.6, 0.6, 0.6}));
  EXPECT_TRUE(d.calibration.drive_friction.fit_scale);  // default: the scale from the model test
  EXPECT_TRUE(v.calibration.drive_friction.fit_scale);
  EXPECT_FALSE(parse_run_spec(kHead + "calibration: {drive_friction: {fit_scale: false}}\n", "s.yaml", kBase)
                   .calibration.drive_friction.fit_scale);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {fit_scale: maybe}}\n").find("calibration.drive_friction.fit_scale"),
            std::string::npos);
  EXPECT_TRUE(d.calibration.drive_friction.from_balance);  // default: each drive's friction from the force balance
  EXPECT_FALSE(parse_run_spec(kHead + "calibration: {drive_friction: {from_balance: false}}\n", "s.yaml", kBase)
                   .calibration.drive_friction.from_balance);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {from_balance: 2}}\n").find("calibration.drive_friction.from_balance"),
            std::string::npos);
  EXPECT_TRUE(d.calibration.drive_friction.weigh_rest);    // default: a sample whose rotor may rest weighs less
  EXPECT_FALSE(d.calibration.drive_friction.weigh_signs);  // default: the force signs used weigh 1
  const DriveFriction swapped = parse_run_spec(kHead + "calibration: {drive_friction: {weigh_rest: false, weigh_signs: true}}\n",
                                               "s.yaml", kBase).calibration.drive_friction;
  EXPECT_FALSE(swapped.weigh_rest);
  EXPECT_TRUE(swapped.weigh_signs);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {weigh_rest: 2}}\n").find("calibration.drive_friction.weigh_rest"),
            std::string::npos);
  // The friction speeds tried: those the latch skew's column cannot take up (default), or every one (1).
  EXPECT_EQ(d.calibration.drive_friction.max_skew_correlation, calib::kMaxSkewCorrelation);
  EXPECT_EQ(parse_run_spec(kHead + "calibration: {drive_friction: {max_skew_correlation: 1}}\n", "s.yaml", kBase)
                .calibration.drive_friction.max_skew_correlation,
            1.0);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {max_skew_correlation: 1.5}}\n")
                .find("calibration.drive_friction.max_skew_correlation: must be a number from 0 to 1 (a correlation), got 1.5"),
            std::string::npos);
  EXPECT_EQ(error_of(kHead + "calibration: {drive_friction: {coulomb_Nm: -0.3}}\n"),
            "s.yaml:3: calibration.drive_friction.coulomb_Nm: -0.3 is out of range (valid: 0 to 20 N m)");
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {viscous_Nm_s: [0.1, 0.2]}}\n")
                .find("calibration.drive_friction.viscous_Nm_s: expected a number or a list of three"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {viscous_Nm_s: [0.1, 0.2, 500]}}\n")
                .find("calibration.drive_friction.viscous_Nm_s[2]: 500 is out of range (valid: 0 to 100 N m s/rad)"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {coulomb: 0.3}}\n").find("calibration.drive_friction"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: 0.3}\n").find("calibration.drive_friction: expected {coulomb_Nm"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {drive_friction: {coulomb_Nm: fast}}\n").find("calibration.drive_friction.coulomb_Nm"),
            std::string::npos);
}

// The reading model gpm run appends to calibration.yaml reads back to the
// last bit through the scenario's own parser (awkward numbers: the shortest
// exact form is written), and is the same section a scenario states.
TEST(RunSpec, MonitorReadingModelYamlRoundTripsBitExact) {
  MonitorReadingModel m = data_sheet_reading_model(DataSheet{});
  m.reading.clearance_mm = {0.005644814301912167, 1.0 / 3.0 * 1e-2, 0.0};
  m.reading.skew_s = {0.0, 5.556675527672076e-05, -8.164314423058782e-05};
  m.reading.compliance_rad_per_Nm = {0.0001, 0.000103386928736235, 0.0};
  m.reading.load.viscous_Nm_s = {0.15000000000000002, 0.1, 0.2};
  m.thermal_time_constant_s = 612.5;
  m.reading.backlash_rad = {0.0, 2.9088820866572158e-4, 1e-5};
  m.reading.harmonic[1] = {1.0 / 3.0 * 1e-5, 0.0, -2e-6, 0.0, 7e-7, 0.0};
  m.reading.harmonic[calib::kCoggingHarmonic] = {0.0, 1.1e-5, 0.0, -3e-6, 0.0, 0.0};  // the data sheet's 24 periods
  MonitorReadingModel at_home = m;  // the reducer's error referenced to 0 at these readings
  at_home.reading.reducer_home_rad = {1.0968648692113863, 3.0941265050681466, 4.825986318579954};
  for (const MonitorReadingModel& want : {m, at_home, ideal_reading_model(), data_sheet_reading_model(DataSheet{})}) {
    const std::string text = monitor_reading_model_yaml(want);
    const MonitorReadingModel got = parse_monitor_reading_model(load_yaml_string(text, "r.yaml")["monitor"], "r.yaml", DataSheet{});
    EXPECT_EQ(got.reading.cyclic_rad, want.reading.cyclic_rad) << text;
    EXPECT_EQ(got.reading.clearance_mm, want.reading.clearance_mm) << text;
    EXPECT_EQ(got.reading.load.coulomb_Nm, want.reading.load.coulomb_Nm) << text;
    EXPECT_EQ(got.reading.load.viscous_Nm_s, want.reading.load.viscous_Nm_s) << text;
    EXPECT_EQ(got.reading.skew_s, want.reading.skew_s) << text;
    EXPECT_EQ(got.reading.compliance_rad_per_Nm, want.reading.compliance_rad_per_Nm) << text;
    EXPECT_EQ(got.thermal_time_constant_s, want.thermal_time_constant_s) << text;
    EXPECT_EQ(got.reading.backlash_rad, want.reading.backlash_rad) << text;
    EXPECT_EQ(got.reading.harmonic, want.reading.harmonic) << text;
    for (std::size_t i = 0; i < 3; ++i)  // NaN (not referenced) where not written
      EXPECT_TRUE(got.reading.reducer_home_rad[i] == want.reading.reducer_home_rad[i] ||
                  (std::isnan(got.reading.reducer_home_rad[i]) && std::isnan(want.reading.reducer_home_rad[i])))
          << text;
    EXPECT_EQ(text.find("reducer_home_rad") != std::string::npos, std::isfinite(want.reading.reducer_home_rad[0]));
    // The same text is a scenario's monitor: section.
    EXPECT_EQ(parse_run_spec(kHead + text, "s.yaml", kBase).monitor.reading.skew_s, want.reading.skew_s);
  }
}

// monitor: what the drift monitor assumes of the readings. Default the
// robot's data sheet (models/gpm2002.yaml: encoder accuracy 2e-5 rad, latch
// skew 50 us per drive, stiffness 1e4 N m/rad, pin clearance 5 um, warm-up
// 600 s, the drives' friction calibration.drive_friction defaults to),
// whatever the twin's effects; `ideal` models none; keys override the preset.
TEST(RunSpec, MonitorReadingModelIsStatedNotTakenFromTheTwin) {
  const RunSpec d = parse_run_spec(kHead, "s.yaml", kBase);
  using Three = std::array<double, 3>;
  EXPECT_EQ(d.monitor.reading.cyclic_rad, (Three{2e-5, 2e-5, 2e-5}));
  EXPECT_EQ(d.monitor.reading.skew_s, (Three{0.0, 50e-6, 100e-6}));
  EXPECT_EQ(d.monitor.reading.compliance_rad_per_Nm, (Three{1e-4, 1e-4, 1e-4}));
  EXPECT_EQ(d.monitor.reading.load.coulomb_Nm, d.calibration.drive_friction.coulomb_Nm);
  EXPECT_EQ(d.monitor.reading.load.viscous_Nm_s, d.calibration.drive_friction.viscous_Nm_s);
  EXPECT_EQ(d.monitor.thermal_time_constant_s, 600.0);
  EXPECT_EQ(d.monitor.reading.clearance_mm, (Three{0.01, 0.01, 0.01}));  // the play of both pins
  // The twin's effects are the simulated machine: they do not change what the monitor assumes.
  const RunSpec fx = parse_run_spec(kHead + "physics: {timestep_s: 0.00025}\nservo: {rate_hz: 4000}\n"
                                            "effects: {preset: realistic, passive_clearance_mm: 0.02, encoder_cyclic_rad: 0, "
                                            "coulomb_friction_Nm: 2, encoder_skew_s: 0.001, thermal: {time_constant_s: 30}}\n",
                                    "s.yaml", kBase);
  EXPECT_EQ(fx.monitor.reading.clearance_mm, d.monitor.reading.clearance_mm);
  EXPECT_EQ(fx.monitor.reading.cyclic_rad, d.monitor.reading.cyclic_rad);
  EXPECT_EQ(fx.monitor.reading.load.coulomb_Nm, d.monitor.reading.load.coulomb_Nm);
  EXPECT_EQ(fx.monitor.reading.skew_s, d.monitor.reading.skew_s);
  EXPECT_EQ(fx.monitor.thermal_time_constant_s, d.monitor.thermal_time_constant_s);
  EXPECT_EQ(parse_run_spec(kHead + "monitor: data_sheet\n", "s.yaml", kBase).monitor.reading.skew_s, d.monitor.reading.skew_s);

  // ideal: no reading error; the drift time constant is the monitor's own default.
  const MonitorReadingModel ideal = parse_run_spec(kHead + "monitor: ideal\n", "s.yaml", kBase).monitor;
  const std::array<double, 3> zero{};
  EXPECT_EQ(ideal.reading.cyclic_rad, zero);
  EXPECT_EQ(ideal.reading.clearance_mm, zero);
  EXPECT_EQ(ideal.reading.skew_s, zero);
  EXPECT_EQ(ideal.reading.compliance_rad_per_Nm, zero);
  EXPECT_EQ(ideal.reading.load.coulomb_Nm, zero);
  EXPECT_EQ(ideal.reading.load.viscous_Nm_s, zero);
  EXPECT_EQ(ideal.thermal_time_constant_s, calib::monitor::MonitorSettings{}.thermal_tau_s);

  // Keys override the preset (default data_sheet); a skew number is encoders 2 and 3 (1 is the reference).
  const MonitorReadingModel m =
      parse_run_spec(kHead + "monitor: {preset: ideal, clearance_mm: [0.001, 0.002, 0.003], skew_s: 2.0e-5, "
                             "drive_friction: {coulomb_Nm: 0.5}, compliance_rad_per_Nm: 2.0e-4, "
                             "encoder_cyclic_rad: 1.0e-5, thermal_time_constant_s: 900}\n",
                     "s.yaml", kBase)
          .monitor;
  EXPECT_EQ(m.reading.clearance_mm, (std::array<double, 3>{0.002, 0.004, 0.006}));
  EXPECT_EQ(m.reading.skew_s, (std::array<double, 3>{0.0, 2e-5, 2e-5}));
  EXPECT_EQ(m.reading.load.coulomb_Nm, (std::array<double, 3>{0.5, 0.5, 0.5}));
  EXPECT_EQ(m.reading.load.viscous_Nm_s, zero);  // kept from the preset
  EXPECT_EQ(m.reading.compliance_rad_per_Nm, (std::array<double, 3>{2e-4, 2e-4, 2e-4}));
  EXPECT_EQ(m.reading.cyclic_rad, (std::array<double, 3>{1e-5, 1e-5, 1e-5}));
  EXPECT_EQ(m.thermal_time_constant_s, 900.0);
  const MonitorReadingModel k = parse_run_spec(kHead + "monitor: {clearance_mm: 0}\n", "s.yaml", kBase).monitor;
  EXPECT_EQ(k.reading.clearance_mm, zero);
  EXPECT_EQ(k.reading.skew_s, d.monitor.reading.skew_s);  // the rest: data_sheet

  // Bad values: one line naming the key and what would be valid.
  EXPECT_EQ(error_of(kHead + "monitor: datasheet\n"),
            "s.yaml:3: monitor: 'datasheet' is not a reading model preset (valid: ideal, data_sheet)");
  EXPECT_EQ(error_of(kHead + "monitor: {preset: real}\n"),
            "s.yaml:3: monitor.preset: 'real' is not a reading model preset (valid: ideal, data_sheet)");
  EXPECT_EQ(error_of(kHead + "monitor: {clearance_mm: -0.005}\n"),
            "s.yaml:3: monitor.clearance_mm: -0.005 is out of range (valid: 0 to 1 mm)");
  EXPECT_EQ(error_of(kHead + "monitor: {encoder_cyclic_rad: [0, 0, 0.02]}\n"),
            "s.yaml:3: monitor.encoder_cyclic_rad[2]: 0.02 is out of range (valid: 0 to 0.01 rad)");
  EXPECT_EQ(error_of(kHead + "monitor: {skew_s: [0, 0.02, 0]}\n"),
            "s.yaml:3: monitor.skew_s[1]: 0.02 s is out of range (valid: -0.01 to 0.01 s)");
  EXPECT_NE(error_of(kHead + "monitor: {skew_s: [0, 0.001]}\n").find("monitor.skew_s: expected a number (encoders 2 and 3) or a list of three"),
            std::string::npos);
  EXPECT_EQ(error_of(kHead + "monitor: {harmonic_rad: [[0, 0, 0, 0, 0, 0]]}\n"),
            "s.yaml:3: monitor.harmonic_rad: expected four lists of six numbers (a1 a2 a3 b1 b2 b3 in rad of each "
            "order: joint, motor, twice motor revolution, cogging; the last may be left out), each within +-0.01 rad");
  // Three lists (a file written before the cogging) are read, the cogging 0.
  const RunSpec three = parse_run_spec(kHead + "monitor: {harmonic_rad: [[0, 0, 0, 0, 0, 0], [1e-5, 0, 0, 0, 0, 0], "
                                                "[0, 0, 0, 0, 0, 0]]}\n", "s.yaml", kBase);
  EXPECT_EQ(three.monitor.reading.harmonic[1][0], 1e-5);
  EXPECT_EQ(three.monitor.reading.harmonic[calib::kCoggingHarmonic], (std::array<double, 6>{}));
  EXPECT_EQ(three.monitor.reading.cogging_periods, 24.0);  // the data sheet's
  EXPECT_EQ(error_of(kHead + "monitor: {reducer_home_rad: [1, 2, 7]}\n"),
            "s.yaml:3: monitor.reducer_home_rad[2]: 7 is out of range (valid: 0 to 6.283185307179586 rad)");
  EXPECT_EQ(error_of(kHead + "monitor: {backlash_rad: 0.5}\n"),
            "s.yaml:3: monitor.backlash_rad: 0.5 is out of range (valid: 0 to 0.01 rad)");
  EXPECT_EQ(error_of(kHead + "monitor: {compliance_rad_per_Nm: 2}\n"),
            "s.yaml:3: monitor.compliance_rad_per_Nm: 2 is out of range (valid: 0 to 1 rad/N m)");
  EXPECT_EQ(error_of(kHead + "monitor: {thermal_time_constant_s: 0.5}\n"),
            "s.yaml:3: monitor.thermal_time_constant_s: 0.5 s is out of range (valid: 1 to 1e6 s)");
  EXPECT_EQ(error_of(kHead + "monitor: {drive_friction: {coulomb_Nm: 30}}\n"),
            "s.yaml:3: monitor.drive_friction.coulomb_Nm: 30 is out of range (valid: 0 to 20 N m)");
  // The monitor cannot fit the friction's scale: only the calibration can.
  EXPECT_NE(error_of(kHead + "monitor: {drive_friction: {fit_scale: true}}\n").find("monitor.drive_friction"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "monitor: {clearance: 0.005}\n").find("monitor"), std::string::npos);
  EXPECT_NE(error_of(kHead + "monitor: [ideal]\n").find("monitor: expected a preset (ideal, data_sheet) or a map"),
            std::string::npos);
}

TEST(RunSpec, ReferenceReadingsTakenWhereTheRobotStands) {
  const RunSpec s = parse_run_spec(kHead + "calibration: {start: reference, reference_at: [210, 245]}\n", "s.yaml", kBase);
  EXPECT_TRUE(s.calibration.start_reference);
  ASSERT_TRUE(s.calibration.reference_at);
  EXPECT_EQ(*s.calibration.reference_at, Eigen::Vector2d(210, 245));
  EXPECT_FALSE(parse_run_spec(kHead, "s.yaml", kBase).calibration.reference_at);  // default: at home
  EXPECT_NE(error_of(kHead + "calibration: {reference_at: [210, 245]}\n").find("needs start: reference"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + "calibration: {start: reference, reference_at: [210]}\n").find("expected [x, y] in mm"),
            std::string::npos);
}

}  // namespace
}  // namespace gpm::scenario
