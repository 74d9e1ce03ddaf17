// A whole video of one run or two side by side: the frame timeline, the
// renderer, the MP4 encoder and PNG snapshots, all or nothing.
//
// Use (gpm render, the scenario runner):
//   sim::SimulationResult r = sim::run_simulation(scenario);
//   RenderOptions o = render_options_from_file(scenario_file);  // + overrides
//   render_video({run_view(r, scenario.name)}, o, "out.mp4", {{12, "frame12.png"}});
//   // nominal vs calibrated controller, side by side:
//   render_video({run_view(nominal, "nominal"), run_view(calibrated, "calibrated")}, o, "cmp.mp4", {});
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "models/progress.hpp"
#include "render/render_options.hpp"
#include "render/scene_renderer.hpp"

namespace gpm::render {

// Number of frames covering simulated times t0..t1 at fps video frames per
// second and speed simulated seconds per video second: floor((t1 - t0) * fps
// / speed) + 1 (frame k shows t0 + k * speed / fps).
int frame_count(double t0, double t1, double fps, double speed);

// Simulated time of frame k.
double frame_time(double t0, int k, double fps, double speed);

// A frame to save as PNG: its index (0-based) and file.
struct FrameRequest {
  int frame = 0;
  std::string path;
};

// Refuses (InputError naming `what`) an output whose name does not end in
// suffix (".mp4", ".png"; any case): the name must say the format written.
// A device or FIFO that exists (e.g. /dev/null) is accepted by any name.
void check_output_suffix(const std::string& path, const std::string& suffix, const std::string& what);

// Parses "N:FILE" (e.g. "12:frame.png"); throws InputError naming `what`.
FrameRequest parse_frame_request(const std::string& text, const std::string& what);

// Cards around the parts of a video: an opening card before the first part
// and a closing card after the last (none if unset).
struct Cards {
  std::optional<Card> opening, closing;
};

// A stretch of a video: a card, or a part (render_parts) shown over its
// whole log; frames [first, first + count).
struct Segment {
  enum class Kind { kOpening, kPart, kClosing };
  Kind kind = Kind::kPart;
  int part = -1;  // the part's index (kPart)
  int first = 0, count = 0;
  int pages = 1;  // a card's pages (card_pages), each count / pages frames
};

// The segments of a video: the opening card, the parts, the closing card,
// one after the other (the timeline, no rendering); a card lasts
// round(seconds * fps) frames, at least 1, per page (pages: the opening's
// and the closing card's, card_pages).
std::vector<Segment> video_segments(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                                    const Cards& cards = {}, const std::array<int, 2>& pages = {1, 1});

// The pages the opening and the closing card take in the options' frame
// size (SceneRenderer::card_pages; 1 for a card not set), measured with a
// renderer of the first part.
std::array<int, 2> card_pages(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                              const Cards& cards);

// The page of a card that frame j of its count frames shows when it takes
// pages pages (SceneRenderer::card_pages): each page an equal share, in turn.
int card_page(int j, int count, int pages);

struct VideoSummary {
  int frames = 0;
  int width = 0, height = 0;
  double wall_s = 0.0;         // rendering and encoding
  double frames_per_s = 0.0;   // frames / wall_s
  std::string gl_renderer;
  std::string codec;
  std::vector<int> part_first;  // render_parts: first frame of each part
  std::vector<Segment> segments;  // cards and parts (video_segments)
};

// How frames reach the encoder: rendered and encoded one after the other
// (kSequential), or overlapped on two threads through a frame queue
// (kOverlapped, frame_queue.hpp; the same bytes).
enum class Pipeline { kSequential, kOverlapped };

// How a video is made beyond its look: the pipeline, and a progress line
// (frames, fps, ETA) on a terminal (none if null).
struct VideoJobOptions {
  Pipeline pipeline = Pipeline::kOverlapped;
  Progress* progress = nullptr;
};

// Renders runs over their whole logs into mp4_path (none if empty) and the
// requested PNG frames. Throws InputError for a bad size, camera, frame index
// or output path; on any failure no output file is left behind.
VideoSummary render_video(const std::vector<RunView>& runs, const RenderOptions& options,
                          const std::string& mp4_path, const std::vector<FrameRequest>& pngs,
                          const VideoJobOptions& job = {});

// Renders parts one after the other into one video (e.g. the story of a
// calibration run: the nominal controller on the test path, the sampling,
// the calibrated controller), each over its whole log with its clock from
// 0, all framed alike (the region covering every part); each part is one
// run or two side by side; the cards before and after. Frame indices of
// pngs count over the whole video (VideoSummary::segments, part_first).
VideoSummary render_parts(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options,
                          const std::string& mp4_path, const std::vector<FrameRequest>& pngs,
                          const VideoJobOptions& job = {}, const Cards& cards = {});

// Frames each part of render_parts would have (the timeline, no rendering).
std::vector<int> part_frame_counts(const std::vector<std::vector<RunView>>& parts, const RenderOptions& options);

}  // namespace gpm::render
