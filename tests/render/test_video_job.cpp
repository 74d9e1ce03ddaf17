// Tests of render/video_job.cpp: the frame timeline, whole videos with PNG
// snapshots, reproducibility, the overlapped pipeline against the sequential
// one, videos in parts, and all-or-nothing failures.
#include <fstream>
#include <iterator>

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
