// Tests of render/scene_renderer.cpp: frames that show the mechanism, the
// end-effector marker where the camera's projection of the true position
// says, chains in their colours, reproducible frames, side-by-side panels,
// the text column with the legend and the scale bar clear of the mechanism,
// and bad input.
#include <set>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "render/mechanism_pose.hpp"
#include "render/overlay_painter.hpp"
#include "render/scene_renderer.hpp"
#include "render_test_util.hpp"

namespace gpm::render {
namespace {

using testing::kCircleScenario;
using testing::kLineScenario;
using testing::run_of;

RenderOptions small(int w = 240, int h = 180) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  return o;
}

Eigen::Vector3d marker_point(const sim::LogRow& row) {
  return {row.actual.x() * 1e-3, row.actual.y() * 1e-3, OverlayStyle::kMarkerTopZ_m};
}

TEST(SceneRenderer, FrameIsNotBlank) {
  const auto& r = run_of(kCircleScenario);
  SceneRenderer sr({run_view(r, "circle")}, small());
  const FrameImage& f = sr.render(0.5);
  ASSERT_EQ(f.width, 240);
  ASSERT_EQ(f.height, 180);
  std::set<int> colours;
  long bright = 0;
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      const auto* p = f.at(x, y);
      colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
      bright += (p[0] + p[1] + p[2] > 300) ? 1 : 0;
    }
  EXPECT_GT(colours.size(), 50u);
  EXPECT_GT(bright, 200);
}

// The marker's centroid lies within 3 pixels of the pinhole projection of the
// true end-effector position, computed from the camera's lookat, distance and
// field of view alone, at several instants along the run.
// KNOWN FAILING (issue 6 open): at the small test sizes the marker disc is a few
// pixels under the text box and not pure magenta, so find_marker counts none.
TEST(SceneRenderer, MarkerIsWhereTheCameraProjectionOfTheTruePositionSays) {
  const auto& r = run_of(kCircleScenario);
  for (const auto& [w, h] : {std::pair{240, 180}, std::pair{320, 320}}) {
    SceneRenderer sr({run_view(r, "")}, small(w, h));
    const mjvCamera& cam = sr.camera(0);
    for (const double t : {0.0, 0.3, 0.55, 0.7, 10.0}) {
      const FrameImage& f = sr.render(t);
      const testing::Blob b = testing::find_marker(f);
      ASSERT_GT(b.pixels, 10) << "t " << t;
      const Eigen::Vector2d want = testing::project_top(cam, sr.fovy_deg(0), w, h, marker_point(row_at(r.log, t)));
      EXPECT_LT((b.centre - want).norm(), 3.0) << w << "x" << h << " t " << t << " got " << b.centre.transpose()
                                               << " want " << want.transpose();
    }
  }
}

// Where chain 1's active link is (its midpoint, projected), the pixel has
// chain 1's hue: red dominant.
TEST(SceneRenderer, ChainsAreDrawnInTheirColours) {
  const auto& r = run_of(kCircleScenario);
  SceneRenderer sr({run_view(r, "")}, small(320, 320));
  const double t = 0.2;
  const FrameImage& f = sr.render(t);
  const JointAngles q = pose_of(r.actual, row_at(r.log, t));
  const auto b = elbows(r.actual.geometry, q.theta_a);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d mid = 0.5 * (r.actual.geometry.A(i) + b[static_cast<size_t>(i)]);
    const Eigen::Vector2d px = testing::project_top(sr.camera(0), sr.fovy_deg(0), 320, 320,
                                                    {mid.x() * 1e-3, mid.y() * 1e-3, 0.012});
    const auto* p = f.at(static_cast<int>(px.x()), static_cast<int>(px.y()));
    const auto& c = OverlayStyle::kChainRgb[static_cast<size_t>(i)];
    const int want = static_cast<int>(std::max_element(c.begin(), c.end()) - c.begin());
    const int got = static_cast<int>(std::max_element(p, p + 3) - p);
    EXPECT_EQ(got, want) << "chain " << i + 1 << " pixel " << int(p[0]) << "," << int(p[1]) << "," << int(p[2]);
  }
}

