// Tests of sim/scenario.cpp: the example scenarios parse, every setting lands
// where it belongs, bad input names the key path, reserved sections are
// accepted, and the actual parameters are seeded and respect `keep`.
#include "sim/scenario.hpp"
#include "models/data_dir.hpp"

#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/robot_yaml.hpp"

namespace gpm::sim {
namespace {

const std::string kScenarios = gpm::scenarios_dir();
const std::string kModels = gpm::models_dir();

Scenario parse(const std::string& text) { return parse_scenario(text, "s.yaml", kModels); }

// The InputError message of parsing text (empty if it parses).
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kMinimal = "sampling: {pattern: disc, radius: 10, count: 3}\n";

TEST(Scenario, ExampleScenariosParse) {
  for (const char* f : {"simulate_disc.yaml", "simulate_circle.yaml"}) {
    const Scenario s = load_scenario(kScenarios + "/" + f);
    EXPECT_TRUE(s.sampling.has_value()) << f;
    EXPECT_EQ(s.controller.geometry, Geometry::gpm2002_nominal()) << f;
  }
  const Scenario c = load_scenario(kScenarios + "/simulate_circle.yaml");
  EXPECT_EQ(c.twin.drives[2].mode, ServoMode::kTorqueOff);
  EXPECT_EQ(c.twin.drives[0].mode, ServoMode::kPosition);
  EXPECT_DOUBLE_EQ(c.twin.encoder.noise_rad, 2e-5);
  ASSERT_TRUE(c.path.has_value());
  EXPECT_DOUBLE_EQ(std::get<CirclePath>(*c.path).period_s, 2.0);
  EXPECT_DOUBLE_EQ(*c.actual.explicit_values[kLa3], 244.5);
}

TEST(Scenario, AlternatingPreloadLandsOnItsDrive) {
  const Scenario s = parse(std::string(kMinimal) +
                           "servo: {modes: [{torque: -2, alternate_s: 1.2}, position, position]}\n");
  EXPECT_EQ(s.twin.drives[0].mode, ServoMode::kTorque);
  EXPECT_EQ(s.twin.drives[0].torque_Nm, -2.0);
  EXPECT_EQ(s.twin.drives[0].alternate_s, 1.2);
  EXPECT_EQ(s.twin.drives[0].ramp_s, 0.2) << "the default ramp";
  const Scenario fast = parse(std::string(kMinimal) +
                              "servo: {modes: [{torque: 1, alternate_s: 0.1}, position, position]}\n");
  EXPECT_EQ(fast.twin.drives[0].ramp_s, 0.05) << "at most half the time between changes";
  const Scenario step = parse(std::string(kMinimal) +
                              "servo: {modes: [{torque: 1, alternate_s: 1, ramp_s: 0}, position, position]}\n");
  EXPECT_EQ(step.twin.drives[0].ramp_s, 0.0);
  EXPECT_EQ(s.twin.drives[1].alternate_s, 0.0);
  const Scenario constant = parse(std::string(kMinimal) + "servo: {modes: [{torque: 1}, position, position]}\n");
  EXPECT_EQ(constant.twin.drives[0].alternate_s, 0.0);
}

TEST(Scenario, SettingsLandWhereTheyBelong) {
  const Scenario s = parse(R"(
robot: gpm2002.yaml
seed: 99
physics: {timestep_s: 0.00025}
servo: {rate_hz: 4000, kp: 80, kv: 12, ki: 5, feedforward: 0.5, torque_limit: 20, velocity_limit: 3}
encoder: {bits: 20, noise_rad: 1e-6}
sampling:
  pattern: line
  from: [200, 240]
  to: [230, 260]
  count: 4
  move_speed_mm_s: 50
  settle: {velocity_rad_s: 0.01, hold_s: 0.1, timeout_s: 3}
  average_s: 0.2
log: {every: 10}
)");
  EXPECT_EQ(s.seed, 99u);
  EXPECT_DOUBLE_EQ(s.twin.mjcf.timestep_s, 0.00025);
  EXPECT_DOUBLE_EQ(s.twin.servo_rate_hz, 4000);
  for (const auto& d : s.twin.drives) {
    EXPECT_DOUBLE_EQ(d.kp, 80);
    EXPECT_DOUBLE_EQ(d.kv, 12);
    EXPECT_DOUBLE_EQ(d.ki, 5);
    EXPECT_DOUBLE_EQ(d.feedforward, 0.5);
    EXPECT_DOUBLE_EQ(d.torque_limit, 20);
    EXPECT_DOUBLE_EQ(d.velocity_limit, 3);
  }
  EXPECT_EQ(s.twin.encoder.bits, 20);
  EXPECT_EQ(s.sampling->pattern, PosePattern::kLine);
  EXPECT_EQ(s.sampling->count, 4);
  EXPECT_DOUBLE_EQ(s.sampling->options.move_speed_mm_s, 50);
  EXPECT_DOUBLE_EQ(s.sampling->options.settle.hold_s, 0.1);
  EXPECT_DOUBLE_EQ(s.sampling->options.average_s, 0.2);
  EXPECT_EQ(s.log_every, 10);
  const auto poses = plan_poses(*s.sampling, s.seed);
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_DOUBLE_EQ(poses[3].x(), 230.0);
}

// Issue 19: trajectory.csv at 200 rows/s unless asked otherwise; log.every: 1
// is the servo rate; log.rate_hz picks the nearest whole divisor of it.
TEST(Scenario, TrajectoryLogRate) {
  const auto every = [](const std::string& extra) {
    return parse_scenario(std::string(kMinimal) + extra, "t.yaml", ".").log_every;
  };
  EXPECT_EQ(every("servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\n"), 20);  // 4000 / 200
  EXPECT_EQ(every("servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\nlog: {every: 1}\n"), 1);
  EXPECT_EQ(every("servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\nlog: {rate_hz: 1000}\n"), 4);
  EXPECT_EQ(every("servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\nlog: {rate_hz: 4000}\n"), 1);
  EXPECT_EQ(every("servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\nlog: {rate_hz: 300}\n"), 13);  // 13.3
  EXPECT_NE(error_of(std::string(kMinimal) + "log: {every: 2, rate_hz: 100}").find("not both"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {rate_hz: 4000}\nphysics: {timestep_s: 0.00025}\n"
                                             "log: {rate_hz: 5000}")
                .find("log.rate_hz: must be at most the servo rate (4000 Hz"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "log: {rate_hz: 0}").find("log.rate_hz"), std::string::npos);
}

TEST(Scenario, ErrorsNameTheKeyPath) {
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: -5, count: 3}").find("sampling.radius: must be positive"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 5, count: 0}").find("sampling.count: must be a whole number"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: spiral, radius: 5, count: 3}").find("sampling.pattern: 'spiral' is not"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {kp: fast}").find("servo.kp: 'fast' is not a number"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [position, off, position]}").find("servo.modes[1]"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torque: 50}, position, position]}").find("servo.modes[0].torque: must be within +-torque_limit (38 N m), got 50"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torque: 1}, position, torque_off]}").find("at least two"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torq: 1}, position, position]}").find("servo.modes[0]"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torque: 1, alternate_s: 0}, position, position]}")
                .find("servo.modes[0].alternate_s: must be from 0.01 to 600 s, got 0"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torque: 1, alternate_s: 1, ramp_s: 0.6}, position, position]}")
                .find("servo.modes[0].ramp_s: must be from 0 to 0.5 s, got 0.6"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{torque: 1, ramp_s: 0.1}, position, position]}")
                .find("servo.modes[0].ramp_s: needs alternate_s"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [{alternate_s: 1}, position, position]}")
                .find("servo.modes[0]: expected {torque: N m}"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {modes: [position, torque_off, torque_off]}").find("at least two"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {rate_hz: 1500}").find("servo.rate_hz"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "actual: {geometry: {la9: 1}}").find("actual.geometry.la9: unknown parameter (did you mean la1?)"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "actual: {perturb: {link_mm: -1}}").find("actual.perturb.link_mm: must be zero or positive"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "actual: {perturb: {keep: [xa1, ya1, xa1]}}").find("actual.perturb.keep[2]: 'xa1' is listed twice"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "encoder: {bits: 17.5}").find("encoder.bits"), std::string::npos);
  EXPECT_NE(error_of("seed: 1\n").find("nothing to simulate"), std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: list, poses: [[1, 2], [3]]}").find("sampling.poses[1]"), std::string::npos);
  EXPECT_NE(error_of("path: {shape: circle, radius: 5}").find("missing key 'period_s'"), std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "robot: nowhere.yaml").find("s.yaml:2: robot: no robot file " + kModels + "/nowhere.yaml"),
            std::string::npos);
  // File and line come first.
  EXPECT_EQ(error_of("seed: 1\nsampling: {pattern: disc, radius: -5, count: 3}").rfind("s.yaml:2: ", 0), 0u);
}

