// A headless OpenGL context through OSMesa (software rendering, llvmpipe):
// no display, no window system. MuJoCo's renderer draws into its own
// off-screen framebuffer object inside this context.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "models/errors.hpp"

namespace gpm::render {

// A failure of the rendering or encoding machinery itself (not the user's input).
class RenderError : public Error {
 public:
  explicit RenderError(const std::string& what) : Error(what) {}
};

// Largest frame side (pixels) the command line accepts; MuJoCo's off-screen
// buffer is sized to the frame, and llvmpipe allows renderbuffers up to
// 16384, so 4096 keeps a frame at most 64 MB.
inline constexpr int kMaxFrameSide = 4096;

// An OSMesa RGBA context with 24-bit depth and 8-bit stencil. Not copyable;
// one per renderer.
class OffscreenContext {
 public:
  // Creates the context and makes it current on this thread; throws
  // RenderError if OSMesa cannot.
  OffscreenContext();
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  // Makes this context current on the calling thread; throws RenderError.
  void make_current();

  // GL_MAX_RENDERBUFFER_SIZE of the implementation (pixels).
  int max_renderbuffer_size() const { return max_renderbuffer_; }

  // The GL renderer string (e.g. "llvmpipe (LLVM 15.0.6, 256 bits)").
  const std::string& renderer() const { return renderer_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int max_renderbuffer_ = 0;
  std::string renderer_;
};

}  // namespace gpm::render
