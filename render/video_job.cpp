#include "render/video_job.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "render/png_writer.hpp"
#include "render/video_encoder.hpp"

namespace gpm::render {

int frame_count(double t0, double t1, double fps, double speed) {
  const double span = std::max(0.0, t1 - t0);
  return static_cast<int>(std::floor(span * fps / speed + 1e-9)) + 1;
}

double frame_time(double t0, int k, double fps, double speed) { return t0 + k * speed / fps; }

FrameRequest parse_frame_request(const std::string& text, const std::string& what) {
  const auto colon = text.find(':');
  FrameRequest r;
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw InputError(fmt::format("{}: expected FRAME:FILE (e.g. 12:frame.png), got '{}'", what, text));
  const std::string n = text.substr(0, colon);
  size_t used = 0;
  long v = -1;
  try {
    v = std::stol(n, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != n.size() || v < 0 || v > 100000000)
    throw InputError(fmt::format("{}: frame must be a whole number >= 0, got '{}'", what, n));
  r.frame = static_cast<int>(v);
  r.path = text.substr(colon + 1);
  return r;
}

namespace {

// Temporary PNG files, renamed together at the end or removed.

}  // namespace

VideoSummary render_video(const std::vector<RunView>& runs, const RenderOptions& options,
                          const std::string& mp4_path, const std::vector<FrameRequest>& pngs) {
  if (!(options.fps > 0)) throw InputError(fmt::format("fps must be positive, got {}", options.fps));
  if (!(options.speed > 0)) throw InputError(fmt::format("speed must be positive, got {}", options.speed));
  SceneRenderer renderer(runs, options);
  const double t0 = renderer.start_time();
  const int n = frame_count(t0, renderer.end_time(), options.fps, options.speed);
  for (const FrameRequest& p : pngs) {
    if (p.frame >= n)
      throw InputError(fmt::format("--frame-png {}: the video has {} frames (0..{})", p.frame, n, n - 1));
  }
  // Every PNG staged (or a device opened in place) before any frame is rendered.
  std::vector<OutputFile> png_out;
  png_out.reserve(pngs.size());
  for (const FrameRequest& p : pngs) png_out.emplace_back(p.path);
  std::optional<VideoEncoder> encoder;
  if (!mp4_path.empty()) encoder.emplace(mp4_path, options.width, options.height, options.fps);
  int last = n - 1;
  if (!encoder) {
    last = -1;
    for (const FrameRequest& p : pngs) last = std::max(last, p.frame);
  }
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k <= last; ++k) {
    bool wanted = encoder.has_value();
    for (const FrameRequest& p : pngs) wanted = wanted || p.frame == k;
    if (!wanted) continue;
    const FrameImage& img = renderer.render(frame_time(t0, k, options.fps, options.speed));
    if (encoder) encoder->add_frame(img);
    for (size_t i = 0; i < pngs.size(); ++i)
      if (pngs[i].frame == k) write_png_to(png_out[i], img);
  }
  if (encoder) encoder->finish();
  for (OutputFile& f : png_out) f.commit();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  VideoSummary s;
  s.frames = encoder ? encoder->frames() : static_cast<int>(pngs.size());
  s.width = options.width;
  s.height = options.height;
  s.wall_s = wall;
  s.frames_per_s = wall > 0 ? s.frames / wall : 0.0;
  s.gl_renderer = renderer.gl_renderer();
  s.codec = encoder ? encoder->codec_name() : "";
  return s;
}

}  // namespace gpm::render
