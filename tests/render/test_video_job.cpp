// Tests of render/video_job.cpp: the frame timeline, whole videos with PNG
// snapshots, reproducibility, the overlapped pipeline against the sequential
// one, videos in parts with their cards and clocks, and all-or-nothing
// failures.
#include <fstream>
#include <iterator>
#include <memory>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "render/png_writer.hpp"
#include "render/video_job.hpp"
#include "render_test_util.hpp"

namespace gpm::render {
namespace {

namespace fs = std::filesystem;
using testing::run_of;

std::string bytes_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

RenderOptions tiny() {
  RenderOptions o;
  o.width = 160;
  o.height = 120;
  o.fps = 20;
  return o;
}

TEST(VideoJob, FrameTimeline) {
  EXPECT_EQ(frame_count(0.0, 1.0, 30.0, 1.0), 31);
  EXPECT_EQ(frame_count(0.0, 0.99, 30.0, 1.0), 30);
  EXPECT_EQ(frame_count(0.5, 0.5, 30.0, 1.0), 1);
  EXPECT_EQ(frame_count(0.0, 1.0, 30.0, 2.0), 16);
  EXPECT_EQ(frame_count(0.0, 0.3, 10.0, 1.0), 4) << "0.3 * 10 is 2.9999...: still 4 frames";
  EXPECT_DOUBLE_EQ(frame_time(0.25, 3, 30.0, 1.0), 0.35);
  EXPECT_DOUBLE_EQ(frame_time(0.0, 3, 30.0, 0.5), 0.05);
}

TEST(VideoJob, FrameRequests) {
  const FrameRequest r = parse_frame_request("12:out/f.png", "--frame-png");
  EXPECT_EQ(r.frame, 12);
  EXPECT_EQ(r.path, "out/f.png");
  EXPECT_EQ(parse_frame_request("0:a:b.png", "x").path, "a:b.png");
  for (const char* bad : {"12", ":f.png", "12:", "-1:f.png", "x:f.png", "1.5:f.png"}) {
    EXPECT_THROW(parse_frame_request(bad, "--frame-png"), InputError) << bad;
  }
}

// ffprobe counts floor(duration * fps) + 1 frames of the requested size; the
// PNG equals the frame rendered alone at that frame's time.
TEST(VideoJob, VideoAndPngOfAScenario) {
  const auto& r = run_of(testing::kCircleScenario);
  const fs::path d = testing::fresh_dir("job");
  const RenderOptions o = tiny();
  const double span = r.log.rows.back().t - r.log.rows.front().t;
  const int expected = static_cast<int>(std::floor(span * o.fps + 1e-9)) + 1;
  ASSERT_GT(expected, 10);
  const VideoSummary s = render_video({run_view(r, "circle")}, o, (d / "v.mp4").string(), {{7, (d / "f7.png").string()}});
  EXPECT_EQ(s.frames, expected);
  EXPECT_EQ(testing::probe((d / "v.mp4").string()), fmt::format("h264,160,120,20/1,{}\n", expected));
  SceneRenderer alone({run_view(r, "circle")}, o);
  EXPECT_EQ(read_png((d / "f7.png").string()).rgb, alone.render(frame_time(r.log.rows.front().t, 7, 20.0, 1.0)).rgb);
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 2) << "no temporary files left";
  fs::remove_all(d);
}

TEST(VideoJob, SameScenarioSameBytes) {
  const auto& r = run_of(testing::kLineScenario);
  const fs::path d = testing::fresh_dir("job_same");
  for (const char* name : {"a", "b"}) {
    render_video({run_view(r, "line")}, tiny(), (d / (std::string(name) + ".mp4")).string(),
                 {{3, (d / (std::string(name) + ".png")).string()}});
  }
  EXPECT_EQ(bytes_of(d / "a.png"), bytes_of(d / "b.png"));
  EXPECT_EQ(bytes_of(d / "a.mp4"), bytes_of(d / "b.mp4"));
  fs::remove_all(d);
}

// Issue 20: rendering and encoding overlapped through the frame queue give
// the same bytes as the sequential loop (video and PNG alike).
TEST(VideoJob, OverlappedPipelineGivesTheSequentialBytes) {
  const auto& r = run_of(testing::kCircleScenario);
  const fs::path d = testing::fresh_dir("job_pipeline");
  for (const Pipeline p : {Pipeline::kSequential, Pipeline::kOverlapped}) {
    const std::string name = p == Pipeline::kSequential ? "seq" : "ovl";
    VideoJobOptions job;
    job.pipeline = p;
    const VideoSummary v = render_video({run_view(r, "circle")}, tiny(), (d / (name + ".mp4")).string(),
                                        {{5, (d / (name + ".png")).string()}}, job);
    EXPECT_GT(v.frames, 10);
  }
  EXPECT_GT(bytes_of(d / "seq.mp4").size(), 1000u);
  EXPECT_EQ(bytes_of(d / "seq.mp4"), bytes_of(d / "ovl.mp4"));
  EXPECT_EQ(bytes_of(d / "seq.png"), bytes_of(d / "ovl.png"));
  fs::remove_all(d);
}

// Parts follow each other: frame counts add up, each part starts at its
// first frame, and a PNG of part 2's first frame is that part rendered alone.
TEST(VideoJob, PartsPlayOneAfterTheOther) {
  const auto& a = run_of(testing::kCircleScenario);
  const auto& b = run_of(testing::kLineScenario);
  const fs::path d = testing::fresh_dir("job_parts");
  const RenderOptions o = tiny();
  const std::vector<std::vector<RunView>> parts = {{run_view(a, "first")}, {run_view(b, "second")}};
  const std::vector<int> n = part_frame_counts(parts, o);
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0], part_frame_counts({{run_view(a, "")}}, o)[0]);
  const VideoSummary v = render_parts(parts, o, (d / "v.mp4").string(), {{n[0], (d / "p.png").string()}});
  EXPECT_EQ(v.frames, n[0] + n[1]);
  EXPECT_EQ(v.part_first, (std::vector<int>{0, n[0]}));
  EXPECT_EQ(testing::probe((d / "v.mp4").string()), fmt::format("h264,160,120,20/1,{}\n", n[0] + n[1]));
  std::vector<RunView> all = {run_view(a, ""), run_view(b, "")};
  SceneRenderer alone({run_view(b, "second")}, o, framing_of(all));
  EXPECT_EQ(read_png((d / "p.png").string()).rgb, alone.render(b.log.rows.front().t).rgb);
  fs::remove_all(d);
}

