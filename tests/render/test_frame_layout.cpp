// Tests of render/frame_layout.cpp against hand-worked cases: the region
// that puts the mechanism right of the text column, the round scale-bar
// lengths, the pinhole scale of the top camera, and the error arrow's
// magnification.
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

// Issue 35: a 10 mm and a 10 um error both read. At 0.58 px/mm (640x480,
// the main job's framing) with a 120 px target: 120 / (10 x 0.58) = 20.7,
// so x20 (116 px); 120 / (0.01 x 0.58) = 20690, so x20000 (116 px).
TEST(FrameLayout, ErrorGainMakesBothAMillimetreAndAMicrometreErrorRead) {
  EXPECT_DOUBLE_EQ(error_gain(std::vector<double>(50, 10.0), 0.58, 120.0), 20.0);
  EXPECT_DOUBLE_EQ(error_gain(std::vector<double>(50, 0.01), 0.58, 120.0), 20000.0);
  for (const double e : {10.0, 1.0, 0.252, 0.01, 0.0093}) {
    const double px = e * error_gain(std::vector<double>(9, e), 0.58, 120.0) * 0.58;
    EXPECT_LE(px, 120.0 + 1e-9) << e;
    EXPECT_GT(px, 120.0 / 2.5 - 1e-9) << e << ": a 1-2-5 step loses at most 2.5x";
  }
  // 1, 2 or 5 x 10^k: 120 / (0.252 x 0.58) = 821 -> 500.
  EXPECT_DOUBLE_EQ(error_gain({0.252}, 0.58, 120.0), 500.0);
}

TEST(FrameLayout, ErrorGainLooksAtThe95thPercentileAndStaysInRange) {
  // 100 errors of 1 mm and 3 spikes of 50 mm: the 95th percentile is 1 mm.
  std::vector<double> e(100, 1.0);
  e.insert(e.end(), {50.0, 50.0, 50.0});
  EXPECT_DOUBLE_EQ(error_gain(e, 1.0, 100.0), 100.0);
  EXPECT_DOUBLE_EQ(error_gain({200.0}, 1.0, 100.0), 1.0) << "never below 1";
  EXPECT_DOUBLE_EQ(error_gain({1e-9}, 1.0, 100.0), 1e5) << "at most 1e5";
  EXPECT_DOUBLE_EQ(error_gain({0.0, 0.0}, 1.0, 100.0), 1.0) << "no error: no magnification";
  EXPECT_DOUBLE_EQ(error_gain({}, 1.0, 100.0), 1.0);
}

}  // namespace
}  // namespace gpm::render
