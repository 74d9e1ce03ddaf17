// Tests of calib/result_yaml.cpp: write then read returns the same numbers to
// the last bit (geometry, std, fixed, diagnostics), NaN/inf survive, the file
// has the docs/FORMATS.md keys, bad files are one-line InputErrors, and a result
// serves as a robot model.
#include "calib/result_yaml.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "calib/paper_values.hpp"
#include "models/errors.hpp"

namespace gpm::calib {
namespace {

Result sample_result() {
  Result r;
  r.geometry = table5_actual();
  r.geometry[kLa1] = 244.1 + 1.0 / 3.0;
  r.free = default_free_mask();
  r.sigma.fill(std::numeric_limits<double>::quiet_NaN());
  for (int i = 0; i < kNumParams; ++i)
    if (r.free.test(static_cast<size_t>(i))) r.sigma[static_cast<size_t>(i)] = 1e-3 / (i + 1.0);
  r.sigma[kLb2] = std::numeric_limits<double>::quiet_NaN();
  r.method = "lm";
  r.cost = Cost::kJ3;
  r.final_cost = 3.0e-20 / 7.0;
  r.iterations = 21;
  r.evaluations = 37;
  r.rank = 11;
  r.condition_number = 6072.0627;
  r.kmrmse_mm = 1.0 / 7.0;
  r.seconds = 0.0123;
  r.notes = {"poorly exciting samples: \"quoted\" and a colon: here"};
  return r;
}

TEST(ResultYaml, RoundTripIsExact) {
  const Result r = sample_result();
  const std::string text = result_to_yaml(r, "GPM2002");
  const Result b = parse_result(text, "mem.yaml");
  EXPECT_EQ(b.geometry, r.geometry);
  EXPECT_EQ(b.free, r.free);
  for (int i = 0; i < kNumParams; ++i) {
    const double x = r.sigma[static_cast<size_t>(i)], y = b.sigma[static_cast<size_t>(i)];
    if (std::isnan(x)) EXPECT_TRUE(std::isnan(y)) << param_name(i);
    else EXPECT_EQ(x, y) << param_name(i);
  }
  EXPECT_EQ(b.method, "lm");
  EXPECT_EQ(b.cost, Cost::kJ3);
  EXPECT_EQ(b.final_cost, r.final_cost);
  EXPECT_EQ(b.iterations, 21);
  EXPECT_EQ(b.evaluations, 37);
  EXPECT_EQ(b.rank, 11);
  EXPECT_EQ(b.condition_number, r.condition_number);
  ASSERT_TRUE(b.kmrmse_mm.has_value());
  EXPECT_EQ(*b.kmrmse_mm, *r.kmrmse_mm);
  EXPECT_EQ(b.notes, r.notes);
  for (const char* key : {"geometry:", "std:", "fixed: [xa1, ya1, xa2, ya2]", "diagnostics:", "  cost: ",
                          "  iterations: ", "  evaluations: ", "  rank: ", "  condition_number: ", "  kmrmse_mm: "})
    EXPECT_NE(text.find(key), std::string::npos) << key;
}

TEST(ResultYaml, AParameterWithoutA1SigmaIsLeftOutOfStd) {
  // Issue 36.5: "std: {lb2: .nan}" became {"lb2": null} in --json, which no
  // robot reader took. The parameter is left out; a null still reads as NaN.
  const std::string text = result_to_yaml(sample_result(), "GPM2002");
  EXPECT_EQ(text.find("lb2: .nan"), std::string::npos) << text;
  EXPECT_NE(text.find("  lb1: "), std::string::npos);
  EXPECT_TRUE(std::isnan(parse_result(text, "r.yaml").sigma[kLb2]));
  std::string json_like = text;
  json_like.replace(json_like.find("  cost: "), 8, "  cost: null #");
  EXPECT_TRUE(std::isnan(parse_result(json_like, "r.json").final_cost));
}

TEST(ResultYaml, ACalibratedGeometryThatIsNoRobotFailsTheRunNotTheInput) {
  Robot base;
  Geometry g = table5_actual();
  EXPECT_EQ(usable_robot(base, g).geometry, g);
  g[kLa2] = 1.45e-10;  // what constant theta_m1 readings calibrated to (issue 36.5)
  try {
    usable_robot(base, g);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    FAIL() << "an input error: " << e.what();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not a usable robot"), std::string::npos) << e.what();
  }
}

TEST(ResultYaml, SaveIsAtomicAndLoadsAsARobot) {
  const auto dir = std::filesystem::temp_directory_path() / "gpm_test_result_yaml";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "r.yaml").string();
  save_result(sample_result(), "GPM2002", path);
  const Robot base;
  const Robot r = robot_from_result(path, base);
  EXPECT_EQ(r.geometry, sample_result().geometry);
  EXPECT_EQ(r.home, base.home);
  EXPECT_THROW(save_result(sample_result(), "GPM2002", (dir / "no" / "r.yaml").string()), InputError);
  EXPECT_FALSE(std::filesystem::exists(dir / "no"));
  std::filesystem::remove_all(dir);
}

TEST(ResultYaml, BadFilesAreOneLineInputErrors) {
  std::string text = result_to_yaml(sample_result(), "GPM2002");
  const auto bad = [](const std::string& t) {
    try {
      parse_result(t, "bad.yaml");
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  std::string t1 = text;
  t1.replace(t1.find("fixed: [xa1"), 11, "fixed: [xq1");
  EXPECT_NE(bad(t1).find("unknown parameter 'xq1'"), std::string::npos);
  std::string t2 = text;
  t2.replace(t2.find("  la3: "), 7, "  la3: x");
  EXPECT_NE(bad(t2).find("la3"), std::string::npos);
  std::string t3 = text;
  t3.replace(t3.find("  cost_function: j3"), 19, "  cost_function: j9");
  EXPECT_NE(bad(t3).find("j9"), std::string::npos);
  EXPECT_THROW(load_result("/nonexistent/r.yaml"), InputError);
}

}  // namespace
}  // namespace gpm::calib