// The excitation path's margin (sampling.path_margin, trajectory only) and
// the tracking bound (servo.max_tracking_mm): documented defaults, set
// values land, bad ones name the key.
TEST(Scenario, PathMarginAndTrackingBound) {
  const std::string fly = "sampling: {pattern: trajectory, count: 11";
  const Scenario d = parse(fly + "}\n");
  EXPECT_EQ(d.sampling->margin, PathMargin{});
  EXPECT_DOUBLE_EQ(d.sampling->margin.singularity, 0.15);
  EXPECT_DOUBLE_EQ(d.sampling->margin.reach_mm, 10.0);
  EXPECT_DOUBLE_EQ(d.sampling->margin.deviation_mm, 20.0);  // servo.max_tracking_mm's default
  EXPECT_EQ(d.sampling->margin.tolerance, (ModelTolerance{1.0, 1.0, 0.02}));
  EXPECT_DOUBLE_EQ(d.max_tracking_mm, 20.0);
  const Scenario s = parse(fly + ", path_margin: {singularity: 0.3, reach_mm: 5, deviation_mm: 7, tolerance: {base_mm: 0.5, link_mm: 0.2, "
                                 "offset_rad: 0.01}}}\nservo: {max_tracking_mm: 8}\n");
  EXPECT_DOUBLE_EQ(s.sampling->margin.singularity, 0.3);
  EXPECT_DOUBLE_EQ(s.sampling->margin.reach_mm, 5.0);
  EXPECT_DOUBLE_EQ(s.sampling->margin.deviation_mm, 7.0);
  EXPECT_EQ(s.sampling->margin.tolerance, (ModelTolerance{0.5, 0.2, 0.01}));
  EXPECT_DOUBLE_EQ(s.max_tracking_mm, 8.0);
  EXPECT_NE(error_of(fly + ", path_margin: {singularity: 1.5}}").find("sampling.path_margin.singularity: must be from 0 to 0.9"),
            std::string::npos);
  EXPECT_NE(error_of(fly + ", path_margin: {deviation_mm: -2}}").find("sampling.path_margin.deviation_mm: must be from 0"),
            std::string::npos);
  EXPECT_NE(error_of(fly + ", path_margin: {tolerance: {offset: 1}}}").find("sampling.path_margin.tolerance.offset"),
            std::string::npos);
  EXPECT_NE(error_of(fly + ", path_margin: 3}").find("sampling.path_margin: expected a map"), std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 3, path_margin: {}}").find("only for pattern: designed or trajectory"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "servo: {max_tracking_mm: -1}").find("servo.max_tracking_mm: must be from 0"),
            std::string::npos);
}

