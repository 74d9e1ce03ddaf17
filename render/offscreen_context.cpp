#include "render/offscreen_context.hpp"

#include <vector>

#include <GL/osmesa.h>

namespace gpm::render {

// The window-system framebuffer OSMesa needs is never drawn to (MuJoCo renders
// into its off-screen framebuffer object), so it stays tiny.
namespace {
constexpr int kWindowSide = 16;
}

struct OffscreenContext::Impl {
  OSMesaContext ctx = nullptr;
  std::vector<unsigned char> window = std::vector<unsigned char>(kWindowSide * kWindowSide * 4);
};

OffscreenContext::OffscreenContext() : impl_(std::make_unique<Impl>()) {
  impl_->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!impl_->ctx) throw RenderError("OSMesa: cannot create an off-screen OpenGL context");
  make_current();
  GLint max_rb = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
  max_renderbuffer_ = max_rb;
  const GLubyte* name = glGetString(GL_RENDERER);
  renderer_ = name ? reinterpret_cast<const char*>(name) : "unknown";
}

OffscreenContext::~OffscreenContext() {
  if (impl_ && impl_->ctx) OSMesaDestroyContext(impl_->ctx);
}

void OffscreenContext::make_current() {
  if (!OSMesaMakeCurrent(impl_->ctx, impl_->window.data(), GL_UNSIGNED_BYTE, kWindowSide,
                         kWindowSide)) {
    throw RenderError("OSMesa: cannot make the off-screen context current");
  }
}

}  // namespace gpm::render
