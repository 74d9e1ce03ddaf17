#include "render/scene_renderer.hpp"

#include <algorithm>
#include <tuple>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/mjcf.hpp"
#include "render/frame_layout.hpp"
#include "render/mechanism_pose.hpp"
#include "render/offscreen_context.hpp"
#include "render/overlay_painter.hpp"
#include "sim/mujoco_util.hpp"

namespace gpm::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kFramingRows = 400;        // log rows sampled to find the region to show
constexpr double kFramingMarginMm = 25.0;  // link radius and base markers
constexpr double kFramingMarginFrac = 0.04;
constexpr double kMarkerRadiusPx = 5.0;
constexpr int kHighQualitySamples = 4;
constexpr double kMaxColumnFrac = 0.5;  // the text column takes at most this share of a panel
constexpr int kSwatchChars = 3;         // legend swatch length, in digit widths
constexpr const char* kLegendDesired = "desired path";
constexpr const char* kLegendActual = "actual trace";
constexpr const char* kLegendError = "error arrow";
constexpr const char* kWidestScaleLabel = "500 mm; error 500 um";
constexpr double kErrorArrowFrac = 0.25;  // the 95th percentile error arrow: at most this share of the height
constexpr double kErrorHeadPx = 9.0;
constexpr std::array<float, 3> kCardTitleRgb = {1.0f, 0.85f, 0.05f};
constexpr std::array<float, 3> kCardLabelRgb = {0.70f, 0.74f, 0.80f};
constexpr std::array<float, 3> kCardTextRgb = {0.97f, 0.97f, 0.97f};

int font_scale_for(int height) {
  if (height < 360) return mjFONTSCALE_50;
  if (height <= 720) return mjFONTSCALE_100;
  if (height <= 1080) return mjFONTSCALE_150;
  return mjFONTSCALE_200;
}

struct RunSlot {
  RunView view;
  sim::ModelPtr model;
  sim::DataPtr data;
  JointAddresses adr;
  mjvScene scene;
  bool scene_made = false;
  mjvOption option;
  mjvCamera camera;
  std::unique_ptr<OverlayPainter> painter;
  std::array<int, 4> viewport{};
  double px_per_mm = 0.0;  // in the plane of the traces (top camera)
  double scale_mm = 0.0;   // scale bar length (0: none)
  double gain = 1.0;       // magnification of the error arrow
  OverlayLayout layout;    // filled as drawn
};

}  // namespace

Framing framing_of(const std::vector<RunView>& runs) {
  Framing f;
  for (const RunView& r : runs) {
    const Geometry& g = r.actual.geometry;
    for (int i = 0; i < 3; ++i) f.include(g.A(i));
    const auto visit = [&](const sim::LogRow& row) {
      const JointAngles q = pose_of(r.actual, row);
      for (const Eigen::Vector2d& b : elbows(g, q.theta_a)) f.include(b);
      f.include(row.actual);
      f.include(row.desired);
    };
    const size_t n = r.log->rows.size();
    const size_t step = std::max<size_t>(1, n / kFramingRows);
    for (size_t k = 0; k < n; k += step) visit(r.log->rows[k]);
    visit(r.log->rows.back());
  }
  const double side = std::max(f.hi.x() - f.lo.x(), f.hi.y() - f.lo.y());
  const Eigen::Vector2d margin = Eigen::Vector2d::Constant(kFramingMarginMm + kFramingMarginFrac * side);
  f.lo -= margin;
  f.hi += margin;
  return f;
}

RunView run_view(const sim::SimulationResult& r, const std::string& label) {
  return RunView{label, r.actual, r.model_xml, &r.log};
}

void check_render_setup(const std::string& model_xml, const RenderOptions& options,
                        const std::string& camera_what) {
  check_size(options.width, options.height, "size");
  const sim::ModelPtr m = sim::load_model_from_xml(model_xml);
  check_camera(m.get(), options.camera, camera_what);
}

struct SceneRenderer::Impl {
  OffscreenContext context;
  std::vector<std::unique_ptr<RunSlot>> slots;
  mjrContext con;
  bool con_made = false;
  int font = mjFONTSCALE_100;
  int column = 0;  // text column width (px); 0: text over the scene
  int pad = 4, line_h = 16, pitch = 20;  // pitch: mjr_overlay's line spacing
  std::vector<unsigned char> bottom_up;
  FrameImage frame;