// The offsets stage (sampling.offsets_first_s, trajectory only): none by
// default, a set value lands, bad ones name the key.
TEST(Scenario, OffsetsStage) {
  const std::string fly = "sampling: {pattern: trajectory, count: 11";
  EXPECT_DOUBLE_EQ(parse(fly + "}\n").sampling->offsets_first_s, 0.0);
  EXPECT_DOUBLE_EQ(parse(fly + ", offsets_first_s: 1.5}\n").sampling->offsets_first_s, 1.5);
  EXPECT_NE(error_of(fly + ", offsets_first_s: -1}").find("sampling.offsets_first_s: must be from 0"), std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: designed, count: 11, offsets_first_s: 1}").find("only for pattern: trajectory"),
            std::string::npos);
}

// sampling.criterion: the design's criterion (designed and trajectory);
// positioning weighs readings along a path, so on the fly only.
TEST(Scenario, DesignCriterion) {
  const std::string fly = "sampling: {pattern: trajectory, count: 11";
  EXPECT_EQ(parse(fly + "}\n").sampling->criterion, DesignCriterion::kAuto);
  EXPECT_EQ(parse(fly + ", criterion: positioning}\n").sampling->criterion, DesignCriterion::kPositioning);
  EXPECT_EQ(parse(fly + ", criterion: worst}\n").sampling->criterion, DesignCriterion::kWorst);
  EXPECT_EQ(parse("sampling: {pattern: designed, count: 11, criterion: d}\n").sampling->criterion, DesignCriterion::kD);
  EXPECT_NE(error_of(fly + ", criterion: best}").find("sampling.criterion: 'best' is not worst, d or positioning"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: designed, count: 11, criterion: positioning}").find("only for pattern: trajectory"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 3, criterion: worst}").find("only for pattern: designed or trajectory"),
            std::string::npos);
}