// Issue 35: a story opens with a card and closes with one, and each part's
// clock starts from 0. Frames at every segment's start and end: taken from
// the MP4 by ffmpeg, the cards' are the card background over most of the
// frame and the parts' are not; saved exactly (--frame-png), a card's equals
// the card rendered alone, and a part's equals the part's run logged from 0
// rendered alone (the second part is logged from 15.545 s, as the calibrated
// controller's test path of a run is: with the clock not reset, its frames
// would show 15.545 s). The overlay's text says "0.000 s" at every part's
// start.
TEST(VideoJob, CardsOpenAndCloseAStoryAndEachPartsClockStartsAtZero) {
  const auto& a = run_of(testing::kCircleScenario);
  const auto& b = run_of(testing::kLineScenario);
  const sim::TrajectoryLog late = testing::shifted(b.log, 15.545);
  const fs::path d = testing::fresh_dir("job_cards");
  RenderOptions o = tiny();  // the smallest frame a story is rendered at
  o.width = kMinCardWidth;
  o.height = kMinCardHeight;
  const std::vector<std::vector<RunView>> parts = {{run_view(a, "1/2 first")},
                                                   {RunView{"2/2 second", b.actual, b.model_xml, &late}}};
  Cards cards;
  cards.opening = Card{"GPM2002", {{"robot", "a 3-RRR planar parallel robot"}}, 0.5};
  cards.closing = Card{"before and after", {{"", "nominal", "calibrated"}, {"at 12 poses", "9.68 mm", "10.2 um"}}, 0.5};

  ASSERT_EQ(card_pages(parts, o, cards), (std::array<int, 2>{1, 1})) << "short cards: one page each";
  const std::vector<Segment> g = video_segments(parts, o, cards);
  const std::vector<int> n = part_frame_counts(parts, o);
  ASSERT_EQ(g.size(), 4u);
  EXPECT_EQ(g[0].kind, Segment::Kind::kOpening);
  EXPECT_EQ(g[1].kind, Segment::Kind::kPart);
  EXPECT_EQ(g[2].kind, Segment::Kind::kPart);
  EXPECT_EQ(g[3].kind, Segment::Kind::kClosing);
  const int total = 10 + n[0] + n[1] + 10;  // 0.5 s cards at 20 fps
  EXPECT_EQ(std::vector<int>({g[0].first, g[1].first, g[2].first, g[3].first}),
            std::vector<int>({0, 10, 10 + n[0], 10 + n[0] + n[1]}));
  EXPECT_EQ(g[3].first + g[3].count, total);

  std::vector<FrameRequest> pngs;
  for (const Segment& s : g)
    for (const int k : {s.first, s.first + s.count - 1})
      pngs.push_back({k, (d / fmt::format("f{}.png", k)).string()});
  const VideoSummary v = render_parts(parts, o, (d / "v.mp4").string(), pngs, {}, cards);
  EXPECT_EQ(v.frames, total);
  EXPECT_EQ(v.part_first, (std::vector<int>{10, 10 + n[0]}));
  EXPECT_EQ(testing::probe((d / "v.mp4").string()), fmt::format("h264,320,240,20/1,{}\n", total));

  // The frames as the video holds them (decoded by ffmpeg).
  std::string select;
  for (const FrameRequest& p : pngs) select += fmt::format("{}eq(n\\,{})", select.empty() ? "" : "+", p.frame);
  int status = -1;
  testing::shell(fmt::format("{} -v error -i '{}' -vf \"select={}\" -vsync 0 '{}'", GPM_FFMPEG, (d / "v.mp4").string(),
                             select, (d / "dec%d.png").string()),
                 &status);
  ASSERT_EQ(status, 0);
  std::vector<RunView> all = {run_view(a, ""), run_view(b, "")};
  const Framing region = framing_of(all);
  std::vector<std::unique_ptr<SceneRenderer>> alone;  // each part alone, logged from 0
  for (size_t p = 0; p < 2; ++p)
    alone.push_back(std::make_unique<SceneRenderer>(
        std::vector<RunView>{run_view(p == 0 ? a : b, parts[p].front().label)}, o, region));
  for (size_t i = 0; i < pngs.size(); ++i) {
    const Segment& s = g[i / 2];
    const int j = pngs[i].frame - s.first;  // frame within its segment
    const FrameImage decoded = read_png((d / fmt::format("dec{}.png", i + 1)).string());
    const FrameImage saved = read_png(pngs[i].path);
    if (s.kind != Segment::Kind::kPart) {
      EXPECT_GT(testing::card_share(decoded), 0.7) << "frame " << pngs[i].frame << ": a card";
      EXPECT_EQ(saved.rgb, alone[0]->render_card(s.kind == Segment::Kind::kOpening ? *cards.opening : *cards.closing).rgb);
      continue;
    }
    EXPECT_LT(testing::card_share(decoded), 0.2) << "frame " << pngs[i].frame << ": a part, not a card";
    const auto& run = s.part == 0 ? a : b;  // logged from 0
    const double t = frame_time(run.log.rows.front().t, j, o.fps, o.speed);
    EXPECT_EQ(saved.rgb, alone[static_cast<size_t>(s.part)]->render(t).rgb) << "frame " << pngs[i].frame << " (part " << s.part << ", frame " << j
                                              << "): not the part's own clock";
    if (j == 0) {
      SceneRenderer shown(parts[static_cast<size_t>(s.part)], o, region);
      EXPECT_EQ(shown.text(0, shown.start_time())[1].substr(0, 8), "0.000 s\n") << "part " << s.part;
    }
  }
  fs::remove_all(d);
}

