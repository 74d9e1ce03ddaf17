// Shared helpers of the render tests: a short twin run, the pinhole projection
// of the top camera computed from its parameters alone, the end-effector
// marker found in an image, and ffprobe.
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <unistd.h>
#include <string>

#include <Eigen/Core>
#include <mujoco/mujoco.h>

#include "render/frame_image.hpp"
#include "render/scene_renderer.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace gpm::render::testing {

// A 20 mm circle around home after a short move to its start: about 0.7 s.
inline const char* kCircleScenario = R"(
name: tiny_circle
seed: 5
encoder: {noise_rad: 1e-5}
path: {shape: circle, centre: [216.5, 250], radius: 20, period_s: 0.5}
log: {every: 2}
)";

// A short straight line from home: about 0.35 s, logged at the servo rate.
inline const char* kLineScenario = R"(
name: tiny_line
seed: 7
actual: {perturb: {base_mm: 0.5, link_mm: 0.5, offset_rad: 0.01}}
path: {shape: line, from: [216.5, 250], to: [246.5, 230], duration_s: 0.3}
log: {every: 1}
)";

// The simulation of scenario text (cached per text: runs once per test binary).
inline const sim::SimulationResult& run_of(const char* text) {
  static std::map<const char*, sim::SimulationResult> cache;
  auto it = cache.find(text);
  if (it == cache.end()) {
    const sim::Scenario s = sim::parse_scenario(text, "test.yaml", ".");
    it = cache.emplace(text, sim::run_simulation(s)).first;
  }
  return it->second;
}

// Pixel (x from the left, y from the top; continuous, pixel centres at k + 0.5)
// where a free camera looking straight down (elevation -90, azimuth 90: +X
// right, +Y up) at lookat from distance, with vertical field fovy_deg, sees
// the world point p (m), in a viewport of width x height pixels.
inline Eigen::Vector2d project_top(const mjvCamera& cam, double fovy_deg, int width, int height,
                                   const Eigen::Vector3d& p) {
  const double f = 0.5 * height / std::tan(0.5 * fovy_deg * M_PI / 180.0);
  const double depth = (cam.lookat[2] + cam.distance) - p.z();
  return {0.5 * width + f * (p.x() - cam.lookat[0]) / depth,
          0.5 * height - f * (p.y() - cam.lookat[1]) / depth};
}

// Centroid (pixel centres) and count of the magenta marker's pixels within
// columns [x0, x1).
struct Blob {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  int pixels = 0;
};
inline Blob find_marker(const FrameImage& img, int x0 = 0, int x1 = -1) {
  if (x1 < 0) x1 = img.width;
  Blob b;
  for (int y = 0; y < img.height; ++y) {
    for (int x = x0; x < x1; ++x) {
      const std::uint8_t* p = img.at(x, y);
      // Magenta at any brightness the lighting gives it: red and blue alike,
      // both well above green (no chain, path, text or floor colour is so).
      if (p[0] > 2 * p[1] + 40 && p[2] > 2 * p[1] + 40 && std::abs(p[0] - p[2]) < 40) {
        b.centre += Eigen::Vector2d(x + 0.5, y + 0.5);
        ++b.pixels;
      }
    }
  }
  if (b.pixels) b.centre /= b.pixels;
  return b;
}

// Share of the pixels of img within tol (each channel) of the card background.
inline double card_share(const FrameImage& img, int tol = 8) {
  long n = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = img.at(x, y);
      bool near = true;
      for (int c = 0; c < 3; ++c) near = near && std::abs(p[c] - std::lround(255.0 * kCardRgb[c])) <= tol;
      n += near ? 1 : 0;
    }
  return static_cast<double>(n) / (static_cast<double>(img.width) * img.height);
}

// A copy of log with every time shifted by dt (a part that starts later).
inline sim::TrajectoryLog shifted(const sim::TrajectoryLog& log, double dt) {
  sim::TrajectoryLog out = log;
  for (sim::LogRow& r : out.rows) r.t += dt;
  return out;
}

// Output of a shell command (stdout), and its exit status.
inline std::string shell(const std::string& cmd, int* status = nullptr) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char buf[512];
  while (fgets(buf, sizeof(buf), p)) out += buf;
  const int rc = pclose(p);
  if (status) *status = rc;
  return out;
}

// ffprobe's "codec,width,height,frames counted by decoding,r_frame_rate" of a video.
inline std::string probe(const std::string& file) {
  return shell(std::string(GPM_FFPROBE) +
               " -v error -count_frames -select_streams v:0 -show_entries "
               "stream=codec_name,width,height,nb_read_frames,r_frame_rate -of csv=p=0 '" + file + "'");
}

// A fresh empty folder for one test.
inline std::filesystem::path fresh_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("gpm_render_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

}  // namespace gpm::render::testing
