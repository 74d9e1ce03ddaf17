// Tests of report/zero_report.cpp: gpm zero's table (one row per run, the
// error against the twin's offsets) and the spread of the main method's runs.
#include "report/zero_report.hpp"

#include <gtest/gtest.h>

namespace gpm::report {
namespace {

// Two grid runs from --start points, a direct run and a stopped section-3 run on a twin.
ZeroReport twin_session() {
  ZeroReport z{"twin.yaml", "MuJoCo twin", "grid", 30.0, 24, 1, Eigen::Vector3d(0.012, -0.008, 0.006), {}};
  z.runs.push_back({"start 1", "grid", Eigen::Vector2d(219.5, 252.5), Eigen::Vector3d(0.01, 0, 0),
                    Eigen::Vector3d(0.0121, -0.008, 0.006), 40, 12, 100.0, 3.0, true, ""});
  z.runs.push_back({"start 2", "grid", Eigen::Vector2d(213, 247.5), Eigen::Vector3d::Constant(NAN),
                    Eigen::Vector3d(0.0119, -0.0081, 0.006), 42, 13, 101.0, 3.1, true, ""});
  z.runs.push_back({"other method", "direct", std::nullopt, Eigen::Vector3d::Constant(NAN),
                    Eigen::Vector3d(0.012, -0.008, 0.006), 20, 6, 50.0, 1.5, true, ""});
  ZeroRun stopped;
  stopped.label = "section 3";
  stopped.method = "lm ml (offsets only)";
  stopped.error = "LM did not converge";
  z.runs.push_back(stopped);
  return z;
}

TEST(ZeroReport, OneRowPerRunWithItsErrorAgainstTheTwin) {
  const std::string md = zero_report(twin_session()).markdown();
  EXPECT_NE(md.find("Hardware: twin.yaml (MuJoCo twin). Circle radius 30 mm, 24 interpolation points, joint 1"),
            std::string::npos);
  EXPECT_NE(md.find("Actual offsets of the twin: 0.01200, -0.00800, 0.00600 rad."), std::string::npos);
  EXPECT_NE(md.find("| start 1 | grid | 219.50, 252.50 | 0.01000, 0.00000, 0.00000 | 0.01210, -0.00800, 0.00600 | "
                    "100 | 40 | 12 | 100.0 | 3.0 |"),
            std::string::npos);
  EXPECT_NE(md.find("| start 2 | grid | 213.00, 247.50 | - |"), std::string::npos);
  EXPECT_NE(md.find("| other method | direct | as found |"), std::string::npos);
  EXPECT_NE(md.find("| section 3 | lm ml (offsets only) | as found | - | stopped: LM did not converge | unknown |"),
            std::string::npos);
}

TEST(ZeroReport, SpreadOfTheMainMethodsRunsFromAStart) {
  const std::string md = zero_report(twin_session()).markdown();
  EXPECT_NE(md.find("Spread of the 2 grid runs (max - min per joint): 0.00020, 0.00010, 0.00000 rad."),
            std::string::npos);
  ZeroReport one = twin_session();
  one.runs.erase(one.runs.begin());
  one.actual.reset();
  const std::string md1 = zero_report(one).markdown();
  EXPECT_EQ(md1.find("Spread"), std::string::npos);
  EXPECT_EQ(md1.find("Actual offsets"), std::string::npos);
}

}  // namespace
}  // namespace gpm::report