TEST(Scenario, UnknownTopLevelKeyIsAnErrorWithASuggestion) {
  EXPECT_NE(error_of(std::string(kMinimal) + "sampeling: {}").find("sampeling: unknown key (did you mean sampling?)"),
            std::string::npos);
}

TEST(Scenario, ReservedSectionsAreAcceptedUnparsed) {
  const std::string text = std::string(kMinimal) +
                           "name: n\ndescription: d\ncalibration: {anything: [1, 2]}\nexpect: {x: 1}\n"
                           "hardware: {backend: twin}\noutputs: [a]\nrender: {fps: 30}\n";
  EXPECT_EQ(error_of(text), "");
  EXPECT_EQ(parse(text).name, "n");
}

TEST(Scenario, EmbeddedRobotAndRelativeRobotPath) {
  const Robot r = load_robot(kModels + "/gpm2002.yaml");
  const Scenario s = parse(std::string(kMinimal) + "robot:\n" + [&] {
    std::string y = robot_to_yaml(r), out;
    for (size_t a = 0, b; a < y.size(); a = b + 1) {
      b = y.find('\n', a);
      out += "  " + y.substr(a, b - a) + "\n";
    }
    return out;
  }());
  EXPECT_EQ(s.controller, r);
}

TEST(Scenario, ActualParametersAreSeededAndKeepTheFrame) {
  const std::string base = std::string(kMinimal) +
                           "actual: {geometry: {la3: 244.5}, perturb: {base_mm: 0.5, link_mm: 0.5, offset_rad: 0.01}}\n";
  const Scenario s1 = parse(base + "seed: 1\n");
  const Robot a = make_actual(s1);
  EXPECT_EQ(a.geometry, make_actual(parse(base + "seed: 1\n")).geometry);
  EXPECT_NE(a.geometry, make_actual(parse(base + "seed: 2\n")).geometry);
  EXPECT_EQ(a.geometry[kLa3], 244.5);
  for (int i : {kXa1, kYa1, kXa2, kYa2}) EXPECT_EQ(a.geometry[i], s1.controller.geometry[i]);
  for (int i : {kXa3, kYa3, kLa1, kLb2, kDth1, kDth3}) EXPECT_NE(a.geometry[i], s1.controller.geometry[i]);
  for (int i = 0; i < kNumParams; ++i) {
    const double lim = is_offset(i) ? 0.06 : 3.0;  // 6 sigma
    EXPECT_LT(std::abs(a.geometry[i] - s1.controller.geometry[i]), lim) << param_name(i);
  }
  const Robot all = make_actual(parse(std::string(kMinimal) + "actual: {perturb: {base_mm: 0.5, keep: []}}\n"));
  EXPECT_NE(all.geometry[kXa1], 0.0);
}