  // The text column of slot s: caption and data at the top; legend and
  // scale bar at the bottom (OpenGL pixels, bottom-up).
  void draw_column(RunSlot& s, const std::array<std::string, 2>& text) {
    const int x0 = s.viewport[0], h = s.viewport[3];
    const int cw = std::max(1, con.charWidth[static_cast<int>('0')]);
    int top = h;  // the column above this row is used
    if (!s.view.label.empty()) {
      mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, mjrRect{x0, 0, column, top}, s.view.label.c_str(), nullptr, &con);
      top -= (1 + static_cast<int>(std::count(s.view.label.begin(), s.view.label.end(), '\n'))) * line_h + 2 * pad;
    }
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, mjrRect{x0, 0, column, top}, text[0].c_str(), text[1].c_str(), &con);
    // Scale bar: a white bar of scale_mm with end ticks, its length written under it.
    int bottom = pad;
    if (s.scale_mm > 0) {
      const std::string label = s.gain > 1 ? fmt::format("{:g} mm; error {}", s.scale_mm, distance_text(s.scale_mm / s.gain))
                                           : fmt::format("{:g} mm", s.scale_mm);
      mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, mjrRect{x0, 0, column, h}, label.c_str(), nullptr, &con);
      bottom += line_h + 2 * pad;
      const int len = static_cast<int>(std::lround(s.scale_mm * s.px_per_mm));
      const int bar_h = std::max(2, line_h / 6), tick_h = std::max(6, line_h / 2);
      const int bx = x0 + pad + cw / 2;
      mjr_rectangle(mjrRect{bx - 1, bottom - 1, len + 2, tick_h + 2}, 0.0f, 0.0f, 0.0f, 0.6f);
      s.layout.scale_x = bx;
      s.layout.scale_y = h - 1 - bottom;
      s.layout.scale_len = len;
      mjr_rectangle(mjrRect{bx, bottom, len, bar_h}, 1.0f, 1.0f, 1.0f, 1.0f);
      mjr_rectangle(mjrRect{bx, bottom, bar_h, tick_h}, 1.0f, 1.0f, 1.0f, 1.0f);
      mjr_rectangle(mjrRect{bx + len - bar_h, bottom, bar_h, tick_h}, 1.0f, 1.0f, 1.0f, 1.0f);
      bottom += tick_h + 2 * pad;
    }
    // Legend: a swatch of each overlay's colour left of its name.
    const int swatch = kSwatchChars * cw;
    const std::string names = fmt::format("{}\n{}\n{}", kLegendDesired, kLegendActual, kLegendError);
    const int legend_h = 3 * pitch + pad;
    mjr_rectangle(mjrRect{x0 + pad, bottom, swatch + 2 * pad, legend_h}, 0.0f, 0.0f, 0.0f, 0.6f);
    mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, mjrRect{x0 + swatch + 3 * pad, bottom - pad, column, h},
                names.c_str(), nullptr, &con);
    const int sw_h = std::max(3, line_h / 5);
    const int row_error = bottom + pad + pitch / 2;
    const std::array<int, 3> rows = {row_error + 2 * pitch, row_error + pitch, row_error};
    const std::array<const std::array<float, 4>*, 3> colours = {&OverlayStyle::kDesiredRgba, &OverlayStyle::kTraceRgba,
                                                                &OverlayStyle::kErrorRgba};
    for (size_t i = 0; i < 3; ++i) {
      const auto& c = *colours[i];
      mjr_rectangle(mjrRect{x0 + 2 * pad, rows[i] - sw_h / 2, swatch, sw_h}, c[0], c[1], c[2], 1.0f);
      s.layout.legend_rows[i] = h - 1 - rows[i];
    }
    s.layout.legend_x0 = x0 + 2 * pad;
    s.layout.legend_x1 = x0 + 2 * pad + swatch;
  }

  // The frame drawn, read into `frame` (top row first).
  void read_frame() {
    const mjrRect full = {0, 0, frame.width, frame.height};
    mjr_readPixels(bottom_up.data(), nullptr, full, &con);
    const size_t row_bytes = static_cast<size_t>(frame.width) * 3;
    for (int y = 0; y < frame.height; ++y) {
      std::memcpy(frame.rgb.data() + static_cast<size_t>(y) * row_bytes,
                  bottom_up.data() + static_cast<size_t>(frame.height - 1 - y) * row_bytes, row_bytes);
    }
  }

  // Width (px) of the longest line of t in font f (mjFONT_NORMAL or mjFONT_BIG).
  int font_px(int f, const std::string& t) const {
    const int* cw = f == mjFONT_BIG ? con.charWidthBig : con.charWidth;
    int w = 0, best = 0;
    for (const char c : t) {
      if (c == '\n') w = 0;
      else if (c > 0 && c < 127) best = std::max(best, w += cw[static_cast<int>(c)]);
    }
    return best;
  }

  // The fonts of the context as a card's layout measures them.
  CardFonts card_fonts() const {
    CardFonts f;
    std::copy(std::begin(con.charWidth), std::end(con.charWidth), f.normal_w.begin());
    std::copy(std::begin(con.charWidthBig), std::end(con.charWidthBig), f.big_w.begin());
    f.normal_h = con.charHeight;
    f.big_h = con.charHeightBig;
    return f;
  }

  // One page of a card's layout drawn (tops from the frame's top).
  void draw_card_page(const CardPage& page) {
    for (const CardLine& line : page.lines)
      for (const CardText& t : line.texts) {
        if (t.text.empty()) continue;
        const int f = t.big ? mjFONT_BIG : mjFONT_NORMAL;
        const int th = t.big ? con.charHeightBig : con.charHeight;
        const std::array<float, 3>& rgb = t.role == CardRole::kTitle   ? kCardTitleRgb
                                          : t.role != CardRole::kText  ? kCardLabelRgb
                                                                       : kCardTextRgb;
        mjr_label(mjrRect{t.x, frame.height - line.top - th, font_px(f, t.text) + 2, th}, f, t.text.c_str(),
                  kCardRgb[0], kCardRgb[1], kCardRgb[2], 1.0f, rgb[0], rgb[1], rgb[2], &con);
      }
  }

  ~Impl() {
    context.make_current();
    if (con_made) mjr_freeContext(&con);
    for (auto& s : slots)
      if (s->scene_made) mjv_freeScene(&s->scene);
  }

  // Loads each run's model and data into a slot, the panels side by side; returns the logs' time span.
  std::pair<double, double> load_runs(const std::vector<RunView>& runs, const RenderOptions& options, int panel_w) {
    double t0 = 1e300, t1 = -1e300;
    for (size_t i = 0; i < runs.size(); ++i) {
      auto s = std::make_unique<RunSlot>();
      s->view = runs[i];
      t0 = std::min(t0, s->view.log->rows.front().t);
      t1 = std::max(t1, s->view.log->rows.back().t);
      s->model = sim::load_model_from_xml(s->view.model_xml);
      mjModel* m = s->model.get();
      m->vis.global.offwidth = options.width;
      m->vis.global.offheight = options.height;
      m->vis.quality.offsamples = options.quality == Quality::kHigh ? kHighQualitySamples : 0;
      OverlayPainter::paint_model(m);
      check_camera(m, options.camera, "camera");
      s->data.reset(mj_makeData(m));
      s->adr = joint_addresses(m);
      s->viewport = {static_cast<int>(i) * panel_w, 0, panel_w, options.height};
      slots.push_back(std::move(s));
    }
    return {t0, t1};
  }

  // Makes MuJoCo's rendering context with an off-screen buffer of the options' size (RenderError otherwise).
  void make_context(const RenderOptions& options) {
    font = font_scale_for(options.height);
    mjr_defaultContext(&con);
    mjr_makeContext(slots.front()->model.get(), &con, font);
    con_made = true;
    mjr_setBuffer(mjFB_OFFSCREEN, &con);
    if (con.currentBuffer != mjFB_OFFSCREEN || con.offWidth < options.width || con.offHeight < options.height)
      throw RenderError(fmt::format("MuJoCo could not make a {}x{} off-screen buffer", options.width, options.height));
  }

  // Width (px) of the longest line of t in the context's font.
  int text_px(const std::string& t) const { return font_px(mjFONT_NORMAL, t); }

  // The text column (frame_layout.hpp): as wide as its longest line; used
  // when it leaves at least half the panel to the mechanism and its lines fit
  // the height, else the text is drawn over the scene in the corners (column 0).
  void fit_text_column(int panel_w, int height) {
    const int cw = std::max(1, con.charWidth[static_cast<int>('0')]);
    pad = std::max(2, cw / 2);
    line_h = std::max(1, con.charHeight);
    pitch = line_h + line_h / 4;  // measured
    int width = text_px("enc 1") + text_px("-3.14159 rad") + 3 * cw;  // the two columns of the data block
    for (const auto& s : slots) width = std::max(width, text_px(s->view.label) + 2 * cw);
    width = std::max(width, kSwatchChars * cw + text_px(std::string(kLegendDesired)) + 4 * cw);
    width = std::max(width, text_px(kWidestScaleLabel) + 2 * cw);
    // Height: caption, 6 data lines, 3 legend lines, the scale bar's label and ticks, margins.
    int label_lines = 0;
    for (const auto& s : slots)
      if (!s->view.label.empty())
        label_lines = std::max(label_lines, 1 + static_cast<int>(std::count(s->view.label.begin(),
                                                                             s->view.label.end(), '\n')));
    const int column_h = (label_lines + 6 + 3 + 1) * pitch + std::max(6, line_h / 2) + 6 * pad;
    column = width <= kMaxColumnFrac * panel_w && column_h <= height ? width : 0;
  }

  // Frames slot s's camera on region and makes its painter, scale bar and scene.
  void make_scene(RunSlot& s, const RenderOptions& options, const Framing& region, int panel_w) {
    mjModel* m = s.model.get();
    const Framing shown = column > 0 && (options.camera == "top" || options.camera == "oblique")
                              ? frame_beside_column(region, panel_w, options.height, column, pad)
                              : region;
    s.camera = make_camera(m, options.camera, shown, static_cast<double>(panel_w) / options.height);
    // Scale of the plane in the image: pixels per mm at the framing distance.
    const double fovy = m->vis.global.fovy;
    const double px_per_m =
        0.5 * options.height / std::tan(0.5 * fovy * kPi / 180.0) / std::max(s.camera.distance, 1e-3);
    const double mm_per_px = 1.0 / (px_per_m * kMetresPerMm);
    const double line_px = std::max(1.5, options.height / 320.0);
    std::vector<double> errors;
    errors.reserve(s.view.log->rows.size());
    for (const sim::LogRow& r : s.view.log->rows) errors.push_back((r.actual - r.desired).norm());
    s.gain = error_gain(std::move(errors), 1.0 / mm_per_px, kErrorArrowFrac * options.height);
    const ErrorArrow arrow{s.gain, kErrorHeadPx * options.height / 480.0 * mm_per_px};
    s.painter = std::make_unique<OverlayPainter>(s.view.actual, *s.view.log, std::max(0.2, 1.5 * mm_per_px),
                                                 std::max(2.0, kMarkerRadiusPx * mm_per_px), line_px, arrow);
    // Scale bar in the plane of the traces, top camera only (elsewhere the scale varies across the image).
    if (options.camera == "top" && column > 0) {
      const int cw = std::max(1, con.charWidth[static_cast<int>('0')]);
      s.px_per_mm = top_px_per_mm(s.camera.distance, OverlayStyle::kPathZ_m, fovy, options.height);
      s.scale_mm = scale_bar_mm(s.px_per_mm, column - 2 * pad - 2 * cw);
    }
    mjv_defaultOption(&s.option);
    for (int g = 0; g < mjNGROUP; ++g) s.option.sitegroup[g] = 0;
    mjv_defaultScene(&s.scene);
    mjv_makeScene(m, &s.scene, m->ngeom + s.painter->max_geoms() + 16);
    s.scene_made = true;
    s.scene.flags[mjRND_SHADOW] = options.quality == Quality::kHigh;
    s.scene.flags[mjRND_REFLECTION] = 0;
    s.scene.flags[mjRND_SKYBOX] = 0;
  }
};

