// Tests of render/render_options.cpp: sizes, quality and the scenario's
// `render` section.
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"
#include "render/offscreen_context.hpp"
#include "render/render_options.hpp"

namespace gpm::render {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RenderOptions, ParsesSizes) {
  int w = 0, h = 0;
  parse_size("640x480", "--size", w, h);
  EXPECT_EQ(w, 640);
  EXPECT_EQ(h, 480);
  parse_size("4096X4096", "--size", w, h);
  EXPECT_EQ(w, 4096);
}

TEST(RenderOptions, BadSizesSayWhatIsWrong) {
  int w = 0, h = 0;
  EXPECT_EQ(error_of([&] { parse_size("0x480", "--size", w, h); }), "--size: size must be positive, got 0x480");
  EXPECT_EQ(error_of([&] { parse_size("-640x480", "--size", w, h); }), "--size: size must be positive, got -640x480");
  EXPECT_EQ(error_of([&] { parse_size("4098x480", "--size", w, h); }),
            "--size: size 4098x480 is beyond the off-screen buffer (maximum 4096x4096)");
  EXPECT_EQ(kMaxFrameSide, 4096);
  EXPECT_NE(error_of([&] { parse_size("641x480", "--size", w, h); }).find("must be even"), std::string::npos);
  EXPECT_NE(error_of([&] { parse_size("640", "--size", w, h); }).find("WxH"), std::string::npos);
  EXPECT_NE(error_of([&] { parse_size("640x48a", "--size", w, h); }).find("WxH"), std::string::npos);
  EXPECT_EQ(w, 0) << "a failed parse leaves the outputs alone";
}

TEST(RenderOptions, Quality) {
  EXPECT_EQ(parse_quality("fast", "q"), Quality::kFast);
  EXPECT_EQ(parse_quality("high", "q"), Quality::kHigh);
  EXPECT_EQ(error_of([] { parse_quality("ultra", "--quality"); }),
            "--quality: quality must be fast or high, got 'ultra'");
  EXPECT_EQ(quality_name(Quality::kHigh), "high");
}

TEST(RenderOptions, DefaultsWithoutASection) {
  const RenderOptions o = render_options_from_yaml(load_yaml_string("name: x\n", "s.yaml"), "s.yaml");
  EXPECT_EQ(o.width, 640);
  EXPECT_EQ(o.height, 480);
  EXPECT_EQ(o.fps, 30.0);
  EXPECT_EQ(o.camera, "top");
  EXPECT_EQ(o.quality, Quality::kFast);
  EXPECT_EQ(o.speed, 1.0);
}

TEST(RenderOptions, ReadsTheSection) {
  const std::string text =
      "name: x\nrender:\n  size: 320x240\n  fps: 25\n  camera: oblique\n  quality: high\n  speed: 0.5\n";
  const RenderOptions o = render_options_from_yaml(load_yaml_string(text, "s.yaml"), "s.yaml");
  EXPECT_EQ(o.width, 320);
  EXPECT_EQ(o.height, 240);
  EXPECT_EQ(o.fps, 25.0);
  EXPECT_EQ(o.camera, "oblique");
  EXPECT_EQ(o.quality, Quality::kHigh);
  EXPECT_EQ(o.speed, 0.5);
  const RenderOptions l = render_options_from_yaml(load_yaml_string("render: {size: [160, 120]}\n", "s.yaml"), "s.yaml");
  EXPECT_EQ(l.width, 160);
  EXPECT_EQ(l.height, 120);
}

TEST(RenderOptions, SectionErrorsNameFileLineAndKey) {
  auto err = [](const std::string& text) {
    return error_of([&] { render_options_from_yaml(load_yaml_string(text, "s.yaml"), "s.yaml"); });
  };
  EXPECT_EQ(err("name: x\nrender:\n  size: 0x10\n"), "s.yaml:3: render.size: size must be positive, got 0x10");
  EXPECT_NE(err("render: {fps: -3}\n").find("render.fps: must be positive"), std::string::npos);
  EXPECT_NE(err("render: {quality: best}\n").find("render.quality: quality must be fast or high"), std::string::npos);
  EXPECT_NE(err("render: {camra: top}\n").find("camera"), std::string::npos);  // did-you-mean
  EXPECT_NE(err("render: {size: 9000x10}\n").find("maximum 4096x4096"), std::string::npos);
}

}  // namespace
}  // namespace gpm::render