TEST(Scenario, ActualThatCannotAssembleIsRefused) {
  const Scenario s = parse(std::string(kMinimal) + "actual: {geometry: {la1: 10}}\n");
  try {
    make_actual(s);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot assemble"), std::string::npos) << e.what();
  }
}

TEST(Scenario, DurationsSpeedsAndCountsAreBounded) {
  // Issue 14.8 / 14.9: each refused with one line giving the valid range.
  EXPECT_EQ(error_of("sampling: {pattern: disc, radius: 10, count: 3, move_speed_mm_s: 1e-300}"),
            "s.yaml:1: sampling.move_speed_mm_s: must be from 1 to 2000 mm/s, got 1e-300");
  EXPECT_EQ(error_of("sampling: {pattern: disc, radius: 10, count: 3, average_s: 1e9}"),
            "s.yaml:1: sampling.average_s: must be from 0.0001 to 10 s, got 1e9");
  EXPECT_EQ(error_of("sampling: {pattern: disc, radius: 10, count: 3, settle: {timeout_s: 1e9}}"),
            "s.yaml:1: sampling.settle.timeout_s: must be from 0.001 to 60 s, got 1e9");
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 3, settle: {hold_s: 1e9}}")
                .find("sampling.settle.hold_s: must be from"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 3, settle: {velocity_rad_s: 1e-300}}")
                .find("sampling.settle.velocity_rad_s: must be from"),
            std::string::npos);
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 10, count: 100000}").find("sampling.count: must be a whole number from 1 to 10000"),
            std::string::npos);
  EXPECT_NE(error_of("path: {shape: circle, radius: 5, period_s: 1e-9}").find("path.period_s: must be from 0.1 to 600 s"),
            std::string::npos);
  EXPECT_NE(error_of("path: {shape: circle, radius: 5, period_s: 1, revolutions: 1e12}").find("path.revolutions: must be from"),
            std::string::npos);
  EXPECT_NE(error_of("path: {shape: line, from: [200, 250], to: [230, 250], duration_s: 1e9}").find("path.duration_s: must be from"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "physics: {timestep_s: 1e-12}").find("physics.timestep_s: must be from 1e-05 to 0.002 s"),
            std::string::npos);
  // Each key alone in range, together beyond what the trajectory log can hold in memory.
  EXPECT_NE(error_of("sampling: {pattern: disc, radius: 100, count: 10000, move_speed_mm_s: 1, settle: {timeout_s: 60}}")
                .find("sampling.count: the run could log up to"),
            std::string::npos);
  // The bounds themselves are accepted.
  EXPECT_EQ(error_of("sampling: {pattern: disc, radius: 10, count: 3, move_speed_mm_s: 2000, average_s: 10, "
                     "settle: {timeout_s: 60, hold_s: 0.0001, velocity_rad_s: 1}}"),
            "");
}

TEST(Scenario, ActualFromARobotFile) {
  // The same geometry as a robot file or as an explicit map gives the same actual robot.
  const Robot file = load_robot(kModels + "/gpm2002.yaml");
  const Scenario s = parse(std::string(kMinimal) + "seed: 5\nactual: gpm2002.yaml\n");
  std::string map = "actual:\n  geometry: {";
  for (int i = 0; i < kNumParams; ++i) map += fmt::format("{}{}: {}", i ? ", " : "", param_name(i), file.geometry[i]);
  map += "}\n";
  const Scenario m = parse(std::string(kMinimal) + "seed: 5\n" + map);
  EXPECT_EQ(make_actual(s).geometry, make_actual(m).geometry);
  EXPECT_EQ(make_actual(s).geometry, file.geometry);  // no perturbation
  // A missing file or a wrong type names the key.
  EXPECT_NE(error_of(std::string(kMinimal) + "actual: nowhere.yaml").find("s.yaml:2: actual: no robot file " + kModels + "/nowhere.yaml"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kMinimal) + "actual: [1, 2]").find("s.yaml:2: actual: expected a robot file"),
            std::string::npos);
}

}  // namespace
}  // namespace gpm::sim
