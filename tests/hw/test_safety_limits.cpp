// Tests of hw/safety_limits.cpp: all keys required, values validated, round trip.
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace gpm::hw
