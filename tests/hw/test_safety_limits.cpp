// Tests of hw/safety_limits.cpp: all keys required, values validated, round trip;
// the supervisor's fast reach test agrees with check_reach (the conditioning's SVDs).
#include <gtest/gtest.h>

#include "models/kinematics.hpp"
#include "models/rng.hpp"

#include "hw_test_util.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

SafetyLimits parse(const std::string& text) {
  const YAML::Node n = load_yaml_string(text, "hw.yaml");
  return safety_limits_from_yaml(n["safety"], "hw.yaml", "safety");
}

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string without(const std::string& key) {
  std::string t = test::kSafetyYaml;
  const size_t a = t.find("  " + key + ":");
  return t.erase(a, t.find('\n', a) - a + 1);
}

TEST(SafetyLimits, ParsesTheExample) {
  const SafetyLimits s = test::example_limits();
  EXPECT_EQ(s.joint_min[1], 2.4);
  EXPECT_EQ(s.max_acceleration[2], 5.0);
  EXPECT_EQ(s.workspace_radius_mm, 90.0);
  EXPECT_EQ(s.watchdog_disable_s, 0.5);
  EXPECT_EQ(parse("safety:\n" + safety_limits_to_yaml(s, 2)), s);
}

TEST(SafetyLimits, EveryKeyIsRequired) {
  for (const char* key : {"joint_min", "joint_max", "max_velocity", "max_acceleration",
                          "workspace_centre", "workspace_radius", "workspace_margin",
                          "reach_margin", "min_transmission", "min_direct", "max_inconsistency",
                          "watchdog_hold", "watchdog_disable", "comms_timeout"}) {
    const std::string e = error_of(without(key));
    EXPECT_NE(e.find(std::string("missing key '") + key + "'"), std::string::npos) << e;
  }
  EXPECT_NE(error_of("name: x\n").find("missing section 'safety'"), std::string::npos);
}

TEST(SafetyLimits, BadValuesNameTheKey) {
  std::string t = test::kSafetyYaml;
  t.replace(t.find("[1.0, 1.0, 1.0]"), 15, "[1.0, -1.0, 1.0]");
  EXPECT_NE(error_of(t).find("safety.max_velocity[1]: must be positive"), std::string::npos)
      << error_of(t);
  t = test::kSafetyYaml;
  t.replace(t.find("watchdog_disable: 0.5"), 21, "watchdog_disable: 0.05");
  EXPECT_NE(error_of(t).find("must be longer than watchdog_hold"), std::string::npos);
  t = test::kSafetyYaml + "  max_speed: 3\n";
  EXPECT_NE(error_of(t).find("unknown key"), std::string::npos);
}

// Speeds, accelerations and lengths beyond what this robot can do are
// refused (max_velocity 1e9 and workspace_radius 1e6 were once accepted).
std::string with(const std::string& key, const std::string& value) {
  std::string t = test::kSafetyYaml;
  const size_t a = t.find("  " + key + ":");
  const size_t b = t.find('\n', a);
  return t.replace(a, b - a, "  " + key + ": " + value);
}

TEST(SafetyLimits, ValuesOutsidePhysicalRangesAreRefused) {
  EXPECT_NE(error_of(with("max_velocity", "[1e9, 1, 1]")).find("max_velocity[0]"), std::string::npos);
  EXPECT_NE(error_of(with("max_velocity", "[1, 1, 20.5]")).find("above 20 rad/s"), std::string::npos);
  EXPECT_EQ(error_of(with("max_velocity", "[20, 20, 20]")), "");
  EXPECT_NE(error_of(with("max_acceleration", "[1, 1e6, 1]")).find("max_acceleration[1]"), std::string::npos);
  EXPECT_NE(error_of(with("workspace_radius", "1e6")).find("(0, 500] mm"), std::string::npos);
  EXPECT_EQ(error_of(with("workspace_radius", "500")), "");
  EXPECT_NE(error_of(with("reach_margin", "1e5")).find("reach_margin"), std::string::npos);
  EXPECT_NE(error_of(with("workspace_centre", "[1e7, 250]")).find("workspace_centre"), std::string::npos);
  EXPECT_NE(error_of(with("joint_max", "[1.9, 3.8, 100]")).find("joint_max"), std::string::npos);
}

// clears_reach passes only what check_reach passes, with check_reach's IK, and
// decides by itself every point whose type-2 measure clears min_direct by
// more than 1e-5 (only a thin band goes to check_reach's SVDs). The points
// cover the whole reachable region and beyond (both verdicts, every reason).
TEST(SafetyLimits, ClearsReachAgreesWithCheckReach) {
  Robot robot;
  robot.limits.reach_margin = 2.0;
  robot.limits.min_transmission = 0.15;
  robot.limits.min_direct = 0.4;  // high enough that many points fail it
  Rng rng(5);
  int cleared = 0, refused = 0, band = 0;
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector2d p(rng.uniform(0.0, 450.0), rng.uniform(0.0, 500.0));
    JointAngles q;
    const bool fast = clears_reach(robot, p, q);
    const Reach r = check_reach(robot, p);
    if (fast) {
      ASSERT_TRUE(r.ok) << p.transpose();
      ASSERT_EQ(q.theta_a, r.q.theta_a);
      ASSERT_EQ(q.theta_b, r.q.theta_b);
      ++cleared;
    } else if (!r.ok) {
      ++refused;
    } else {
      ASSERT_LE(r.cond.direct, robot.limits.min_direct * (1.0 + 1e-5)) << p.transpose();
      ++band;
    }
  }
  EXPECT_GT(cleared, 1000);
  EXPECT_GT(refused, 1000);
  EXPECT_LE(band, 5);
  // The workspace sentence with the IK is the one without it.
  const SafetyLimits limits = test::example_limits();
  robot.limits.min_direct = limits.min_direct;
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(216.5, 250.0), Eigen::Vector2d(216.5, 350.0),
                                  Eigen::Vector2d(300.0, 250.0), Eigen::Vector2d(NAN, 1.0)}) {
    JointAngles q;
    const std::string why = workspace_violation(limits, robot, p, "target", &q);
    const Reach r = check_reach(robot, p);
    const bool in_disc = (p - limits.workspace_centre).norm() <= limits.workspace_radius_mm - limits.workspace_margin_mm;
    EXPECT_EQ(why.empty(), in_disc && r.ok) << p.transpose();
    if (why.empty()) {
      EXPECT_EQ(q.theta_a, r.q.theta_a);
    }
  }
}

}  // namespace
}  // namespace gpm::hw