// A pixel of the frame's edge band (the last `band` rows and columns) that is not the card's background.
bool text_in_edge_band(const FrameImage& f, int band) {
  for (int y = 0; y < f.height; ++y)
    for (int x = 0; x < f.width; ++x) {
      if (y < f.height - band && x < f.width - band) continue;
      const std::uint8_t* p = f.at(x, y);
      for (int c = 0; c < 3; ++c)
        if (std::abs(p[c] - std::lround(255.0 * kCardRgb[c])) > 8) return true;
    }
  return false;
}

// Issue 35: a card taller than the frame is shown in pages, each for the
// card's seconds, none running off the frame. The main job's opening card
// (17 lines of 18 px in the overlay font: about 370 px) at the smallest
// story frame, 320x240, takes several pages; each frame's bottom and right
// bands (half the 13 px margin) are background only, the pages differ and
// follow each other, and a story under 320x240 is refused naming the flag.
// At 640x480 the same card is one page.
TEST(VideoJob, ATallCardIsShownInPagesWithinTheFrame) {
  const auto& a = run_of(testing::kCircleScenario);
  const fs::path d = testing::fresh_dir("job_pages");
  RenderOptions o = tiny();
  o.width = kMinCardWidth;
  o.height = kMinCardHeight;
  const std::vector<std::vector<RunView>> parts = {{run_view(a, "1/1 circle")}};
  Cards cards;
  cards.opening = Card{"GPM2002: calibration on its digital twin",
                       {{"robot", "GPM2002, a 3-RRR planar parallel robot, simulated in MuJoCo"},
                        {"procedure", "Accuracy-first calibration of the GPM2002 on the realistic twin, with compensation"},
                        {"", "9100 readings taken on the fly along a path through 40 designed poses (9.1 s of robot motion),"},
                        {"", "then the ML calibration (Levenberg-Marquardt)"},
                        {""},
                        {"shown", "1/3 nominal model test path"},
                        {"", "2/3 sampling for the calibration"},
                        {"", "3/3 calibrated model test path"},
                        {"", "then the errors before and after, measured in this run"},
                        {"", "cyan arrow: the tracking error, magnified as the panel states"}},
                       0.5};
  const std::array<int, 2> pages = card_pages(parts, o, cards);
  ASSERT_GE(pages[0], 2) << "17 lines of 18 px do not fit 240 px";
  EXPECT_EQ(pages[1], 1) << "no closing card";
  const std::vector<Segment> g = video_segments(parts, o, cards, pages);
  ASSERT_EQ(g.size(), 2u);
  EXPECT_EQ(g[0].count, 10 * pages[0]) << "0.5 s at 20 fps per page";
  std::vector<FrameRequest> pngs;
  for (int p = 0; p < pages[0]; ++p)
    for (const int k : {10 * p, 10 * p + 9}) pngs.push_back({k, (d / fmt::format("c{}.png", k)).string()});
  const VideoSummary v = render_parts(parts, o, "", pngs, {}, cards);
  EXPECT_EQ(v.segments[1].first, g[1].first);
  SceneRenderer alone(parts.front(), o);
  for (size_t i = 0; i < pngs.size(); ++i) {
    const FrameImage f = read_png(pngs[i].path);
    const int page = pngs[i].frame / 10;
    EXPECT_GT(testing::card_share(f), 0.7) << "frame " << pngs[i].frame;
    EXPECT_FALSE(text_in_edge_band(f, 6)) << "frame " << pngs[i].frame << ": text beyond the margins";
    EXPECT_EQ(f.rgb, alone.render_card(*cards.opening, page).rgb) << "frame " << pngs[i].frame << ": page " << page;
    if (i % 2 == 1 && page > 0) {
      EXPECT_NE(f.rgb, read_png(pngs[i - 2].path).rgb) << "page " << page << " repeats";
    }
  }
  try {
    check_card_size(160, 120, "--size");
    FAIL() << "160x120 accepted for a story";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "--size: size 160x120 is too small for the story's cards (valid: 320x240 to "
                                     "4096x4096, even; --simulation-only renders the sampling alone at any size)");
  }
  EXPECT_NO_THROW(check_card_size(320, 240, "--size"));
  o.width = 640;
  o.height = 480;
  EXPECT_EQ(card_pages(parts, o, cards)[0], 1) << "640x480: one page";
  fs::remove_all(d);
}