SceneRenderer::SceneRenderer(const std::vector<RunView>& runs, const RenderOptions& options,
                             const std::optional<Framing>& region_in) {
  if (runs.empty() || runs.size() > 2)
    throw InputError(fmt::format("render: one or two runs can be shown, got {}", runs.size()));
  check_size(options.width, options.height, "size");
  for (const RunView& r : runs) {
    if (!r.log || r.log->rows.empty())
      throw InputError(fmt::format("render: run '{}' has an empty trajectory log (nothing to show)", r.label));
  }
  sim::install_mujoco_handlers();
  impl_ = std::make_unique<Impl>();
  Impl& im = *impl_;
  if (im.context.max_renderbuffer_size() < std::max(options.width, options.height))
    throw InputError(fmt::format("size: {}x{} is beyond the off-screen buffer (maximum {}x{})", options.width,
                                 options.height, im.context.max_renderbuffer_size(),
                                 im.context.max_renderbuffer_size()));

  const Framing region = region_in ? *region_in : framing_of(runs);
  const int panel_w = options.width / static_cast<int>(runs.size());
  std::tie(t0_, t1_) = im.load_runs(runs, options, panel_w);
  im.make_context(options);
  im.fit_text_column(panel_w, options.height);
  for (auto& s : im.slots) im.make_scene(*s, options, region, panel_w);
  im.frame.width = options.width;
  im.frame.height = options.height;
  im.frame.rgb.assign(static_cast<size_t>(options.width) * options.height * 3, 0);
  im.bottom_up.assign(im.frame.rgb.size(), 0);
}

