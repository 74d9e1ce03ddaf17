// Tests of models/robot_yaml.cpp: the nominal file, the lossless round trip,
// and one test per class of bad input (each gives one clear InputError line).
#include "models/robot_yaml.hpp"
#include "models/data_dir.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

const std::string kNominal = gpm::models_dir() + "/gpm2002.yaml";

std::string error_of(const std::string& text) {
  try {
    parse_robot(text, "robot.yaml");
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << "one line";
    return m;
  }
  return "";
}

std::string nominal_text() {
  return robot_to_yaml(Robot{});
}

TEST(RobotYaml, NominalFileIsTheGpm2002) {
  const Robot r = load_robot(kNominal);
  EXPECT_EQ(r.name, "GPM2002");
  EXPECT_EQ(r.geometry, Geometry::gpm2002_nominal());
  EXPECT_EQ(r.home, Eigen::Vector2d(216.5, 250));
  EXPECT_EQ(r, Robot{});
}

TEST(RobotYaml, RoundTripIsBitExact) {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto dir = std::filesystem::temp_directory_path() / "gpm_test_robot_yaml";
  std::filesystem::create_directories(dir);
  for (int trial = 0; trial < 200; ++trial) {
    Robot r;
    for (int i = 0; i < kNumParams; ++i) r.geometry[i] += (is_offset(i) ? 0.01 : 0.5) * n(rng);
    r.home += Eigen::Vector2d(n(rng), n(rng));
    r.limits.reach_margin = std::abs(n(rng));
    const char* names[] = {"x: y", "null", "~", "1e3", "a \\ \"b\"", "caf\xc3\xa9"};
    r.name = trial % 2 ? "GPM2002 #" + std::to_string(trial) : names[(trial / 2) % 6];
    const std::string path = (dir / "r.yaml").string();
    save_robot(r, path);
    const Robot back = load_robot(path);
    ASSERT_EQ(back, r) << robot_to_yaml(r);
    for (int i = 0; i < kNumParams; ++i) ASSERT_EQ(back.geometry[i], r.geometry[i]);
  }
  std::filesystem::remove_all(dir);
}

// A calibration result file as gpm calibrate writes it (calib/result_yaml.cpp).
std::string result_text() {
  std::string t = nominal_text();
  t = t.substr(0, t.find("home:"));
  t.replace(t.find("  la1: 244"), 10, "  la1: 244.1");
  return "# gpm calibrate result: mm and rad (docs/FORMATS.md)\n" + t +
         "std:                 # 1-sigma of each estimated parameter\n"
         "  la1: 0.0021\n  ya3: .nan\n  dth1: 1.5e-05\n"
         "fixed: [xa1, ya1, xa2, ya2]\n"
         "diagnostics:\n"
         "  method: \"lm\"\n  cost_function: ml\n  cost: 1.25e-09\n  iterations: 12\n  evaluations: 13\n"
         "  rank: 11\n  free_parameters: 11\n  condition_number: .inf\n  kmrmse_mm: 0.0031\n"
         "  seconds: 0.25\n  converged: true\n  rank_deficient: false\n"
         "  notes:\n    - \"poorly exciting samples: condition number 1e6\"\n";
}

TEST(RobotYaml, ResultFileIsARobotFileAndKeepsItsRecord) {
  // Issue 18.2: accepted, the std, fixed and diagnostics kept.
  const Robot r = parse_robot(result_text(), "result.yaml");
  EXPECT_EQ(r.geometry[kLa1], 244.1);
  EXPECT_EQ(r.home, Robot{}.home);
  ASSERT_TRUE(r.calibration.has_value());
  const CalibrationRecord& c = *r.calibration;
  EXPECT_EQ(c.sigma[kLa1], 0.0021);
  EXPECT_EQ(c.sigma[kDth1], 1.5e-05);
  EXPECT_TRUE(std::isnan(*c.sigma[kYa3]));
  EXPECT_FALSE(c.sigma[kLb2].has_value());
  EXPECT_EQ(c.fixed, parse_param_list("xa1,ya1,xa2,ya2", "fixed"));
  ASSERT_EQ(c.diagnostics.size(), 13u);
  EXPECT_EQ(c.diagnostics[0], (std::pair<std::string, std::string>("method", "lm")));
  EXPECT_EQ(c.diagnostics[3], (std::pair<std::string, std::string>("iterations", "12")));
  EXPECT_EQ(c.diagnostics[12].first, "notes");
  // Round trip: written as a robot file and read back, the same robot, record included.
  const Robot back = parse_robot(robot_to_yaml(r), "again.yaml");
  EXPECT_EQ(back, r) << robot_to_yaml(r);
  EXPECT_EQ(robot_to_yaml(back), robot_to_yaml(r));
  // The drift monitor's reading model that gpm run adds is accepted (gpm
  // monitor reads it; the robot is the same without it).
  const Robot with_monitor =
      parse_robot(result_text() + "monitor: {skew_s: [0, 5.0e-5, 1.0e-4], clearance_mm: 0.005}\n", "result.yaml");
  EXPECT_EQ(with_monitor, r);
  // A plain robot file has no record, and writes none.
  EXPECT_FALSE(parse_robot(nominal_text(), "r.yaml").calibration.has_value());
  EXPECT_EQ(robot_to_yaml(Robot{}).find("diagnostics"), std::string::npos);
}

