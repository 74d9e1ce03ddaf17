// Tests of render/video_encoder.cpp: ffprobe reads an H.264 MP4 of the
// expected size, rate and frame count; decoded frames look like the input;
// failures leave no file.
#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "render/png_writer.hpp"
#include "render/video_encoder.hpp"
#include "render_test_util.hpp"

namespace gpm::render {
namespace {

namespace fs = std::filesystem;

// A frame with a bright square at (k * 4, 10): top-left quadrant darker.
FrameImage moving_square(int w, int h, int k) {
  FrameImage img;
  img.width = w;
  img.height = h;
  img.rgb.assign(static_cast<size_t>(w) * h * 3, 40);
  for (int y = 10; y < 30; ++y)
    for (int x = k * 4; x < k * 4 + 20 && x < w; ++x) {
      auto* p = img.rgb.data() + (static_cast<size_t>(y) * w + x) * 3;
      p[0] = 250;
      p[1] = 200;
      p[2] = 30;
    }
  return img;
}

TEST(VideoEncoder, FfprobeReadsSizeRateAndFrameCount) {
  const fs::path d = testing::fresh_dir("enc");
  const std::string out = (d / "v.mp4").string();
  {
    VideoEncoder enc(out, 96, 64, 25.0);
    for (int k = 0; k < 17; ++k) enc.add_frame(moving_square(96, 64, k));
    EXPECT_FALSE(fs::exists(out)) << "only the temporary file exists until finish()";
    enc.finish();
    EXPECT_EQ(enc.frames(), 17);
    EXPECT_EQ(enc.codec_name(), "libx264");
  }
  EXPECT_EQ(testing::probe(out), "h264,96,64,25/1,17\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::remove_all(d);
}

// Frame 9 decoded by ffmpeg matches the frame given, up to compression.
TEST(VideoEncoder, DecodedFrameMatchesTheInput) {
  const fs::path d = testing::fresh_dir("enc_decode");
  const std::string out = (d / "v.mp4").string();
  VideoEncoder enc(out, 96, 64, 30.0);
  for (int k = 0; k < 12; ++k) enc.add_frame(moving_square(96, 64, k));
  enc.finish();
  const std::string png = (d / "f9.png").string();
  int status = -1;
  testing::shell(std::string(GPM_FFMPEG) + " -v error -i '" + out + "' -vf \"select=eq(n\\,9)\" -frames:v 1 '" +
                     png + "'",
                 &status);
  ASSERT_EQ(status, 0);
  const FrameImage got = read_png(png);
  const FrameImage want = moving_square(96, 64, 9);
  ASSERT_EQ(got.rgb.size(), want.rgb.size());
  double diff = 0.0;
  for (size_t i = 0; i < got.rgb.size(); ++i) diff += std::abs(int(got.rgb[i]) - int(want.rgb[i]));
  EXPECT_LT(diff / got.rgb.size(), 6.0);
  // The square is where frame 9 put it (not flipped, not another frame).
  EXPECT_GT(got.at(36 + 10, 20)[0], 200);
  EXPECT_LT(got.at(36 + 10, 50)[0], 80);
  fs::remove_all(d);
}

TEST(VideoEncoder, FractionalFrameRate) {
  const fs::path d = testing::fresh_dir("enc_rate");
  const std::string out = (d / "v.mp4").string();
  VideoEncoder enc(out, 32, 32, 12.5);
  for (int k = 0; k < 5; ++k) enc.add_frame(moving_square(32, 32, k));
  enc.finish();
  EXPECT_EQ(testing::probe(out), "h264,32,32,25/2,5\n");
  fs::remove_all(d);
}

TEST(VideoEncoder, UnfinishedEncoderLeavesNothing) {
  const fs::path d = testing::fresh_dir("enc_abort");
  {
    VideoEncoder enc((d / "v.mp4").string(), 32, 32, 30.0);
    enc.add_frame(moving_square(32, 32, 0));
  }
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

TEST(VideoEncoder, BadOutputAndSizes) {
  EXPECT_THROW(VideoEncoder("/nonexistent-gpm-folder/v.mp4", 32, 32, 30.0), InputError);
  const fs::path d = testing::fresh_dir("enc_bad");
  EXPECT_THROW(VideoEncoder(d.string(), 32, 32, 30.0), InputError);
  EXPECT_THROW(VideoEncoder((d / "v.mp4").string(), 33, 32, 30.0), InputError);
  EXPECT_THROW(VideoEncoder((d / "v.mp4").string(), 32, 32, 0.0), InputError);
  EXPECT_TRUE(fs::is_empty(d));
  fs::remove_all(d);
}

}  // namespace
}  // namespace gpm::render
