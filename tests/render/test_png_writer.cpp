// Tests of render/png_writer.cpp: lossless PNG round trip, all-or-nothing.
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "render/png_writer.hpp"
#include "render_test_util.hpp"

namespace gpm::render {
namespace {

namespace fs = std::filesystem;

FrameImage gradient(int w, int h) {
  FrameImage img;
  img.width = w;
  img.height = h;
  img.rgb.resize(static_cast<size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      auto* p = img.rgb.data() + (static_cast<size_t>(y) * w + x) * 3;
      p[0] = static_cast<std::uint8_t>(x * 7);
      p[1] = static_cast<std::uint8_t>(y * 13);
      p[2] = static_cast<std::uint8_t>((x + y) * 3);
    }
  return img;
}

TEST(PngWriter, RoundTripIsExactAndTopRowFirst) {
  const fs::path d = testing::fresh_dir("png");
  const FrameImage img = gradient(37, 21);
  write_png((d / "f.png").string(), img);
  const FrameImage back = read_png((d / "f.png").string());
  EXPECT_EQ(back.width, 37);
  EXPECT_EQ(back.height, 21);
  EXPECT_EQ(back.rgb, img.rgb);
  // An independent reader agrees on size and on the top-left pixel.
  const std::string info = testing::shell(std::string(GPM_FFPROBE) +
                                          " -v error -show_entries stream=width,height -of csv=p=0 '" +
                                          (d / "f.png").string() + "'");
  EXPECT_EQ(info, "37,21\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::remove_all(d);
}

TEST(PngWriter, UnwritablePathLeavesNothing) {
  EXPECT_THROW(write_png("/nonexistent-gpm-folder/f.png", gradient(4, 4)), InputError);
  const fs::path d = testing::fresh_dir("png_dir");
  EXPECT_THROW(write_png(d.string(), gradient(4, 4)), InputError);
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

TEST(PngWriter, ReadingAMissingFileIsAnInputError) {
  EXPECT_THROW(read_png("/nonexistent-gpm-folder/f.png"), InputError);
}

}  // namespace
}  // namespace gpm::render
