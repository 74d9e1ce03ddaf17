// Tests of hw/backends/twin_backend.cpp: drives off until activated, position hold,
// commanded motion, torque-off joints follow the others, time advances by read();
// the observer sees the twin at the instant its readings were latched; in mixed
// modes with thermal growth and events it steps as sim/'s twin of those modes.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/backends/twin_backend.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

TEST(TwinBackend, HoldsThenFollowsCommands) {
  TwinBackend twin(twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004));
  EXPECT_THROW(twin.read(0.0), LifecycleError);
  twin.configure();
  const HardwareState s0 = twin.last_state();
  EXPECT_FALSE(s0.drive[0].enabled);
  twin.activate();
  double t = 0.0;
  for (int k = 0; k < 50; ++k) {
    twin.write(hold_command(s0.theta_m), t);
    t += 0.004;
    twin.read(t);
  }
  EXPECT_NEAR(twin.last_state().time_s, 0.2, 1e-3);
  EXPECT_LT((twin.last_state().theta_m - s0.theta_m).cwiseAbs().maxCoeff(), 2e-4);
  EXPECT_TRUE(twin.last_state().drive[2].enabled);
  // Move along consistent targets of the twin's own actual robot: it follows.
  const Robot& actual = twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004).actual;
  Eigen::Vector3d target = s0.theta_m;
  for (int k = 1; k <= 250; ++k) {
    const Eigen::Vector2d p = actual.home + Eigen::Vector2d(20.0 * k / 250, 0);
    target = readings_from_active(actual.geometry, inverse_kinematics(actual.geometry, p, actual.branch).theta_a);
    for (int i = 0; i < 3; ++i) target[i] = wrap_2pi(target[i]);
    twin.write(hold_command(target), t);
    t += 0.004;
    twin.read(t);
  }
  for (int k = 0; k < 100; ++k) {
    twin.write(hold_command(target), t);
    t += 0.004;
    twin.read(t);
  }
  EXPECT_LT((twin.last_state().theta_m - target).cwiseAbs().maxCoeff(), 3e-4);
  EXPECT_NEAR(twin.snapshot().ee_mm.x(), actual.home.x() + 20.0, 0.1);
}

// The observer's snapshot is the drive loop tick at which the readings of
// each read were latched (the truth of the same instant), once per read.
TEST(TwinBackend, TheObserverSeesTheInstantTheReadingsWereLatched) {
  TwinBackend twin(twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004));
  int seen = 0;
  sim::TwinSnapshot last;
  twin.observe([&](const sim::TwinSnapshot& s) { ++seen, last = s; });
  twin.configure();
  twin.activate();
  const Eigen::Vector3d q0 = twin.last_state().theta_m;
  const double tick = 1.0 / 2000.0;  // the fixture's servo.rate_hz
  double t = 0.0;
  for (int k = 1; k <= 20; ++k) {
    twin.write(hold_command(q0 + Eigen::Vector3d(0.0, 1e-3 * k, 0.0)), t);
    t += 0.004;
    const HardwareState& st = twin.read(t);
    EXPECT_EQ(seen, k);
    EXPECT_EQ(last.readings, st.theta_m);  // the readings of this read, latched at that tick
    EXPECT_NEAR(std::remainder(last.time_s, tick), 0.0, 1e-9);
    EXPECT_LE(last.time_s, st.time_s);
    EXPECT_GT(last.time_s, t - 0.004);
  }
  twin.observe({});
  twin.read(t + 0.004);
  EXPECT_EQ(seen, 20);
}

TEST(TwinBackend, TorqueOffJointReportsDisabledAndStillReads) {
  TwinBackend twin(twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004));
  twin.configure();
  twin.activate();
  HardwareCommand c = hold_command(twin.last_state().theta_m);
  c.mode[2] = JointMode::kTorqueOff;
  twin.write(c, 0.0);
  const HardwareState& s = twin.read(0.04);
  EXPECT_TRUE(s.drive[0].enabled);
  EXPECT_FALSE(s.drive[2].enabled);
  EXPECT_EQ(s.torque[2], 0.0);
  twin.deactivate();
  EXPECT_FALSE(twin.read(0.08).drive[0].enabled);
}

// A torque-off joint 1 with thermal growth and an event (as the main job): the
// state's own model copy (thermal growth, events) is made from the all-position
// model and stepped with the mixed-mode one. The drive modes live in the
// TwinModel's config, not in the compiled mjModel, so the two are the same
// model byte for byte, and the backend steps exactly as sim/'s twin built for
// modes [torque_off, position, position] does (joint 1 exerts no torque).
TEST(TwinBackend, MixedModesWithThermalGrowthStepAsTheTwinOfThoseModes) {
  TwinBackendConfig config = twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004);
  config.twin.effects.thermal = sim::ThermalEffect{2.3e-5, 20.0, 0.5, std::nullopt, std::nullopt};
  sim::GeometryEvent event;
  event.at_s = 0.1, event.over_s = 0.2;
  event.delta[lb(1)] = 0.05;
  config.twin.events = {event};
  sim::TwinConfig mixed = config.twin;
  mixed.drives[0].mode = sim::ServoMode::kTorqueOff;
  config.twin = mixed;  // the scenario's modes, as gpm run gives them
  TwinBackend twin(config);
  twin.configure();
  twin.activate();
  const std::array<JointMode, 3> modes{JointMode::kTorqueOff, JointMode::kPosition, JointMode::kPosition};
  const mjModel* all = twin.model({JointMode::kPosition, JointMode::kPosition, JointMode::kPosition}).mj();
  const sim::TwinModel& stepped = twin.model(modes);
  EXPECT_EQ(stepped.config().drives[0].mode, sim::ServoMode::kTorqueOff);
  ASSERT_EQ(all->nbuffer, stepped.mj()->nbuffer);
  EXPECT_EQ(std::memcmp(all->buffer, stepped.mj()->buffer, static_cast<std::size_t>(all->nbuffer)), 0);

  // sim/'s twin of the same scenario, given the commands the backend gives its drives.
  const sim::TwinModel model(config.actual, mixed);
  sim::TwinState direct(model, config.seed);
  Eigen::Vector3d last = twin.last_state().theta_m;
  const double theta1_start = twin.snapshot().theta_a[0];
  double t = 0.0;
  for (int k = 1; k <= 100; ++k) {
    HardwareCommand c = hold_command(last);
    c.mode = modes;
    c.theta_m[1] = last[1] + 1e-4, c.theta_m[2] = last[2] - 1e-4;  // a slow ramp of joints 2 and 3
    const Eigen::Vector3d step = c.theta_m - last;
    Eigen::Vector3d reference = last + 0.5 * step, velocity = step / 0.004;
    reference[0] = direct.last.readings[0], velocity[0] = 0.0;
    twin.write(c, t);
    sim::twin_command(direct, reference, velocity);
    t += 0.004;
    const HardwareState& s = twin.read(t);
    while (direct.data->time + 0.5 * model.timestep_s() < t) sim::twin_step(model, direct);
    ASSERT_EQ(s.torque[0], 0.0) << "read " << k;
    ASSERT_EQ(twin.snapshot().theta_a, direct.last.theta_a) << "read " << k;
    ASSERT_EQ(twin.snapshot().ee_mm, direct.last.ee_mm) << "read " << k;
    last = c.theta_m;
  }
  EXPECT_GT(twin.snapshot().growth, 1e-5);  // thermal growth in effect
  EXPECT_GT(std::abs(twin.snapshot().theta_a[0] - theta1_start), 1e-3);  // the free joint 1 followed the others
}

}  // namespace
}  // namespace gpm::hw
