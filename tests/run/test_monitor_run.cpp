// Tests of run/monitor_run.cpp: gpm run's monitoring hook (the calibrated
// model monitors `operation:` after the calibration), the monitor's reading
// model taken from the scenario's effects, and monitoring through hw/ (the
// twin backend, and the drive emulator over Modbus as the hw tests run it).
#include "run/monitor_run.hpp"

#include <gtest/gtest.h>

#include "hw/backends/drive_emulator.hpp"
#include "hw/clock.hpp"
#include "hw/hardware_config.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "tests/hw/hw_test_util.hpp"
#include "run/runner.hpp"
#include "run/summary_json.hpp"
#include "sim/scenario.hpp"

namespace gpm::scenario {
namespace {

const std::string kBase = gpm::scenarios_dir();

std::string run_yaml(const std::string& operation) {
  return "robot: robots/table5_frame.yaml\nseed: 3\n"
         "actual: {geometry: {xa3: 433.5, ya3: 499.4, la1: 244.1, lb2: 244.2, dth1: 0.01, dth3: -0.01}}\n"
         "encoder: {bits: 20}\n"
         "sampling: {pattern: disc, radius: 130, count: 20, move_speed_mm_s: 250}\n"
         "calibration: {cost: ml}\n" +
         operation;
}

// With operation: the calibrated model monitors it; the monitor starts from
// the calibration's geometry and 1-sigma, and its summary joins summary.json.
TEST(MonitorRun, GpmRunMonitorsTheOperationWithTheCalibratedModel) {
  const RunSpec spec = parse_run_spec(
      run_yaml("operation: {path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}, duration_s: 8}\n"),
      "t.yaml", kBase);
  const RunOutcome o = run_scenario(spec, "t.yaml");
  ASSERT_TRUE(o.calibration);
  ASSERT_TRUE(o.monitor);
  EXPECT_EQ(o.monitor->controller.geometry.values, o.calibration->geometry.values);
  EXPECT_EQ(o.monitor->false_alarms, 0);
  EXPECT_NEAR(o.monitor->simulated_s, 8.0, 0.01);
  // The prior of an estimated parameter is the calibration's 1-sigma.
  const auto& m = o.monitor->model;
  for (int k = 0; k < m.n_free; ++k) {
    const int p = m.free_index[static_cast<size_t>(k)];
    EXPECT_NEAR(std::sqrt(m.prior_variance[static_cast<size_t>(k)]) / m.scale[static_cast<size_t>(k)],
                o.calibration->sigma[static_cast<size_t>(p)], 1e-12 + 1e-9 * o.calibration->sigma[static_cast<size_t>(p)])
        << param_name(p);
  }
  const std::string json = summary_json(o);
  EXPECT_NE(json.find("\"monitor\""), std::string::npos);
  EXPECT_NE(json.find("\"false_alarms\": 0"), std::string::npos) << json;
}

// events: belong to the operation: the calibration's sampling (about 20 s
// of stop-and-go here, longer than the event's at_s) runs on the mechanism
// before them, so it is the same with or without them, and the monitor of
// the operation detects the jump.
TEST(MonitorRun, OperationEventsLeaveTheCalibrationAloneAndAreDetected) {
  const std::string op =
      "operation: {path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}, duration_s: 8}\n";
  const RunOutcome plain = run_scenario(parse_run_spec(run_yaml(op), "t.yaml", kBase), "t.yaml");
  const RunOutcome with =
      run_scenario(parse_run_spec(run_yaml(op + "events: [{at_s: 5, change: {dth2: 1.0e-3}}]\n"), "t.yaml", kBase),
                   "t.yaml");
  ASSERT_TRUE(plain.calibration && with.calibration);
  EXPECT_GT(with.sim.sampling_s, 5.0) << "the sampling should outlast the event's time";
  EXPECT_EQ(with.calibration->geometry.values, plain.calibration->geometry.values);
  ASSERT_TRUE(with.monitor);
  ASSERT_EQ(with.monitor->detections.size(), 1u);
  ASSERT_TRUE(with.monitor->detections[0].detected_s) << "the jump at 5 s was not detected";
  EXPECT_GE(*with.monitor->detections[0].detected_s, 5.0);
  EXPECT_EQ(with.monitor->false_alarms, 0);
}

TEST(MonitorRun, GpmRunWithoutOperationDoesNotMonitor) {
  const RunSpec spec = parse_run_spec(run_yaml(""), "t.yaml", kBase);
  const RunOutcome o = run_scenario(spec, "t.yaml");
  EXPECT_FALSE(o.monitor);
  EXPECT_EQ(summary_json(o).find("\"monitor\""), std::string::npos);
}

// The reading model follows the twin's stated effects; a calibration in
// motion replaces the skew and compliance with its estimates.
TEST(MonitorRun, ReadingModelComesFromTheEffectsOrTheCalibration) {
  sim::TwinConfig twin;
  twin.effects = sim::realistic_effects();
  calib::monitor::MonitorSettings ms;
  apply_reading_model(ms, twin, std::nullopt);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(ms.skew_s[i], twin.effects.encoder_skew_s[i]);
    EXPECT_EQ(ms.compliance_rad_per_Nm[i], twin.effects.mjcf.compliance_rad_per_Nm[i]);
    EXPECT_EQ(ms.coulomb_Nm[i], twin.effects.mjcf.coulomb_Nm[i]);
    EXPECT_DOUBLE_EQ(ms.viscous_Nm_s[i], twin.mjcf.active_damping + twin.effects.mjcf.viscous_Nm_s[i]);
    EXPECT_EQ(ms.cyclic_rad[i], twin.effects.encoder_cyclic_rad[i]);
    EXPECT_DOUBLE_EQ(ms.clearance_mm[i], 1e3 * twin.effects.mjcf.clearance_m[i]);
  }
  apply_reading_model(ms, twin, std::array<double, 5>{1e-5, 2e-5, 3e-4, 4e-4, 5e-4});
  EXPECT_EQ(ms.skew_s, (std::array<double, 3>{0.0, 1e-5, 2e-5}));
  EXPECT_EQ(ms.compliance_rad_per_Nm, (std::array<double, 3>{3e-4, 4e-4, 5e-4}));
}

// Through hardware: the twin backend's actual robot (the fixture's perturbed
// GPM2002) follows the circle for a few seconds.
const std::string kSrc = GPM_SOURCE_DIR;
const std::string kTwinScenario = kSrc + "/tests/fixtures/twin_disc.yaml";
// Emulator writes before an injected slip: four a cycle (three position
// commands, the latch) at 250 Hz, the move to the path's start, then about
// 4.5 s of the operation.
constexpr long kSlipAfterWrites = 6000;

struct HardwareRig {
  hw::test::TempDir dir;
  Robot actual;
  explicit HardwareRig(const std::string& name) : dir(name) {
    actual = hw::twin_config_from_scenario(kTwinScenario, 0.004).actual;
    hw::test::write_text(dir.path() / "actual.yaml", robot_to_yaml(actual));
    hw::test::write_text(dir.path() / "op.yaml",
                         "name: op\nrobot: " + kSrc + "/models/gpm2002.yaml\nencoder: {bits: 17}\n"
                         "operation: {path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}, duration_s: 6}\n");
  }
  // A hardware file for backend (twin or modbus) whose controller is robot_file.
  std::string hardware(const std::string& backend, const std::string& extra, const std::string& robot_file) {
    const auto p = dir.path() / (backend + ".yaml");
    hw::test::write_text(p, "backend: " + backend + "\nrate_hz: 250\ncontroller: " + robot_file + "\n" + extra +
                                hw::test::kSafetyYaml);
    return p.string();
  }
  sim::Scenario scenario() const { return sim::load_scenario((dir.path() / "op.yaml").string()); }
};

// The calibrated (here: the actual) model raises no alarm through the twin
// backend; the nominal model (0.3 mm and 0.01 rad off) is alarmed as soon as
// the monitor may alarm. Truth unknown: no false-alarm count.
TEST(MonitorRun, MonitorsThroughTheTwinBackend) {
  HardwareRig rig("monitor_twin");
  const std::string hw_actual = rig.hardware("twin", "twin: {scenario: " + kTwinScenario + "}\n",
                                             (rig.dir.path() / "actual.yaml").string());
  std::array<double, kNumParams> prior;
  prior.fill(std::numeric_limits<double>::quiet_NaN());
  const MonitorOutcome good = run_monitor_hardware(rig.scenario(), hw_actual, rig.actual, prior);
  EXPECT_FALSE(good.truth_known);
  EXPECT_FALSE(good.hardware.empty());
  EXPECT_GT(good.cycles, 1500);  // 7 s at 250 Hz
  EXPECT_GT(good.accepted, 500);
  EXPECT_TRUE(good.alarms.empty()) << good.alarms.front().explanation;
  EXPECT_TRUE(monitor_summary(good)["false_alarms"].is_null());
  EXPECT_TRUE(monitor_summary(good)["final_error"].empty());

  const std::string hw_nominal = rig.hardware("twin", "twin: {scenario: " + kTwinScenario + "}\n", kSrc + "/models/gpm2002.yaml");
  const MonitorOutcome bad = run_monitor_hardware(rig.scenario(), hw_nominal, Robot{}, prior);
  ASSERT_FALSE(bad.alarms.empty());
  // as soon as the monitor may alarm (one window learnt), with a parameter named
  EXPECT_LT(bad.alarms.front().t_s, 4.0);
  EXPECT_GE(bad.alarms.front().param, 0) << bad.alarms.front().explanation;
}

// Monitors the rig's operation through the drive emulator (Modbus/TCP on
// localhost, the example register map, with or without its latch, faults
// injected as given): readings, speeds and torques come from the drives'
// registers, read one drive after the other while the robot moves.
MonitorOutcome monitor_through_emulator(HardwareRig& rig, const hw::EmulatorFaults& faults, bool latch) {
  hw::ManualClock clock{true};
  hw::EmulatorOptions o;
  o.clock = &clock;
  o.faults = faults;
  std::string map = hw::test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  if (!latch) {  // every line that names the latch goes
    std::string kept;
    for (size_t at = 0; at < map.size();) {
      const size_t end = std::min(map.find('\n', at), map.size() - 1) + 1;
      const std::string line = map.substr(at, end - at);
      if (line.find("latch") == std::string::npos) kept += line;
      at = end;
    }
    map = kept;
  }
  const auto map_path = rig.dir.path() / "map.yaml";
  hw::test::write_text(map_path, map);
  hw::DriveEmulator emu(hw::load_register_map(map_path.string()), hw::twin_config_from_scenario(kTwinScenario, 0.004), o);
  const int port = emu.start();
  map.replace(map.find("port: 1502"), 10, "port: " + std::to_string(port));
  hw::test::write_text(map_path, map);
  const std::string file = rig.hardware("modbus", "modbus: {register_map: map.yaml}\n", (rig.dir.path() / "actual.yaml").string());
  std::array<double, kNumParams> prior;
  prior.fill(std::numeric_limits<double>::quiet_NaN());
  MonitorOutcome out = run_monitor_hardware(rig.scenario(), file, rig.actual, prior);
  EXPECT_NE(out.hardware.find("modbus"), std::string::npos) << out.hardware;
  EXPECT_GT(out.cycles, 1500);
  EXPECT_GT(out.accepted, 500);  // every joint moving: most cycles give a sample
  for (const MonitorEstimateRow& r : out.estimates)
    for (int k = 0; k < kNumParams; ++k)
      if (out.model.settings.estimate[static_cast<size_t>(k)]) EXPECT_TRUE(std::isfinite(r.value[static_cast<size_t>(k)]));
  for (const MonitorAlarm& a : out.alarms) EXPECT_FALSE(a.explanation.empty());
  return out;
}

// Through the drive emulator with the map's latch, the three readings of a
// cycle are of one instant, as on the twin backend: the correctly calibrated
// (actual) model raises no alarm while the robot moves at about 0.1 m/s.
// Read one after another without the latch, the readings of a cycle are up
// to a plant tick apart (some 8 counts at these joint speeds) and the
// closure alarms (measured: 2 alarms in the 7 s, the first explained as a
// 1.5e-4 rad offset jump of joint 1).
TEST(MonitorRun, MonitorsThroughTheDriveEmulatorWithoutFalseAlarms) {
  HardwareRig rig("monitor_modbus");
  const MonitorOutcome out = monitor_through_emulator(rig, {}, true);
  EXPECT_TRUE(out.alarms.empty()) << out.alarms.size() << " alarms, first: " << out.alarms.front().explanation;
}

// The same robot whose joint-2 encoder slips by 10 counts (an offset jump of
// -4.8e-4 rad, injected in the emulator's drive after about 4.5 s of
// operation): the monitor alarms after the slip and explains it as that
// offset jump (measured: dth2 -4.7e-4 rad, 0.5 s after the slip).
TEST(MonitorRun, DetectsAnEncoderSlipThroughTheDriveEmulator) {
  HardwareRig rig("monitor_slip");
  hw::EmulatorFaults f;
  f.slip_after_writes = kSlipAfterWrites;
  f.slip_axis = 1;
  f.slip_counts = 10;
  const MonitorOutcome out = monitor_through_emulator(rig, f, true);
  ASSERT_FALSE(out.alarms.empty());
  std::printf("first alarm at %.2f s: %s\n", out.alarms.front().t_s, out.alarms.front().explanation.c_str());
  EXPECT_GT(out.alarms.front().t_s, 3.0);  // none before the slip
  EXPECT_EQ(out.alarms.front().param, dth(1)) << out.alarms.front().explanation;
  EXPECT_NEAR(out.alarms.front().delta, -10 * 2 * M_PI / 131072, 1e-4) << out.alarms.front().explanation;
}

TEST(MonitorRun, HardwareRefusesEventsBeforeMoving) {
  HardwareRig rig("monitor_events");
  hw::test::write_text(rig.dir.path() / "ev.yaml",
                       "name: ev\nrobot: " + kSrc + "/models/gpm2002.yaml\nencoder: {bits: 17}\n"
                       "operation: {path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}, duration_s: 6}\n"
                       "events: [{at_s: 3, change: {dth2: 1.0e-4}}]\n");
  const std::string hw_file = rig.hardware("twin", "twin: {scenario: " + kTwinScenario + "}\n", (rig.dir.path() / "actual.yaml").string());
  std::array<double, kNumParams> prior;
  prior.fill(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(run_monitor_hardware(sim::load_scenario((rig.dir.path() / "ev.yaml").string()), hw_file, rig.actual, prior),
               InputError);
}

}  // namespace
}  // namespace gpm::scenario
