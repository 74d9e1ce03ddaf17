// Tests of render/overlay_painter.cpp: decimated path and trace, geoms
// within the scene's capacity, chain colours, the magnified error arrow,
// and the text (clock from the part's start, distances in um / mm).
#include <set>

#include <gtest/gtest.h>

#include "models/mjcf.hpp"
#include "render/overlay_painter.hpp"
#include "render_test_util.hpp"
#include "sim/mujoco_util.hpp"

namespace gpm::render {
namespace {

sim::TrajectoryLog straight_log(int rows, double length_mm) {
  sim::TrajectoryLog log;
  for (int k = 0; k < rows; ++k) {
    sim::LogRow r;
    r.t = 0.001 * k;
    r.desired = Eigen::Vector2d(216.5 + length_mm * k / (rows - 1), 250.0);
    r.actual = r.desired + Eigen::Vector2d(0.0, 0.01);
    log.rows.push_back(r);
  }
  return log;
}

struct Scene {
  mjvScene scn;
  explicit Scene(const mjModel* m, int maxgeom) {
    mjv_defaultScene(&scn);
    mjv_makeScene(m, &scn, maxgeom);
  }
  ~Scene() { mjv_freeScene(&scn); }
  int count(const std::array<float, 4>& rgba) const {
    int n = 0;
    for (int i = 0; i < scn.ngeom; ++i)
      n += std::equal(rgba.begin(), rgba.end(), scn.geoms[i].rgba) ? 1 : 0;
    return n;
  }
};

TEST(OverlayPainter, PathIsThinnedToTheSpacingWithBothEndsKept) {
  const sim::TrajectoryLog log = straight_log(1001, 100.0);  // 0.1 mm per row
  const OverlayPainter p(Robot{}, log, 1.95, 3.0, 2.0);
  const auto& pts = p.desired_points();
  ASSERT_GE(pts.size(), 2u);
  EXPECT_EQ(pts.front(), log.rows.front().desired);
  EXPECT_EQ(pts.back(), log.rows.back().desired);
  for (size_t k = 1; k + 1 < pts.size(); ++k) EXPECT_GE((pts[k] - pts[k - 1]).norm(), 1.95);
  EXPECT_NEAR(static_cast<double>(pts.size()), 51.0, 1.0);
  EXPECT_NEAR(static_cast<double>(p.trace_points()), 51.0, 1.0);
}

TEST(OverlayPainter, TraceGrowsWithTimeAndMarkerSitsAtTheTruePosition) {
  const sim::TrajectoryLog log = straight_log(1001, 100.0);
  const OverlayPainter p(Robot{}, log, 1.95, 3.0, 2.0);
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  Scene early(m.get(), p.max_geoms()), late(m.get(), p.max_geoms());
  p.add_geoms(&early.scn, 0.25, log.rows[250]);
  p.add_geoms(&late.scn, 0.75, log.rows[750]);
  EXPECT_EQ(early.count(OverlayStyle::kDesiredRgba), 50);
  EXPECT_EQ(late.count(OverlayStyle::kDesiredRgba), 50);
  EXPECT_NEAR(early.count(OverlayStyle::kTraceRgba), 13, 1);
  EXPECT_NEAR(late.count(OverlayStyle::kTraceRgba), 38, 1);
  ASSERT_EQ(late.count(OverlayStyle::kMarkerRgba), 1);
  const mjvGeom& mk = late.scn.geoms[late.scn.ngeom - 1];
  EXPECT_NEAR(mk.pos[0], log.rows[750].actual.x() * 1e-3, 1e-6);
  EXPECT_NEAR(mk.pos[1], log.rows[750].actual.y() * 1e-3, 1e-6);
  EXPECT_NEAR(mk.pos[2] + mk.size[2], OverlayStyle::kMarkerTopZ_m, 1e-6);
  EXPECT_NEAR(mk.size[0], 3e-3, 1e-9);
  EXPECT_LE(late.scn.ngeom, p.max_geoms());
}

TEST(OverlayPainter, NeverOverflowsTheScene) {
  const sim::TrajectoryLog log = straight_log(1001, 100.0);
  const OverlayPainter p(Robot{}, log, 1.95, 3.0, 2.0);
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  Scene small(m.get(), 10);
  p.add_geoms(&small.scn, 1.0, log.rows.back());
  EXPECT_EQ(small.scn.ngeom, 10);
}

TEST(OverlayPainter, LongRunsAreCappedInGeoms) {
  const sim::TrajectoryLog log = straight_log(20001, 20000.0);  // 1 mm per row
  const OverlayPainter p(Robot{}, log, 0.5, 3.0, 2.0);
  EXPECT_LE(p.desired_points().size(), 1501u);
  EXPECT_LE(p.max_geoms(), 3100);
}

TEST(OverlayPainter, ChainsGetDistinctColours) {
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  OverlayPainter::paint_model(m.get());
  std::set<std::array<float, 3>> colours;
  for (int i = 1; i <= 3; ++i) {
    for (const char* kind : {"geom_a", "geom_b"}) {
      const int g = mj_name2id(m.get(), mjOBJ_GEOM, (kind + std::to_string(i)).c_str());
      colours.insert({m->geom_rgba[4 * g], m->geom_rgba[4 * g + 1], m->geom_rgba[4 * g + 2]});
    }
    const int ga = mj_name2id(m.get(), mjOBJ_GEOM, ("geom_a" + std::to_string(i)).c_str());
    EXPECT_EQ(m->geom_rgba[4 * ga], OverlayStyle::kChainRgb[static_cast<size_t>(i - 1)][0]);
  }
  EXPECT_EQ(colours.size(), 6u);
}

TEST(OverlayPainter, TextShowsTheClockFromThePartsStartTheErrorAndReadings) {
  sim::LogRow r;
  r.t = 16.795;
  r.desired = {100.0, 200.0};
  r.actual = {100.003, 200.004};  // 5 um away
  r.readings = {1.1, 3.2, 4.75};
  const auto t = OverlayPainter::text(r, 15.545, 2000.0);
  EXPECT_EQ(t[0], "time\nerror\narrow\nenc 1\nenc 2\nenc 3");
  EXPECT_EQ(t[1], "1.250 s\n5.00 um\nx2000\n1.10000 rad\n3.20000 rad\n4.75000 rad");
  r.actual = {100.0, 212.0768};  // the "error 12076.8 um"
  EXPECT_EQ(OverlayPainter::text(r, 16.795)[1], "0.000 s\n12.1 mm\nnone\n1.10000 rad\n3.20000 rad\n4.75000 rad");
}

// 3 significant digits; um below 1 mm (rounding included), mm from there on.
TEST(OverlayPainter, DistancesHaveThreeSignificantDigitsAndTheirUnit) {
  EXPECT_EQ(distance_text(0.00926), "9.26 um");
  EXPECT_EQ(distance_text(0.0099), "9.90 um");
  EXPECT_EQ(distance_text(0.2524), "252 um");
  EXPECT_EQ(distance_text(0.9994), "999 um");
  EXPECT_EQ(distance_text(0.9996), "1.00 mm");
  EXPECT_EQ(distance_text(9.68), "9.68 mm");
  EXPECT_EQ(distance_text(12.0768), "12.1 mm");
  EXPECT_EQ(distance_text(0.0), "0 um");
  EXPECT_EQ(distance_text(1.28e-5), "0.0128 um");
  EXPECT_EQ(distance_text(2.8e-14), "< 0.001 um") << "the sampling's first row: no 12-decimal noise";
  EXPECT_EQ(distance_text(std::nan("")), "-");
}

// The arrow: three cyan lines (shaft and two barbs); the shaft runs from the
// desired point to desired + gain x (actual - desired); no arrow at gain 0.
TEST(OverlayPainter, ErrorArrowIsTheErrorVectorTimesTheGain) {
  const sim::TrajectoryLog log = straight_log(101, 10.0);  // actual 10 um above desired
  const OverlayPainter p(Robot{}, log, 1.0, 3.0, 2.0, ErrorArrow{1000.0, 2.0});
  const sim::ModelPtr m = sim::load_model_from_xml(mjcf_from_robot(Robot{}));
  Scene s(m.get(), p.max_geoms());
  const sim::LogRow& row = log.rows[50];
  p.add_geoms(&s.scn, row.t, row);
  ASSERT_EQ(s.count(OverlayStyle::kErrorRgba), 3);
  const mjvGeom* shaft = nullptr;
  for (int i = 0; i < s.scn.ngeom && !shaft; ++i)
    if (std::equal(OverlayStyle::kErrorRgba.begin(), OverlayStyle::kErrorRgba.end(), s.scn.geoms[i].rgba))
      shaft = &s.scn.geoms[i];
  // A line connector (mjv_makeConnector): from pos, along the frame's z axis, size[2] long (m).
  EXPECT_NEAR(shaft->pos[0], row.desired.x() * 1e-3, 1e-6);
  EXPECT_NEAR(shaft->pos[1], row.desired.y() * 1e-3, 1e-6);
  EXPECT_NEAR(shaft->pos[2], OverlayStyle::kErrorZ_m, 1e-6);
  EXPECT_NEAR(shaft->size[2], 10.0 * 1e-3, 1e-6) << "10 um x 1000 = 10 mm";
  EXPECT_NEAR(shaft->mat[5], 1.0, 1e-6) << "upwards (+y), as the error";
  EXPECT_EQ(s.count(OverlayStyle::kMarkerRgba), 1);
  EXPECT_TRUE(std::equal(OverlayStyle::kMarkerRgba.begin(), OverlayStyle::kMarkerRgba.end(),
                         s.scn.geoms[s.scn.ngeom - 1].rgba)) << "the marker stays the last geom";
  const OverlayPainter none(Robot{}, log, 1.0, 3.0, 2.0);
  Scene s0(m.get(), none.max_geoms());
  none.add_geoms(&s0.scn, row.t, row);
  EXPECT_EQ(s0.count(OverlayStyle::kErrorRgba), 0);
}

}  // namespace
}  // namespace gpm::render
