// bench_render: frames per second of off-screen rendering alone and of
// rendering plus H.264 encoding, at a given size and quality, on one
// scenario's run (default scenarios/simulate_circle.yaml, 640x480, fast);
// then the whole run through gpm render's video job, overlapped (render and
// encode on two threads) and sequential.
//   bench_render [SCENARIO.yaml] [--size WxH] [--quality fast|high] [--frames N] [--repeat R]
// Prints "name frames_per_second" lines.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <time.h>

#include "render/render_options.hpp"
#include "render/scene_renderer.hpp"
#include "render/video_encoder.hpp"
#include "render/video_job.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

int main(int argc, char** argv) {
  using namespace gpm;
  std::string scenario = std::string(GPM_SCENARIOS_DIR) + "/simulate_circle.yaml";
  render::RenderOptions o;
  int frames = 240;
  int repeat = 3;
  try {
    for (int i = 1; i < argc; ++i) {
      if (!std::strcmp(argv[i], "--size") && i + 1 < argc) render::parse_size(argv[++i], "--size", o.width, o.height);
      else if (!std::strcmp(argv[i], "--quality") && i + 1 < argc) o.quality = render::parse_quality(argv[++i], "--quality");
      else if (!std::strcmp(argv[i], "--frames") && i + 1 < argc) frames = std::stoi(argv[++i]);
      else if (!std::strcmp(argv[i], "--repeat") && i + 1 < argc) repeat = std::max(1, std::stoi(argv[++i]));
      else if (argv[i][0] != '-') scenario = argv[i];
      else {
        std::fprintf(stderr, "usage: bench_render [SCENARIO] [--size WxH] [--quality fast|high] [--frames N] [--repeat R]\n");
        return 2;
      }
    }
    const sim::Scenario s = sim::load_scenario(scenario);
    const sim::SimulationResult r = sim::run_simulation(s);
    render::SceneRenderer sr({render::run_view(r, s.name)}, o);
    const double t0 = sr.start_time(), span = sr.end_time() - t0;
    using Clock = std::chrono::steady_clock;
    auto t = Clock::now();
    for (int k = 0; k < frames; ++k) sr.render(t0 + span * k / frames);
    const double render_fps = frames / std::chrono::duration<double>(Clock::now() - t).count();
    const std::string out = (std::filesystem::temp_directory_path() / "gpm_bench_render.mp4").string();
    t = Clock::now();
    {
      render::VideoEncoder enc(out, o.width, o.height, o.fps);
      for (int k = 0; k < frames; ++k) enc.add_frame(sr.render(t0 + span * k / frames));
      enc.finish();
    }
    const double both_fps = frames / std::chrono::duration<double>(Clock::now() - t).count();
    std::filesystem::remove(out);
    // The whole run through gpm render's video job (render/video_job.hpp):
    // render and encode overlapped on two threads (render/frame_queue.hpp)
    // and one after the other, alternated `repeat` times; the best of each
    // (a shared machine only ever slows a run down).
    // Also the CPU time per frame (all threads of the process), which a
    // loaded machine changes less than the wall time: with two idle cores the
    // overlapped pipeline can reach about 2000 / (cpu ms per frame) frames/s.
    double overlapped_fps = 0.0, sequential_fps = 0.0, cpu_ms = 1e300;
    const auto cpu_s = [] {
      timespec ts{};
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
      return ts.tv_sec + 1e-9 * ts.tv_nsec;
    };
    for (int rep = 0; rep < repeat; ++rep) {
      for (const render::Pipeline p : {render::Pipeline::kOverlapped, render::Pipeline::kSequential}) {
        render::VideoJobOptions job;
        job.pipeline = p;
        const double c0 = cpu_s();
        const render::VideoSummary v = render::render_video({render::run_view(r, s.name)}, o, out, {}, job);
        if (p == render::Pipeline::kOverlapped) cpu_ms = std::min(cpu_ms, 1e3 * (cpu_s() - c0) / v.frames);
        std::filesystem::remove(out);
        double& best = p == render::Pipeline::kOverlapped ? overlapped_fps : sequential_fps;
        best = std::max(best, v.frames_per_s);
      }
    }
    std::printf("renderer %s\n", sr.gl_renderer().c_str());
    std::printf("render_%dx%d_%s %.1f\n", o.width, o.height, render::quality_name(o.quality).c_str(), render_fps);
    std::printf("render_encode_%dx%d_%s %.1f\n", o.width, o.height, render::quality_name(o.quality).c_str(), both_fps);
    std::printf("video_job_sequential_%dx%d_%s %.1f\n", o.width, o.height, render::quality_name(o.quality).c_str(),
                sequential_fps);
    std::printf("video_job_overlapped_%dx%d_%s %.1f\n", o.width, o.height, render::quality_name(o.quality).c_str(),
                overlapped_fps);
    std::printf("video_job_cpu_ms_per_frame_%dx%d_%s %.2f\n", o.width, o.height,
                render::quality_name(o.quality).c_str(), cpu_ms);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 2;
  }
  return 0;
}
