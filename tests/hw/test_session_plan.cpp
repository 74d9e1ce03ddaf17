// Tests of hw/procedures/session_plan.cpp: poses files and scenario plans.
#include <gtest/gtest.h>

#include "hw/procedures/session_plan.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

TEST(SessionPlan, PosesFile) {
  const test::TempDir dir("plan");
  test::write_text(dir / "p.yaml",
                   "poses: [[236.5, 260], [196.5, 240]]\nsampling: {move_speed_mm_s: 50, settle: "
                   "{hold_s: 0.3}}\n");
  const SessionPlan p = load_poses_plan((dir / "p.yaml").string());
  ASSERT_EQ(p.poses.size(), 2u);
  EXPECT_EQ(p.poses[1], Eigen::Vector2d(196.5, 240));
  EXPECT_EQ(p.options.move_speed_mm_s, 50.0);
  EXPECT_EQ(p.options.settle.hold_s, 0.3);
}

TEST(SessionPlan, BadPosesNameTheKey) {
  const test::TempDir dir("plan2");
  test::write_text(dir / "p.yaml", "poses: [[236.5, 260], [196.5]]\n");
  try {
    load_poses_plan((dir / "p.yaml").string());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("poses[1]: expected [x, y] in mm"), std::string::npos) << e.what();
  }
  test::write_text(dir / "q.yaml", "poses: [[236.5, 260]]\nsampling: {speed: 3}\n");
  EXPECT_THROW(load_poses_plan((dir / "q.yaml").string()), InputError);
}

TEST(SessionPlan, ScenarioPlan) {
  const SessionPlan p = plan_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml");
  EXPECT_EQ(p.poses.size(), 30u);
  EXPECT_EQ(p.options.move_speed_mm_s, 150.0);
  for (const auto& x : p.poses) EXPECT_LE((x - Eigen::Vector2d(216.5, 250)).norm(), 60.0 + 1e-9);
}

// A plan whose poses the procedure designs (the main job's trajectory) is
// not a stop-and-go session: refused, naming the file and the command that runs it.
TEST(SessionPlan, ADesignedPlanIsReferredToGpmRun) {
  try {
    plan_from_scenario(kSrc + "/scenarios/main.yaml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("main.yaml: sampling.pattern: trajectory"), std::string::npos) << what;
    EXPECT_NE(what.find("gpm run"), std::string::npos) << what;
  }
}

// Speeds and durations outside physical ranges are refused before anything
// moves (1e-300 mm/s once recorded at the wrong place, 1e9 s hung).
TEST(SessionPlan, SettingsOutsidePhysicalRangesAreRefused) {
  const test::TempDir dir("plan3");
  auto error_of = [&](const std::string& sampling) {
    test::write_text(dir / "p.yaml", "poses: [[236.5, 260]]\nsampling: " + sampling + "\n");
    try {
      load_poses_plan((dir / "p.yaml").string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("{move_speed_mm_s: 1e-300}").find("sampling.move_speed_mm_s"), std::string::npos);
  EXPECT_NE(error_of("{move_speed_mm_s: 1e9}").find("sampling.move_speed_mm_s: must be from 1 to 2000 mm/s"), std::string::npos);
  EXPECT_NE(error_of("{average_s: 1e9}").find("sampling.average_s"), std::string::npos);
  EXPECT_NE(error_of("{settle: {timeout_s: 1e9}}").find("sampling.settle.timeout_s"), std::string::npos);
  EXPECT_NE(error_of("{pattern: disc}").find("sampling.pattern"), std::string::npos);
  EXPECT_EQ(error_of("{move_speed_mm_s: 1000, average_s: 10, settle: {timeout_s: 60}}"), "");
  // The same bounds hold for a scenario's plan.
  test::write_text(dir / "s.yaml",
                   "name: s\nsampling: {pattern: circle, radius: 10, count: 3, average_s: 1e9}\n");
  EXPECT_THROW(plan_from_scenario((dir / "s.yaml").string()), InputError);
}

}  // namespace
}  // namespace gpm::hw