TEST(VideoJob, SpeedShortensTheVideo) {
  const auto& r = run_of(testing::kLineScenario);
  const fs::path d = testing::fresh_dir("job_speed");
  RenderOptions o = tiny();
  const VideoSummary normal = render_video({run_view(r, "")}, o, "", {{0, (d / "a.png").string()}});
  o.speed = 2.0;
  const VideoSummary fast = render_video({run_view(r, "")}, o, (d / "v.mp4").string(), {});
  const double span = r.log.rows.back().t - r.log.rows.front().t;
  EXPECT_EQ(fast.frames, static_cast<int>(std::floor(span * 10.0 + 1e-9)) + 1);
  EXPECT_EQ(normal.frames, 1) << "PNG only: one frame rendered";
  fs::remove_all(d);
}

TEST(VideoJob, BadFrameOrPathLeavesNothing) {
  const auto& r = run_of(testing::kLineScenario);
  const fs::path d = testing::fresh_dir("job_bad");
  try {
    render_video({run_view(r, "")}, tiny(), (d / "v.mp4").string(), {{100000, (d / "f.png").string()}});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--frame-png 100000: the video has"), std::string::npos) << e.what();
  }
  EXPECT_THROW(render_video({run_view(r, "")}, tiny(), (d / "v.mp4").string(),
                            {{1, "/nonexistent-gpm-folder/f.png"}}),
               InputError);
  EXPECT_THROW(render_video({run_view(r, "")}, tiny(), "/nonexistent-gpm-folder/v.mp4", {{1, (d / "f.png").string()}}),
               InputError);
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

}  // namespace
}  // namespace gpm::render