TEST(SceneRenderer, SameRunRendersIdenticalFrames) {
  const auto& r = run_of(kLineScenario);
  std::vector<std::uint8_t> first;
  {
    SceneRenderer a({run_view(r, "line")}, small());
    first = a.render(0.2).rgb;
  }
  SceneRenderer b({run_view(r, "line")}, small());
  EXPECT_EQ(b.render(0.2).rgb, first);
  EXPECT_NE(b.render(0.05).rgb, first) << "another instant must differ";
}

// KNOWN FAILING (issue 6 open): at the small test sizes the marker disc is a few
// pixels under the text box and not pure magenta, so find_marker counts none.
// At 640x480 with the top camera the text, the legend and the scale bar sit
// in a column left of the mechanism: every base joint, elbow and the
// end-effector (with the base markers' radius, at the height of the marker)
// project right of it over the whole run; the legend's swatches have the
// traces' colours; the scale bar stands for a round length and its white run
// is as long as the pinhole projection of that length in the plane of the
// traces, computed from the camera alone.
TEST(SceneRenderer, LegendAndScaleBarInAColumnClearOfTheMechanism) {
  const auto& r = run_of(kCircleScenario);
  SceneRenderer sr({run_view(r, "caption")}, small(640, 480));
  const FrameImage& f = sr.render(0.3);
  const OverlayLayout l = sr.layout(0);
  ASSERT_GT(l.column, 60);
  ASSERT_LT(l.column, 0.4 * 640);
  const mjvCamera& cam = sr.camera(0);
  const double fovy = sr.fovy_deg(0);
  double leftmost = 1e9;
  for (const sim::LogRow& row : r.log.rows) {
    const JointAngles q = pose_of(r.actual, row);
    std::vector<Eigen::Vector2d> pts = {row.actual, row.desired};
    for (int i = 0; i < 3; ++i) pts.push_back(r.actual.geometry.A(i));
    for (const Eigen::Vector2d& b : elbows(r.actual.geometry, q.theta_a)) pts.push_back(b);
    for (const Eigen::Vector2d& p : pts) {
      const Eigen::Vector3d edge((p.x() - 22.0) * 1e-3, p.y() * 1e-3, OverlayStyle::kMarkerTopZ_m);
      leftmost = std::min(leftmost, testing::project_top(cam, fovy, 640, 480, edge).x());
    }
  }
  EXPECT_GT(leftmost, l.column) << "the mechanism reaches under the text column";

  // Legend swatches: flat colours (mjr_rectangle), the traces' RGB.
  const auto colour_at = [&f](int x, int y) {
    const std::uint8_t* p = f.at(x, y);
    return Eigen::Vector3d(p[0], p[1], p[2]);
  };
  const auto& d = OverlayStyle::kDesiredRgba;
  const auto& t = OverlayStyle::kTraceRgba;
  const int xs = (l.legend_x0 + l.legend_x1) / 2;
  EXPECT_LT((colour_at(xs, l.legend_rows[0]) - 255.0 * Eigen::Vector3d(d[0], d[1], d[2])).norm(), 3.0);
  EXPECT_LT((colour_at(xs, l.legend_rows[1]) - 255.0 * Eigen::Vector3d(t[0], t[1], t[2])).norm(), 3.0);
  EXPECT_LT(l.legend_x1, l.column);

  // Scale bar: a round length (1, 2 or 5 x 10^k mm) ...
  ASSERT_GT(l.scale_mm, 0.0);
  const double mantissa = l.scale_mm / std::pow(10.0, std::floor(std::log10(l.scale_mm) + 1e-9));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9)
      << l.scale_mm;
  // ... drawn as long as the camera projects it at the height of the traces.
  const Eigen::Vector3d c(cam.lookat[0], cam.lookat[1], OverlayStyle::kPathZ_m);
  const double want_px = (testing::project_top(cam, fovy, 640, 480, c + Eigen::Vector3d(l.scale_mm * 1e-3, 0, 0)) -
                          testing::project_top(cam, fovy, 640, 480, c)).norm();
  int white = 0;
  for (int x = 0; x < l.column; ++x) {
    const std::uint8_t* p = f.at(x, l.scale_y);
    white += (p[0] > 240 && p[1] > 240 && p[2] > 240) ? 1 : 0;
  }
  EXPECT_NEAR(white, want_px, 1.0);
  EXPECT_LT(l.scale_x + l.scale_len, l.column);
  EXPECT_GT(want_px, 0.3 * l.column) << "a bar long enough to read";
}

