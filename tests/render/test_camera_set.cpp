// Tests of render/camera_set.cpp: camera names, errors and framing.
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/mjcf.hpp"
#include "render/camera_set.hpp"
#include "render_test_util.hpp"
#include "sim/mujoco_util.hpp"

namespace gpm::render {
namespace {

sim::ModelPtr model_with_camera() {
  std::string xml = mjcf_from_robot(Robot{});
  const std::string tag = "<worldbody>";
  xml.insert(xml.find(tag) + tag.size(), R"(<camera name="side" pos="0.2 -0.8 0.4" xyaxes="1 0 0 0 0.5 1"/>)");
  return sim::load_model_from_xml(xml);
}

TEST(CameraSet, NamesAreTheBuiltInsThenTheModels) {
  const sim::ModelPtr plain = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  EXPECT_EQ(camera_names(plain.get()), (std::vector<std::string>{"top", "oblique"}));
  const sim::ModelPtr m = model_with_camera();
  EXPECT_EQ(camera_names(m.get()), (std::vector<std::string>{"top", "oblique", "side"}));
}

TEST(CameraSet, UnknownCameraListsTheValidOnes) {
  const sim::ModelPtr m = model_with_camera();
  try {
    check_camera(m.get(), "front", "--camera");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--camera: unknown camera 'front' (valid: top, oblique, side)");
  }
  EXPECT_NO_THROW(check_camera(m.get(), "side", "--camera"));
  EXPECT_THROW(make_camera(m.get(), "Top", Framing{}, 1.0), InputError);
}

TEST(CameraSet, ModelCameraIsFixed) {
  const sim::ModelPtr m = model_with_camera();
  const mjvCamera c = make_camera(m.get(), "side", Framing{}, 1.0);
  EXPECT_EQ(c.type, mjCAMERA_FIXED);
  EXPECT_EQ(c.fixedcamid, 0);
}

// Every corner of the framed region projects inside the image, and the
// region touches the image edge on its tighter axis (no wasted zoom).
TEST(CameraSet, TopCameraFramesTheRegionExactly) {
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  Framing f;
  f.include({-100, 50});
  f.include({500, 350});
  for (const auto& [w, h] : {std::pair{640, 480}, std::pair{320, 480}}) {
    const mjvCamera c = make_camera(m.get(), "top", f, static_cast<double>(w) / h);
    EXPECT_EQ(c.type, mjCAMERA_FREE);
    EXPECT_DOUBLE_EQ(c.elevation, -90.0);
    EXPECT_NEAR(c.lookat[0], 0.2, 1e-12);
    EXPECT_NEAR(c.lookat[1], 0.2, 1e-12);
    double fill = 0.0;
    for (const double x : {f.lo.x(), f.hi.x()}) {
      for (const double y : {f.lo.y(), f.hi.y()}) {
        const Eigen::Vector2d px =
            testing::project_top(c, m->vis.global.fovy, w, h, {x * 1e-3, y * 1e-3, 0.0});
        EXPECT_GE(px.x(), -1e-6);
        EXPECT_LE(px.x(), w + 1e-6);
        EXPECT_GE(px.y(), -1e-6);
        EXPECT_LE(px.y(), h + 1e-6);
        fill = std::max({fill, std::abs(px.x() - 0.5 * w) / (0.5 * w), std::abs(px.y() - 0.5 * h) / (0.5 * h)});
      }
    }
    EXPECT_NEAR(fill, 1.0, 1e-9) << w << "x" << h;
  }
}

TEST(CameraSet, ObliqueLooksDownFromFurtherAway) {
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  Framing f;
  f.include({0, 0});
  f.include({400, 400});
  const mjvCamera top = make_camera(m.get(), "top", f, 4.0 / 3.0);
  const mjvCamera obl = make_camera(m.get(), "oblique", f, 4.0 / 3.0);
  EXPECT_GT(obl.elevation, -90.0);
  EXPECT_LT(obl.elevation, 0.0);
  EXPECT_GT(obl.distance, top.distance);
}

}  // namespace
}  // namespace gpm::render
