// Tests of run/monitor_run.cpp: gpm run's monitoring hook (the calibrated
// model monitors `operation:` after the calibration) and the monitor's
// reading model taken from the scenario's effects.
#include "run/monitor_run.hpp"

#include <gtest/gtest.h>

#include "models/data_dir.hpp"
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

}  // namespace
}  // namespace gpm::scenario
