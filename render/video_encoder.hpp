// H.264 MP4 video through libavcodec (libx264) and libavformat, in process:
// no external program, errors reported where they happen. Written to a
// temporary file in the destination's folder and renamed by finish(); a
// destroyed, unfinished encoder removes its temporary file.
#pragma once

#include <memory>
#include <string>

#include "render/frame_image.hpp"

namespace gpm::render {

// Encoder settings: x264 preset and constant rate factor (lower = better).
struct VideoSettings {
  std::string preset = "veryfast";
  int crf = 20;
};

class VideoEncoder {
 public:
  // Opens the temporary file next to path for a width x height video at fps
  // frames per second (sizes even). Throws InputError naming path if it
  // cannot be written, RenderError if no H.264 encoder is available.
  VideoEncoder(const std::string& path, int width, int height, double fps, const VideoSettings& settings = {});
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  // Encodes one frame (same size as the video). Throws InputError on write
  // failure (disk full), RenderError for encoder failures.
  void add_frame(const FrameImage& img);

  // Flushes the encoder, writes the trailer and renames the file into place.
  void finish();

  int frames() const { return frames_; }
  // Name of the codec in use (e.g. "libx264").
  std::string codec_name() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int frames_ = 0;
};

}  // namespace gpm::render
