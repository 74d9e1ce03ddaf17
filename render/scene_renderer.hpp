// Renders one run, or two side by side, at any instant of their logs: the
// mechanism re-posed from the log row (mechanism_pose.hpp), the overlays
// (overlay_painter.hpp) and the text, into an RGB frame, off-screen.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/robot.hpp"
#include "render/camera_set.hpp"
#include "render/card_layout.hpp"
#include "render/frame_image.hpp"
#include "render/render_options.hpp"
#include "sim/sampling.hpp"
#include "sim/simulate.hpp"

namespace gpm::render {

// One run to show: the actual robot the twin was built from, the MJCF it ran
// and its trajectory log (not owned: it must outlive the renderer).
struct RunView {
  std::string label;
  Robot actual;
  std::string model_xml;
  const sim::TrajectoryLog* log = nullptr;
};

// A view of a simulation result (r must outlive the view).
RunView run_view(const sim::SimulationResult& r, const std::string& label);

// Checks what can be checked before a simulation runs: the size (positive,
// even, within the off-screen buffer) and the camera name against the model
// compiled from model_xml. Throws InputError; camera errors start with
// camera_what (e.g. "--camera").
void check_render_setup(const std::string& model_xml, const RenderOptions& options,
                        const std::string& camera_what = "camera");

// The region of the plane (mm) a free camera shows for these runs: the base
// joints, elbows, end-effector and desired path over every log, with a margin.
Framing framing_of(const std::vector<RunView>& runs);

// Background of a card (RGB, 0..1): no scene frame is this uniform.
inline constexpr std::array<float, 3> kCardRgb = {0.06f, 0.10f, 0.24f};

// Where the 2-D overlays of a panel are (image pixels, x from the left, y
// from the top), for tests and tools.
struct OverlayLayout {
  int column = 0;         // width of the text column at the panel's left (0: text over the scene)
  double scale_mm = 0.0;  // length the scale bar stands for (0: no bar; top camera with a column only)
  double px_per_mm = 0.0;  // its pixels per mm, in the plane of the traces
  int scale_x = 0, scale_y = 0, scale_len = 0;  // the bar: left end, row, length (px)
  std::array<int, 3> legend_rows{};  // rows of the desired-path, actual-trace and error-arrow swatches
  int legend_x0 = 0, legend_x1 = 0;  // swatch columns [x0, x1)
};

class SceneRenderer {
 public:
  // One or two runs (side by side, each in half the width), framing region
  // (framing_of(runs) if not given). Throws InputError for a bad size or
  // camera, or an empty log; RenderError if OpenGL fails.
  SceneRenderer(const std::vector<RunView>& runs, const RenderOptions& options,
                const std::optional<Framing>& region = std::nullopt);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // The frame at simulated time t (each run shows its log row at t; the
  // clock reads t - start_time(): each part of a video from 0).
  const FrameImage& render(double t);

  // The pages a card takes in the frame's size (render/card_layout.hpp: 1
  // when it fits).
  int card_pages(const Card& card) const;
  // Page `page` of a card (title and rows on a plain background) in the frame's size.
  const FrameImage& render_card(const Card& card, int page = 0);

  // The data block run i's panel shows at time t (labels, values), as
  // render(t) draws it.
  std::array<std::string, 2> text(size_t i, double t) const;

  // The magnification of run i's error arrow (frame_layout.hpp: error_gain).
  double arrow_gain(size_t i) const;

  // The camera of run i (as built by make_camera) and the viewport it draws in
  // (left, bottom, width, height in OpenGL pixels, bottom-up).
  const mjvCamera& camera(size_t i) const;
  std::array<int, 4> viewport(size_t i) const;
  // The overlay layout of run i's panel (positions known after the first render()).
  OverlayLayout layout(size_t i) const;
  // Vertical field of view (degrees) of free cameras in run i's model.
  double fovy_deg(size_t i) const;

  // First and last logged times over all runs.
  double start_time() const { return t0_; }
  double end_time() const { return t1_; }

  // The GL renderer string (llvmpipe ...).
  const std::string& gl_renderer() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  double t0_ = 0.0, t1_ = 0.0;
};

}  // namespace gpm::render
