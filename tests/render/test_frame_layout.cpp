// Tests of render/frame_layout.cpp against hand-worked cases: the region
// that puts the mechanism right of the text column, the round scale-bar
// lengths, and the pinhole scale of the top camera.
#include "render/frame_layout.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace gpm::render {
namespace {

TEST(FrameLayout, RegionBesideTheColumn) {
  // A 100 x 100 mm region in a 400 x 200 px panel, column 100 px, pad 10:
  // free area 280 x 180 px, so 1.8 px/mm (height bound); the region is
  // 180 px wide, centred in x 110..390: left edge at 110 + 50 = 160 px.
  Framing f;
  f.include({0, 0});
  f.include({100, 100});
  const Framing g = frame_beside_column(f, 400, 200, 100, 10);
  const double s = 1.8;
  EXPECT_NEAR(g.hi.x() - g.lo.x(), 400 / s, 1e-9);  // the panel's aspect, at 1.8 px/mm
  EXPECT_NEAR(g.hi.y() - g.lo.y(), 200 / s, 1e-9);
  EXPECT_NEAR((0.0 - g.lo.x()) * s, 160.0, 1e-9);  // where the region's left edge lands
  EXPECT_NEAR((0.0 - g.lo.y()) * s, 10.0, 1e-9);   // bottom: pad (height bound)
  EXPECT_NEAR((g.hi.y() - 100.0) * s, 10.0, 1e-9);
  // Width bound: a wide region (400 x 50 mm) fills the 280 px: 0.7 px/mm,
  // left edge at column + pad.
  Framing w;
  w.include({0, 0});
  w.include({400, 50});
  const Framing h = frame_beside_column(w, 400, 200, 100, 10);
  EXPECT_NEAR((h.hi.x() - h.lo.x()) * 0.7, 400.0, 1e-9);
  EXPECT_NEAR((0.0 - h.lo.x()) * 0.7, 110.0, 1e-9);
}

TEST(FrameLayout, ScaleBarIsTheLongestRoundLengthThatFits) {
  EXPECT_DOUBLE_EQ(scale_bar_mm(1.0, 120), 100.0);   // 120 mm fit: 100
  EXPECT_DOUBLE_EQ(scale_bar_mm(1.0, 99), 50.0);
  EXPECT_DOUBLE_EQ(scale_bar_mm(0.55, 120), 200.0);  // 218 mm fit: 200
  EXPECT_DOUBLE_EQ(scale_bar_mm(2.0, 30), 10.0);     // 15 mm: 10
  EXPECT_DOUBLE_EQ(scale_bar_mm(1.0, 100), 100.0);   // exactly fits
  EXPECT_DOUBLE_EQ(scale_bar_mm(100.0, 50), 0.5);
  EXPECT_DOUBLE_EQ(scale_bar_mm(1000.0, 50), 0.0) << "below 0.1 mm: no bar";
  EXPECT_DOUBLE_EQ(scale_bar_mm(0.0, 50), 0.0);
}

TEST(FrameLayout, TopCameraScale) {
  // fovy 90 deg: focal length = half the height (240 px); 1 m away: 0.24 px/mm.
  EXPECT_NEAR(top_px_per_mm(1.0, 0.0, 90.0, 480), 0.24, 1e-12);
  // 0.2 m above the plane is 0.8 m from the camera: 0.3 px/mm.
  EXPECT_NEAR(top_px_per_mm(1.0, 0.2, 90.0, 480), 0.3, 1e-12);
}

}  // namespace
}  // namespace gpm::render