TEST(RobotYaml, ResultSectionsAreValidated) {
  const std::string t = result_text();
  const auto with = [&](const std::string& from, const std::string& to) {
    std::string u = t;
    u.replace(u.find(from), from.size(), to);
    return error_of(u);
  };
  EXPECT_NE(with("  la1: 0.0021", "  lx1: 0.0021").find("std.lx1: unknown parameter (did you mean la1?)"), std::string::npos);
  EXPECT_NE(with("  la1: 0.0021", "  xa1: 0.0021").find("std.xa1: a fixed parameter has no 1-sigma"), std::string::npos);
  EXPECT_NE(with("  la1: 0.0021", "  la1: -1").find("std.la1: a 1-sigma must be .nan (not determined) or from 0 to 100 mm, got -1"),
            std::string::npos);
  // A 1-sigma too large to mean anything (its square overflows a filter) or
  // infinite is refused, not replaced by a default (issue 36.6).
  EXPECT_NE(with("  la1: 0.0021", "  la1: 1e300").find("std.la1: a 1-sigma must be"), std::string::npos);
  EXPECT_NE(with("  la1: 0.0021", "  la1: .inf").find("std.la1: a 1-sigma must be"), std::string::npos);
  EXPECT_NE(with("  dth1: 1.5e-05", "  dth1: 2").find("std.dth1: a 1-sigma must be .nan (not determined) or from 0 to 1 rad"),
            std::string::npos);
  EXPECT_EQ(with("  la1: 0.0021", "  la1: 100"), "");
  EXPECT_NE(with("fixed: [xa1,", "fixed: [xq1,").find("fixed[0]: unknown parameter 'xq1'"), std::string::npos);
  EXPECT_NE(with("  iterations: 12", "  iterations: many").find("diagnostics.iterations"), std::string::npos);
  EXPECT_NE(with("  converged: true", "  converged: 3").find("diagnostics.converged: expected true or false"),
            std::string::npos);
  EXPECT_NE(with("fixed: [xa1, ya1, xa2, ya2]", "fixed: xa1").find("fixed: expected a list"), std::string::npos);
  // Keys another version may add are kept, not refused.
  EXPECT_EQ(with("  seconds: 0.25", "  seconds: 0.25\n  threads: 2"), "");
}

TEST(RobotYaml, SigmaBeyondItsBoundIsWrittenAsNotDetermined) {
  // A computed 1-sigma the reader would refuse (a rank-deficient fit's 1e6
  // mm) is written .nan, so every written result reads back.
  Robot r = parse_robot(result_text(), "result.yaml");
  r.calibration->sigma[kLa1] = 1e6;
  r.calibration->sigma[kDth1] = std::numeric_limits<double>::infinity();
  const Robot back = parse_robot(robot_to_yaml(r), "again.yaml");
  EXPECT_TRUE(std::isnan(*back.calibration->sigma[kLa1]));
  EXPECT_TRUE(std::isnan(*back.calibration->sigma[kDth1]));
  EXPECT_EQ(sigma_for_file(0.5, kDth1), 0.5);
  EXPECT_TRUE(std::isnan(sigma_for_file(1.5, kDth1)));
  EXPECT_EQ(sigma_for_file(1.5, kLa1), 1.5);
}

TEST(RobotYaml, UnknownKeySuggestsNearest) {
  std::string t = nominal_text();
  t.replace(t.find("xa3:"), 4, "xb3:");
  EXPECT_EQ(error_of(t), "robot.yaml:7: geometry.xb3: unknown parameter (did you mean xa3?)");
  EXPECT_NE(error_of("nmae: x\n" + t.substr(t.find("geometry"))).find("did you mean name?"),
            std::string::npos);
}

TEST(RobotYaml, MissingKey) {
  std::string t = nominal_text();
  t.erase(t.find("  la2:"), t.find('\n', t.find("  la2:")) - t.find("  la2:") + 1);
  EXPECT_NE(error_of(t).find("missing key 'la2'"), std::string::npos) << error_of(t);
  EXPECT_NE(error_of("name: x\n").find("missing key 'geometry'"), std::string::npos);
}

TEST(RobotYaml, NonNumericAndNonFinite) {
  std::string t = nominal_text();
  std::string u = t;
  t.replace(t.find("la2: 244"), 8, "la2: abc");
  EXPECT_NE(error_of(t).find("geometry.la2: 'abc' is not a number"), std::string::npos) << error_of(t);
  u.replace(u.find("la2: 244"), 8, "la2: .inf");
  EXPECT_NE(error_of(u).find("geometry.la2: value must be a finite number"), std::string::npos);
}

TEST(RobotYaml, NonPositiveLength) {
  std::string t = nominal_text();
  t.replace(t.find("lb1: 244"), 8, "lb1: -3");
  EXPECT_NE(error_of(t).find("geometry.lb1: link length must be positive, got -3"),
            std::string::npos);
}

TEST(RobotYaml, HomeNotReachable) {
  std::string t = nominal_text();
  t.replace(t.find("la1: 244"), 8, "la1: 10");
  t.replace(t.find("lb1: 244"), 8, "lb1: 10");
  const std::string e = error_of(t);
  EXPECT_NE(e.find("home (216.5, 250) is not reachable"), std::string::npos) << e;
  EXPECT_NE(e.find("chain 1"), std::string::npos) << e;
}

TEST(RobotYaml, BadElbowAndLimits) {
  std::string t = nominal_text();
  t.replace(t.find("elbow: [ccw"), 11, "elbow: [up");
  EXPECT_NE(error_of(t).find("elbow[0]: 'up' is not ccw or cw"), std::string::npos) << error_of(t);
  std::string u = nominal_text();
  u.replace(u.find("min_direct: 0.15"), 16, "min_direct: 2");
  EXPECT_NE(error_of(u).find("limits.min_direct: must be in [0, 1)"), std::string::npos);
}

TEST(RobotYaml, SaveToUnwritablePathLeavesNothing) {
  EXPECT_THROW(save_robot(Robot{}, "/nonexistent-dir/r.yaml"), InputError);
}

}  // namespace
}  // namespace gpm
