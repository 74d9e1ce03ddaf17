// What a video looks like: frame size, frame rate, camera, quality and
// playback speed; from the scenario's `render` section and the command line.
//
// Scenario section (every key optional):
//   render:
//     size: 640x480        # WxH pixels, even (H.264 4:2:0), at most kMaxFrameSide
//     fps: 30              # video frames per second
//     camera: top          # top, oblique, or a camera defined in the model
//     quality: fast        # fast (no multisampling, no shadows) or high (4x MSAA + shadows)
//     speed: 1             # simulated seconds per video second
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace gpm::render {

enum class Quality { kFast, kHigh };

struct RenderOptions {
  int width = 640;
  int height = 480;
  double fps = 30.0;
  std::string camera = "top";
  Quality quality = Quality::kFast;
  double speed = 1.0;
};

// Parses "WxH" (e.g. "640x480"); throws InputError naming `what` for a
// malformed, non-positive, odd or too large size (the message gives the maximum).
void parse_size(const std::string& text, const std::string& what, int& width, int& height);

// Checks a size: positive, even, at most kMaxFrameSide per side; throws
// InputError naming `what`.
void check_size(int width, int height, const std::string& what);

// The smallest frame of a video with cards (a gpm run scenario's story):
// MuJoCo's overlay font is 18 px high at every size, so a smaller frame
// would show the opening card in tens of pages.
inline constexpr int kMinCardWidth = 320;
inline constexpr int kMinCardHeight = 240;

// Checks a video with cards is at least kMinCardWidth x kMinCardHeight;
// throws InputError naming `what` (e.g. "--size") and the valid range.
void check_card_size(int width, int height, const std::string& what);

// Parses "fast" or "high"; throws InputError naming `what`.
Quality parse_quality(const std::string& text, const std::string& what);

// Options from the `render` section of a scenario root (defaults where
// absent); throws InputError naming the file, line and key.
RenderOptions render_options_from_yaml(const YAML::Node& root, const std::string& file);

// Options from the `render` section of a scenario file.
RenderOptions render_options_from_file(const std::string& scenario_file);

// "fast" or "high".
std::string quality_name(Quality q);

}  // namespace gpm::render
