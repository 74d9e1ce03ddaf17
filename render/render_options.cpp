#include "render/render_options.hpp"

#include <charconv>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"
#include "render/offscreen_context.hpp"

namespace gpm::render {
namespace {

bool parse_int(std::string_view s, int& out) {
  if (s.empty()) return false;
  const char* end = s.data() + s.size();
  const auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end;
}

}  // namespace

void check_size(int width, int height, const std::string& what) {
  if (width <= 0 || height <= 0)
    throw InputError(fmt::format("{}: size must be positive, got {}x{}", what, width, height));
  if (width > kMaxFrameSide || height > kMaxFrameSide)
    throw InputError(fmt::format("{}: size {}x{} is beyond the off-screen buffer (maximum {}x{})",
                                 what, width, height, kMaxFrameSide, kMaxFrameSide));
  if (width % 2 != 0 || height % 2 != 0)
    throw InputError(fmt::format("{}: size {}x{} must be even in both sides (H.264 4:2:0 video)",
                                 what, width, height));
}

void check_card_size(int width, int height, const std::string& what) {
  if (width < kMinCardWidth || height < kMinCardHeight)
    throw InputError(fmt::format("{}: size {}x{} is too small for the story's cards (valid: {}x{} to {}x{}, even; "
                                 "--simulation-only renders the sampling alone at any size)",
                                 what, width, height, kMinCardWidth, kMinCardHeight, kMaxFrameSide, kMaxFrameSide));
}

void parse_size(const std::string& text, const std::string& what, int& width, int& height) {
  const auto x = text.find_first_of("xX");
  int w = 0, h = 0;
  const bool negative = text.find('-') != std::string::npos;
  if (x == std::string::npos || !parse_int(std::string_view(text).substr(0, x), w) ||
      !parse_int(std::string_view(text).substr(x + 1), h)) {
    if (negative)
      throw InputError(fmt::format("{}: size must be positive, got '{}'", what, text));
    throw InputError(fmt::format("{}: size must be WxH in pixels (e.g. 640x480), got '{}'", what, text));
  }
  check_size(w, h, what);
  width = w;
  height = h;
}

Quality parse_quality(const std::string& text, const std::string& what) {
  if (text == "fast") return Quality::kFast;
  if (text == "high") return Quality::kHigh;
  throw InputError(fmt::format("{}: quality must be fast or high, got '{}'", what, text));
}

std::string quality_name(Quality q) { return q == Quality::kHigh ? "high" : "fast"; }

RenderOptions render_options_from_yaml(const YAML::Node& root, const std::string& file) {
  RenderOptions o;
  if (!root.IsMap() || !root["render"]) return o;
  const YAML::Node r = root["render"];
  if (r.IsNull()) return o;
  yaml_check_keys(r, file, "render", {"size", "fps", "camera", "quality", "speed"});
  if (r["size"]) {
    const std::string where = yaml_where(file, r["size"], "render.size");
    const std::string what = where.substr(0, where.size() - 2);
    if (r["size"].IsSequence() && r["size"].size() == 2) {
      const int w = static_cast<int>(yaml_integer(r["size"][0], file, "render.size[0]", -1000000, 1000000));
      const int h = static_cast<int>(yaml_integer(r["size"][1], file, "render.size[1]", -1000000, 1000000));
      check_size(w, h, what);
      o.width = w;
      o.height = h;
    } else {
      parse_size(yaml_string(r["size"], file, "render.size"), what, o.width, o.height);
    }
  }
  if (r["fps"]) {
    o.fps = yaml_positive(r["fps"], file, "render.fps");
    if (o.fps > 240)
      throw InputError(fmt::format("{}must be at most 240, got {}", yaml_where(file, r["fps"], "render.fps"), o.fps));
  }
  if (r["camera"]) o.camera = yaml_string(r["camera"], file, "render.camera");
  if (r["quality"]) {
    const std::string where = yaml_where(file, r["quality"], "render.quality");
    o.quality = parse_quality(yaml_string(r["quality"], file, "render.quality"),
                              where.substr(0, where.size() - 2));
  }
  if (r["speed"]) o.speed = yaml_positive(r["speed"], file, "render.speed");
  return o;
}

RenderOptions render_options_from_file(const std::string& scenario_file) {
  return render_options_from_yaml(load_yaml_file(scenario_file), scenario_file);
}

}  // namespace gpm::render
