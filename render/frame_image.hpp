// One rendered frame: 8-bit RGB, rows top-down (row 0 is the top of the image).
#pragma once

#include <cstdint>
#include <vector>

namespace gpm::render {

struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgb;  // width * height * 3 bytes, rows top-down

  // Pointer to pixel (x, y), y counted from the top.
  const std::uint8_t* at(int x, int y) const { return rgb.data() + (static_cast<size_t>(y) * width + x) * 3; }
};

}  // namespace gpm::render
