// Tests of sim/events.cpp and the events of the twin (sim/twin.cpp) and of
// scenario files (sim/scenario.cpp): closed-form geometry over time, an
// encoder slip seen by the readings and not by the mechanism, a link change
// ramped into the MuJoCo model with the loops still closed, and one-line
// errors for bad events.
#include "sim/events.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "models/bounds.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "sim/scenario.hpp"
#include "sim/twin.hpp"

namespace gpm::sim {
namespace {

GeometryEvent step(double at, int param, double delta) {
  GeometryEvent e;
  e.at_s = at;
  e.delta[static_cast<std::size_t>(param)] = delta;
  return e;
}

TEST(Events, GeometryOverTimeFollowsStepsAndRamps) {
  const Geometry g0 = Geometry::gpm2002_nominal();
  GeometryEvent drift = step(10.0, kLb1, 0.02);
  drift.over_s = 4.0;
  const std::vector<GeometryEvent> events{step(5.0, kDth2, 1e-4), step(6.0, kLa3, 0.01), drift};
  EXPECT_EQ(geometry_at(g0, events, 4.999).values, g0.values);
  // An offset step is immediate.
  EXPECT_DOUBLE_EQ(geometry_at(g0, events, 5.0)[kDth2], g0[kDth2] + 1e-4);
  // A length step ramps in linearly over kStepRampS.
  EXPECT_NEAR(geometry_at(g0, events, 6.0 + 0.5 * kStepRampS)[kLa3], g0[kLa3] + 0.005, 1e-12);
  EXPECT_NEAR(geometry_at(g0, events, 6.0 + 2.0 * kStepRampS)[kLa3], g0[kLa3] + 0.01, 1e-12);
  // A drift grows linearly over over_s and then stays.
  EXPECT_NEAR(geometry_at(g0, events, 11.0)[kLb1], g0[kLb1] + 0.005, 1e-12);
  EXPECT_NEAR(geometry_at(g0, events, 100.0)[kLb1], g0[kLb1] + 0.02, 1e-12);
  const Geometry after = geometry_after(g0, events);
  for (int k = 0; k < kNumParams; ++k) EXPECT_NEAR(after[k], geometry_at(g0, events, 1e6)[k], 1e-12);
}

TEST(Events, EncoderSlipShiftsTheReadingNotTheMechanism) {
  // Ideal encoders, joint 2 torque-off (its drive does not react to the slip).
  Robot actual;
  TwinConfig c;
  c.encoder.bits = 0;
  c.drives[1].mode = ServoMode::kTorqueOff;
  c.events = {step(0.05, kDth2, 1e-3)};
  const TwinModel m(actual, c);
  TwinState s(m, 1);
  while (s.last.time_s < 0.04) twin_step(m, s);
  const Eigen::Vector3d before_m = s.last.readings, before_a = s.last.theta_a;
  while (s.last.time_s < 0.1) twin_step(m, s);
  EXPECT_NEAR(wrap_pi(s.last.readings[1] - before_m[1]), -1e-3, 1e-9);
  EXPECT_NEAR(s.last.theta_a[1], before_a[1], 1e-7);
  EXPECT_NEAR(wrap_pi(s.last.readings[0] - before_m[0]), 0.0, 1e-7);
}

TEST(Events, LinkChangeRampsIntoTheModelWithTheLoopsClosed) {
  Robot actual;
  TwinConfig c;
  c.encoder.bits = 0;
  c.events = {step(0.1, kLb1, 0.02)};  // 20 um on passive link 1
  const TwinModel m(actual, c);
  TwinState s(m, 1);
  while (s.last.time_s < 0.1 + 1.2 * kStepRampS) {
    twin_step(m, s);
    ASSERT_LT(s.last.violation_m, 1e-6);  // never a jump: the loops stay closed to 1 um
  }
  EXPECT_NEAR(s.geometry[kLb1], actual.geometry[kLb1] + 0.02, 1e-12);
  EXPECT_NEAR(geometry_at_time(m, s.last.time_s)[kLb1], actual.geometry[kLb1] + 0.02, 1e-12);
}

std::string error_of(const std::string& text) {
  try {
    parse_scenario(text, "m.yaml", models_dir());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kOperation =
    "operation:\n  path: {shape: circle, centre: [216.5, 250], radius: 60, period_s: 4}\n  duration_s: 60\n";

TEST(Events, ScenarioEventsParseAndBadOnesAreOneLineErrors) {
  const Scenario s = parse_scenario(std::string(kOperation) + "events:\n  - {at_s: 30, change: {dth2: 1.0e-4}}\n"
                                    "  - {at_s: 10, ramp: {la1: 0.01}, over_s: 20}\n",
                                    "m.yaml", models_dir());
  ASSERT_TRUE(s.operation);
  EXPECT_DOUBLE_EQ(s.operation->duration_s, 60.0);
  ASSERT_EQ(s.twin.events.size(), 2u);
  EXPECT_DOUBLE_EQ(s.twin.events[0].delta[kDth2], 1e-4);
  EXPECT_DOUBLE_EQ(s.twin.events[1].over_s, 20.0);
  EXPECT_NE(error_of(std::string(kOperation) + "events:\n  - {at_s: 30, change: {dth4: 1.0e-4}}\n")
                .find("events[0].change.dth4: unknown parameter 'dth4' (did you mean dth1?)"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kOperation) + "events:\n  - {at_s: 90, change: {dth2: 1.0e-4}}\n")
                .find("events[0].at_s: must be from 0 to 60"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kOperation) + "events:\n  - {at_s: 1, change: {dth2: 1}, ramp: {dth2: 1}, over_s: 1}\n")
                .find("exactly one of change"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 3}\nevents:\n  - {at_s: 1, change: {dth2: 1.0e-4}}\n")
                .find("give an 'operation' section"),
            std::string::npos);
}

TEST(Events, AScenarioHoldsAtMostKMaxEvents) {
  // Issue 36.8: each event is checked every servo cycle; 100,000 of them were accepted.
  std::string many = std::string(kOperation) + "events:\n";
  for (std::size_t k = 0; k <= limits::kMaxEvents; ++k) many += "  - {at_s: 30, change: {dth2: 1.0e-4}}\n";
  EXPECT_NE(error_of(many).find("events: 1001 events; at most 1000 in one scenario"), std::string::npos)
      << error_of(many);
}

}  // namespace
}  // namespace gpm::sim
