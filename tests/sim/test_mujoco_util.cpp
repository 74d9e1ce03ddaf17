// Tests of sim/mujoco_util.cpp: models load from text through the virtual
// file system, and MuJoCo's complaints become SimError instead of stdin waits.
#include "sim/mujoco_util.hpp"

#include <gtest/gtest.h>

namespace gpm::sim {
namespace {

const char* kPendulum = R"(<mujoco><worldbody><body name="b"><joint name="j" type="hinge"/>
  <geom type="sphere" size="0.1" mass="1"/></body></worldbody></mujoco>)";

TEST(MujocoUtil, LoadsModelFromText) {
  const ModelPtr m = load_model_from_xml(kPendulum);
  ASSERT_TRUE(m);
  EXPECT_EQ(m->nq, 1);
  EXPECT_EQ(require_id(m.get(), mjOBJ_JOINT, "j"), 0);
}

TEST(MujocoUtil, BadXmlThrowsWithMujocoMessage) {
  try {
    load_model_from_xml("<mujoco><worldbody><body><joint type=\"nonsense\"/></body></worldbody></mujoco>");
    FAIL() << "expected SimError";
  } catch (const SimError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot compile"), std::string::npos) << e.what();
  }
}

TEST(MujocoUtil, MissingNameThrows) {
  const ModelPtr m = load_model_from_xml(kPendulum);
  EXPECT_THROW(require_id(m.get(), mjOBJ_SITE, "ee"), SimError);
}

TEST(MujocoUtil, MujocoErrorsThrowInsteadOfExiting) {
  install_mujoco_handlers();
  EXPECT_THROW(mju_error("provoked"), SimError);
}

}  // namespace
}  // namespace gpm::sim
