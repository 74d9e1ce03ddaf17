// Tests of calib/excitation/pose_list.hpp: the pose list is a scenario whose
// sampling plan (sim/scenario.hpp, pattern list) reads back the same poses.
#include <gtest/gtest.h>

#include "calib/excitation/pose_list.hpp"
#include "sim/scenario.hpp"

namespace gpm::calib::excitation {
namespace {

TEST(PoseList, ScenarioLoaderReadsBackTheSamePoses) {
  const std::vector<Eigen::Vector2d> poses = {{216.5, 250.0}, {0.1 + 0.2, 1.0 / 3.0}, {300.125, 199.0}};
  const std::string text = pose_list_yaml(poses, "designed by a test\n\nsecond line");
  EXPECT_EQ(text.rfind("# designed by a test\n#\n# second line\nsampling:\n", 0), 0u) << text;
  const sim::Scenario s = sim::parse_scenario(text, "poses.yaml", ".");
  ASSERT_TRUE(s.sampling.has_value());
  EXPECT_EQ(s.sampling->pattern, sim::PosePattern::kList);
  ASSERT_EQ(s.sampling->poses.size(), poses.size());
  for (size_t k = 0; k < poses.size(); ++k) EXPECT_EQ(s.sampling->poses[k], poses[k]);  // bit-exact
}

}  // namespace
}  // namespace gpm::calib::excitation
