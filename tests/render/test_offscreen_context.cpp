// Tests of render/offscreen_context.cpp: a headless GL context that renders.
#include <cstdlib>

#include <GL/osmesa.h>
#include <gtest/gtest.h>

#include "render/offscreen_context.hpp"

namespace gpm::render {
namespace {

TEST(OffscreenContext, RendersWithoutADisplay) {
  ASSERT_EQ(std::getenv("DISPLAY"), nullptr) << "the test must run with DISPLAY unset";
  OffscreenContext ctx;
  EXPECT_FALSE(ctx.renderer().empty());
  // Clear the (16x16) window buffer to a colour and read it back through GL.
  glClearColor(0.2f, 0.4f, 0.6f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glFinish();
  unsigned char px[4] = {};
  glReadPixels(3, 5, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
  EXPECT_NEAR(px[0], 51, 1);
  EXPECT_NEAR(px[1], 102, 1);
  EXPECT_NEAR(px[2], 153, 1);
}

TEST(OffscreenContext, RenderbuffersHoldTheLargestAcceptedFrame) {
  OffscreenContext ctx;
  EXPECT_GE(ctx.max_renderbuffer_size(), kMaxFrameSide);
}

TEST(OffscreenContext, TwoContextsSwitch) {
  OffscreenContext a;
  OffscreenContext b;
  a.make_current();
  EXPECT_EQ(OSMesaGetCurrentContext() != nullptr, true);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  b.make_current();
  glClearColor(0, 0, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  a.make_current();
  unsigned char px[4] = {};
  glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, px);
  EXPECT_EQ(px[0], 255);
  EXPECT_EQ(px[2], 0);
}

}  // namespace
}  // namespace gpm::render