// Panels too narrow for a column keep the text over the scene.
TEST(SceneRenderer, NarrowPanelsKeepTheTextOverTheScene) {
  const auto& a = run_of(kCircleScenario);
  SceneRenderer sr({run_view(a, "a"), run_view(a, "b")}, small(320, 240));
  sr.render(0.1);
  EXPECT_EQ(sr.layout(0).column, 0);
  EXPECT_EQ(sr.layout(0).scale_mm, 0.0);
}

TEST(SceneRenderer, TwoRunsSideBySideEachWithItsMarker) {
  const auto& a = run_of(kCircleScenario);
  const auto& b = run_of(kLineScenario);
  SceneRenderer sr({run_view(a, "circle"), run_view(b, "line")}, small(320, 160));
  EXPECT_EQ(sr.viewport(0), (std::array<int, 4>{0, 0, 160, 160}));
  EXPECT_EQ(sr.viewport(1), (std::array<int, 4>{160, 0, 160, 160}));
  const double t = 0.3;
  const FrameImage& f = sr.render(t);
  for (size_t i = 0; i < 2; ++i) {
    const auto& run = i == 0 ? a : b;
    const testing::Blob blob = testing::find_marker(f, 160 * static_cast<int>(i), 160 * static_cast<int>(i + 1));
    ASSERT_GT(blob.pixels, 5);
    const Eigen::Vector2d want = testing::project_top(sr.camera(i), sr.fovy_deg(i), 160, 160,
                                                      marker_point(row_at(run.log, t))) +
                                 Eigen::Vector2d(160.0 * i, 0.0);
    EXPECT_LT((blob.centre - want).norm(), 3.0) << "panel " << i;
  }
  EXPECT_DOUBLE_EQ(sr.start_time(), std::min(a.log.rows.front().t, b.log.rows.front().t));
  EXPECT_DOUBLE_EQ(sr.end_time(), std::max(a.log.rows.back().t, b.log.rows.back().t));
}

TEST(SceneRenderer, HighQualityKeepsTheGeometry) {
  const auto& r = run_of(kCircleScenario);
  RenderOptions o = small();
  o.quality = Quality::kHigh;
  SceneRenderer hi({run_view(r, "")}, o);
  SceneRenderer lo({run_view(r, "")}, small());
  const FrameImage fh = hi.render(0.4);
  const FrameImage& fl = lo.render(0.4);
  EXPECT_NE(fh.rgb, fl.rgb);
  EXPECT_LT((testing::find_marker(fh).centre - testing::find_marker(fl).centre).norm(), 1.0);
}

// KNOWN FAILING (issue 6 open): at the small test sizes the marker disc is a few
// pixels under the text box and not pure magenta, so find_marker counts none.
TEST(SceneRenderer, ObliqueCameraShowsTheMarkerToo) {
  const auto& r = run_of(kCircleScenario);
  RenderOptions o = small();
  o.camera = "oblique";
  SceneRenderer sr({run_view(r, "")}, o);
  EXPECT_GT(testing::find_marker(sr.render(0.4)).pixels, 5);
}

TEST(SceneRenderer, BadInputIsAnInputError) {
  const auto& r = run_of(kLineScenario);
  RenderOptions o = small();
  o.camera = "nope";
  try {
    SceneRenderer sr({run_view(r, "")}, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "camera: unknown camera 'nope' (valid: top, oblique)");
  }
  EXPECT_THROW(SceneRenderer({run_view(r, "")}, small(0, 100)), InputError);
  EXPECT_THROW(SceneRenderer({run_view(r, "")}, small(5000, 100)), InputError);
  EXPECT_THROW(SceneRenderer({}, small()), InputError);
  sim::TrajectoryLog empty;
  RunView v = run_view(r, "empty");
  v.log = &empty;
  EXPECT_THROW(SceneRenderer({v}, small()), InputError);
  EXPECT_THROW(check_render_setup(r.model_xml, o, "--camera"), InputError);
  EXPECT_NO_THROW(check_render_setup(r.model_xml, small()));
}

}  // namespace
}  // namespace gpm::render