SceneRenderer::~SceneRenderer() = default;

const FrameImage& SceneRenderer::render(double t) {
  Impl& im = *impl_;
  im.context.make_current();
  mjr_setBuffer(mjFB_OFFSCREEN, &im.con);
  for (auto& s : im.slots) {
    const mjModel* m = s->model.get();
    mjData* d = s->data.get();
    const sim::LogRow& row = row_at(*s->view.log, t);
    apply_pose(m, d, s->adr, pose_of(s->view.actual, row));
    mjv_updateScene(m, d, &s->option, nullptr, &s->camera, mjCAT_ALL, &s->scene);
    s->painter->add_geoms(&s->scene, t, row);
    const mjrRect vp = {s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]};
    mjr_render(vp, &s->scene, &im.con);
    const auto text = OverlayPainter::text(row, t0_, s->gain);
    if (im.column > 0) {
      im.draw_column(*s, text);
    } else {
      mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, vp, text[0].c_str(), text[1].c_str(), &im.con);
      if (!s->view.label.empty())
        mjr_overlay(mjFONT_NORMAL, mjGRID_TOPRIGHT, vp, s->view.label.c_str(), nullptr, &im.con);
    }
  }
  im.read_frame();
  return im.frame;
}

int SceneRenderer::card_pages(const Card& card) const {
  return static_cast<int>(lay_out_card(card, impl_->card_fonts(), impl_->frame.width, impl_->frame.height).size());
}

