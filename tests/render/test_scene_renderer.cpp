// Tests of render/scene_renderer.cpp: frames that show the mechanism, the
// end-effector marker where the camera's projection of the true position
// says, chains in their colours, reproducible frames, side-by-side panels,
// the text column with the legend and the scale bar clear of the mechanism,
// the clock from the start of what is shown, the magnified error arrow,
// cards, and bad input.
#include <set>

#include <fmt/format.h>
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
  const auto& e = OverlayStyle::kErrorRgba;
  EXPECT_LT((colour_at(xs, l.legend_rows[2]) - 255.0 * Eigen::Vector3d(e[0], e[1], e[2])).norm(), 3.0);
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

// Issue 35: the clock reads the time since the start of what is shown. A run
// logged from 15.545 s shows "0.000 s" at its start, and frame for frame the
// same image as the same run logged from 0.
TEST(SceneRenderer, ClockStartsAtZeroWhereverTheLogStarts) {
  const auto& r = run_of(kLineScenario);
  const sim::TrajectoryLog late = testing::shifted(r.log, 15.545);
  const RunView v = run_view(r, "line");
  const RunView lv{"line", r.actual, r.model_xml, &late};
  SceneRenderer at0({v}, small(640, 480)), at15({lv}, small(640, 480));
  const double t0 = r.log.rows.front().t, span = r.log.rows.back().t - t0;
  ASSERT_NEAR(t0, 0.0, 1e-9);
  EXPECT_EQ(at15.text(0, 15.545)[1].substr(0, 8), "0.000 s\n");
  EXPECT_EQ(at15.text(0, 15.545 + span)[1].substr(0, 8), fmt::format("{:.3f} s\n", late.rows.back().t - 15.545));
  for (const double t : {0.0, 0.5 * span, span}) {
    EXPECT_EQ(at15.text(0, 15.545 + t), at0.text(0, t));
    const std::vector<std::uint8_t> want = at0.render(t).rgb;
    EXPECT_EQ(at15.render(15.545 + t).rgb, want) << "t = " << t;
  }
}

// Issue 35: the error arrow makes a 10 mm and a 10 um error both read: drawn
// from the desired point, gain x error long, at least 40 px at 640x480 in
// either case (the cyan pixels right of the text column, measured from the
// pinhole projection of the desired point), the gain stated in the text.
TEST(SceneRenderer, ErrorArrowReadsForAMillimetreAndAMicrometreError) {
  const auto& r = run_of(kCircleScenario);
  for (const double e_mm : {10.0, 0.01}) {
    sim::TrajectoryLog log = r.log;
    for (sim::LogRow& row : log.rows) row.actual = row.desired + Eigen::Vector2d(0.0, -e_mm);  // straight down
    SceneRenderer sr({RunView{"", r.actual, r.model_xml, &log}}, small(640, 480));
    const double t = 0.3;
    const FrameImage& f = sr.render(t);
    const OverlayLayout l = sr.layout(0);
    const double gain = sr.arrow_gain(0);
    const sim::LogRow& row = row_at(log, t);
    const Eigen::Vector2d from = testing::project_top(
        sr.camera(0), sr.fovy_deg(0), 640, 480,
        Eigen::Vector3d(row.desired.x() * 1e-3, row.desired.y() * 1e-3, OverlayStyle::kErrorZ_m));
    const Eigen::Vector2d to = testing::project_top(
        sr.camera(0), sr.fovy_deg(0), 640, 480,
        Eigen::Vector3d(row.desired.x() * 1e-3, (row.desired.y() - gain * e_mm) * 1e-3, OverlayStyle::kErrorZ_m));
    double reach = 0.0;
    int cyan = 0;
    for (int y = 0; y < f.height; ++y)
      for (int x = l.column; x < f.width; ++x) {
        const std::uint8_t* p = f.at(x, y);
        if (p[0] < 90 && p[1] > 170 && p[2] > 170) {
          ++cyan;
          reach = std::max(reach, (Eigen::Vector2d(x + 0.5, y + 0.5) - from).norm());
        }
      }
    EXPECT_GT(cyan, 30) << e_mm << " mm";
    EXPECT_NEAR(reach, (to - from).norm(), 3.0) << e_mm << " mm at x" << gain;
    EXPECT_GE(reach, 40.0) << e_mm << " mm at x" << gain;
    EXPECT_NE(sr.text(0, t)[1].find(fmt::format("\nx{:.0f}\n", gain)), std::string::npos) << sr.text(0, t)[1];
  }
}

// A card: the background colour over most of the frame, the title in its
// colour; no scene frame is so uniform.
TEST(SceneRenderer, CardsAreTextOnAPlainBackground) {
  const auto& r = run_of(kCircleScenario);
  SceneRenderer sr({run_view(r, "")}, small(320, 240));
  const Card card{"GPM2002: before and after", {{"error", "nominal", "calibrated"}, {"at 12 poses", "9.68 mm", "10.2 um"}}};
  const FrameImage& f = sr.render_card(card);
  EXPECT_GT(testing::card_share(f), 0.8);
  EXPECT_LT(testing::card_share(f), 0.99) << "text is drawn";
  int title = 0;
  for (int y = 0; y < f.height / 4; ++y)
    for (int x = 0; x < f.width; ++x) title += f.at(x, y)[0] > 180 && f.at(x, y)[2] < 90 ? 1 : 0;
  EXPECT_GT(title, 40) << "a yellow title at the top";
  EXPECT_LT(testing::card_share(sr.render(0.3)), 0.2);
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
