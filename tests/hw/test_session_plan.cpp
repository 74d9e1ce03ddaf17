// Tests of hw/session_plan.cpp: poses files and scenario plans.
#include <gtest/gtest.h>

#include "hw/session_plan.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

TEST(SessionPlan, PosesFile) {
  const auto dir = test::temp_dir("plan");
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
  const auto dir = test::temp_dir("plan2");
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
  const SessionPlan p = plan_from_scenario(kSrc + "/scenarios/simulate_disc.yaml");
  EXPECT_EQ(p.poses.size(), 30u);
  EXPECT_EQ(p.options.move_speed_mm_s, 150.0);
  for (const auto& x : p.poses) EXPECT_LE((x - Eigen::Vector2d(216.5, 250)).norm(), 60.0 + 1e-9);
}

}  // namespace
}  // namespace gpm::hw