const FrameImage& SceneRenderer::render_card(const Card& card, int page) {
  Impl& im = *impl_;
  im.context.make_current();
  mjr_setBuffer(mjFB_OFFSCREEN, &im.con);
  mjr_rectangle(mjrRect{0, 0, im.frame.width, im.frame.height}, kCardRgb[0], kCardRgb[1], kCardRgb[2], 1.0f);
  const std::vector<CardPage> pages = lay_out_card(card, im.card_fonts(), im.frame.width, im.frame.height);
  im.draw_card_page(pages.at(static_cast<size_t>(std::clamp(page, 0, static_cast<int>(pages.size()) - 1))));
  im.read_frame();
  return im.frame;
}

std::array<std::string, 2> SceneRenderer::text(size_t i, double t) const {
  const RunSlot& s = *impl_->slots.at(i);
  return OverlayPainter::text(row_at(*s.view.log, t), t0_, s.gain);
}

double SceneRenderer::arrow_gain(size_t i) const { return impl_->slots.at(i)->gain; }

const mjvCamera& SceneRenderer::camera(size_t i) const { return impl_->slots.at(i)->camera; }

std::array<int, 4> SceneRenderer::viewport(size_t i) const { return impl_->slots.at(i)->viewport; }

OverlayLayout SceneRenderer::layout(size_t i) const {
  const RunSlot& s = *impl_->slots.at(i);
  OverlayLayout l = s.layout;
  l.column = impl_->column;
  l.scale_mm = s.scale_mm;
  l.px_per_mm = s.px_per_mm;
  return l;
}

double SceneRenderer::fovy_deg(size_t i) const { return impl_->slots.at(i)->model->vis.global.fovy; }

const std::string& SceneRenderer::gl_renderer() const { return impl_->context.renderer(); }

}  // namespace gpm::render
