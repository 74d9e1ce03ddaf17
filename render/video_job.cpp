#include "render/video_job.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <cstdio>
#include <optional>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "render/frame_queue.hpp"
#include "render/png_writer.hpp"
#include "render/video_encoder.hpp"

namespace gpm::render {
namespace {

// Frames waiting for the encoder at most (a frame is 0.9 MB at 640x480).
constexpr int kQueuedFrames = 3;

}  // namespace

int frame_count(double t0, double t1, double fps, double speed) {
  const double span = std::max(0.0, t1 - t0);
  return static_cast<int>(std::floor(span * fps / speed + 1e-9)) + 1;
}

double frame_time(double t0, int k, double fps, double speed) { return t0 + k * speed / fps; }

void check_output_suffix(const std::string& path, const std::string& suffix, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (!ec && (fs::is_character_file(st) || fs::is_fifo(st) || fs::is_block_file(st))) return;
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == suffix) return;
  const std::string format = suffix == ".mp4" ? "H.264 MP4" : suffix == ".png" ? "PNG" : suffix;
  throw InputError(fmt::format("{} {}: gpm render writes {} only: give a name ending in {} (got {})", what, path,
                               format, suffix, ext.empty() ? "no suffix" : "'" + ext + "'"));
}

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

std::vector<int> part_frame_counts(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options) {
  std::vector<int> n;
  for (const std::vector<RunView>& runs : parts) {
    double t0 = 1e300, t1 = -1e300;
    for (const RunView& r : runs) {
      if (!r.log || r.log->rows.empty())
        throw InputError(fmt::format("render: run '{}' has an empty trajectory log (nothing to show)", r.label));
      t0 = std::min(t0, r.log->rows.front().t);
      t1 = std::max(t1, r.log->rows.back().t);
    }
    n.push_back(frame_count(t0, t1, options.fps, options.speed));
  }
  return n;
}

std::vector<Segment> video_segments(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                                    const Cards& cards, const std::array<int, 2>& pages) {
  std::vector<Segment> out;
  int n = 0;
  const auto card = [&](Segment::Kind kind, const std::optional<Card>& c) {
    if (!c) return;
    const int per_page = std::max(1, static_cast<int>(std::lround(c->seconds * options.fps)));
    const int k = std::max(1, pages[kind == Segment::Kind::kOpening ? 0 : 1]);
    const int count = per_page * k;
    out.push_back(Segment{kind, -1, n, count, k});
    n += count;
  };
  card(Segment::Kind::kOpening, cards.opening);
  const std::vector<int> counts = part_frame_counts(parts, options);
  for (size_t i = 0; i < counts.size(); ++i) {
    out.push_back(Segment{Segment::Kind::kPart, static_cast<int>(i), n, counts[i], 1});
    n += counts[i];
  }
  card(Segment::Kind::kClosing, cards.closing);
  return out;
}

std::array<int, 2> card_pages(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                              const Cards& cards) {
  if ((!cards.opening && !cards.closing) || parts.empty()) return {1, 1};
  std::vector<RunView> all;
  for (const auto& runs : parts) all.insert(all.end(), runs.begin(), runs.end());
  const SceneRenderer renderer(parts.front(), options, framing_of(all));
  return {cards.opening ? renderer.card_pages(*cards.opening) : 1, cards.closing ? renderer.card_pages(*cards.closing) : 1};
}

int card_page(int j, int count, int pages) {
  if (count <= 0 || pages <= 1) return 0;
  return static_cast<int>(std::clamp<long long>(static_cast<long long>(j) * pages / count, 0, pages - 1));
}

VideoSummary render_video(const std::vector<RunView>& runs, const RenderOptions& options,
                          const std::string& mp4_path, const std::vector<FrameRequest>& pngs,
                          const VideoJobOptions& job) {
  return render_parts({runs}, options, mp4_path, pngs, job);
}

VideoSummary render_parts(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                          const std::string& mp4_path, const std::vector<FrameRequest>& pngs,
                          const VideoJobOptions& job, const Cards& cards) {
  if (!(options.fps > 0)) throw InputError(fmt::format("fps must be positive, got {}", options.fps));
  if (!(options.speed > 0)) throw InputError(fmt::format("speed must be positive, got {}", options.speed));
  if (parts.empty()) throw InputError("render: nothing to show (no part)");
  // The first renderer checks the size and the camera before any file is
  // opened, and measures the cards' pages.
  std::vector<RunView> all;
  for (const auto& runs : parts) all.insert(all.end(), runs.begin(), runs.end());
  const Framing region = framing_of(all);
  auto renderer = std::make_unique<SceneRenderer>(parts.front(), options, region);
  const std::array<int, 2> pages = {cards.opening ? renderer->card_pages(*cards.opening) : 1,
                                    cards.closing ? renderer->card_pages(*cards.closing) : 1};
  const std::vector<Segment> segments = video_segments(parts, options, cards, pages);
  std::vector<int> first;
  for (const Segment& g : segments)
    if (g.kind == Segment::Kind::kPart) first.push_back(g.first);
  const int n = segments.back().first + segments.back().count;
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
  std::vector<bool> wanted(static_cast<size_t>(n), encoder.has_value());
  for (const FrameRequest& p : pngs) wanted[static_cast<size_t>(p.frame)] = true;

  // What happens to a rendered frame: encoded, and saved as the PNGs asking for it.
  const auto consume = [&](const FrameImage& img, int k) {
    if (encoder) encoder->add_frame(img);
    for (size_t i = 0; i < pngs.size(); ++i)
      if (pngs[i].frame == k) write_png_to(png_out[i], img);
  };
  std::optional<FrameQueue> queue;
  if (job.pipeline == Pipeline::kOverlapped) queue.emplace(kQueuedFrames, consume);
  const auto start = std::chrono::steady_clock::now();
  int rendered = 0;
  std::string gl;
  for (const Segment& g : segments) {
    const size_t part = static_cast<size_t>(std::max(0, g.part));
    if (g.kind == Segment::Kind::kPart && part > 0)
      renderer = std::make_unique<SceneRenderer>(parts[part], options, region);
    const double t0 = renderer->start_time();
    const Card* card = g.kind == Segment::Kind::kOpening   ? &*cards.opening
                       : g.kind == Segment::Kind::kClosing ? &*cards.closing
                                                           : nullptr;
    for (int j = 0; j < g.count; ++j) {  // a card too tall for the frame: its pages in turn
      const int k = g.first + j;
      if (!wanted[static_cast<size_t>(k)]) continue;
      const FrameImage& img = card ? renderer->render_card(*card, card_page(j, g.count, g.pages))
                                   : renderer->render(frame_time(t0, j, options.fps, options.speed));
      if (queue) queue->push(img, k);
      else consume(img, k);
      ++rendered;
      if (job.progress) job.progress->update(rendered);
    }
    gl = renderer->gl_renderer();
  }
  if (queue) queue->finish();
  if (job.progress) job.progress->finish();
  if (encoder) encoder->finish();
  for (OutputFile& f : png_out) f.commit();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  VideoSummary s;
  s.frames = encoder ? encoder->frames() : static_cast<int>(pngs.size());
  s.width = options.width;
  s.height = options.height;
  s.wall_s = wall;
  s.frames_per_s = wall > 0 ? rendered / wall : 0.0;
  s.gl_renderer = gl;
  s.codec = encoder ? encoder->codec_name() : "";
  s.part_first = first;
  s.segments = segments;
  return s;
}

}  // namespace gpm::render
