// The off-screen context: OSMesa (llvmpipe) drawing into a framebuffer object.
// glad's header must come before OSMesa's: it defines gl.h's guard (__gl_h_) so
// <GL/osmesa.h> does not pull in Mesa's own prototypes, and it provides the GL types and
// the GLAPI/GLAPIENTRY macros that osmesa.h uses. This is the only file that includes an
// OSMesa header.
#include <glad/gl.h>
// (keep this order)
#include <GL/osmesa.h>

#include "context_internal.hpp"
#include "render/context.hpp"

#include <memory>
#include <stdexcept>
#include <string>

namespace gs::render {
namespace {

GLADapiproc osmesaGetProc(const char* name) {
  return reinterpret_cast<GLADapiproc>(OSMesaGetProcAddress(name));
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height, int samples) : width_(width), height_(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
      throw std::runtime_error("cannot create an OSMesa context: invalid size " +
                               std::to_string(width) + "x" + std::to_string(height) +
                               " (each side must be 1..16384 pixels)");
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           8,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (context_ == nullptr)
      throw std::runtime_error(
          "cannot create an OSMesa context: OSMesaCreateContextAttribs refused an OpenGL 3.3 "
          "core profile (is libosmesa6 with the llvmpipe driver installed? "
          "LIBGL_ALWAYS_SOFTWARE and GALLIUM_DRIVER=llvmpipe may help)");
    try {
      // OSMesa needs a client buffer to make the context current; drawing goes to our FBO,
      // so a single pixel is enough.
      bindContext();
      framebuffer_ = std::make_unique<Framebuffer>(width, height, samples);
      framebuffer_->bind();
    } catch (...) {
      detail::setGlFunctionsLoadedFor(nullptr);
      OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
      OSMesaDestroyContext(context_);
      throw;
    }
  }

  ~OsMesaContext() override {
    // The FBO must be deleted while its context is current.
    if (OSMesaGetCurrentContext() != context_) {
      try {
        bindContext();
      } catch (...) {
      }
    }
    framebuffer_.reset();
    if (detail::glFunctionsLoadedFor(this)) detail::setGlFunctionsLoadedFor(nullptr);
    OSMesaMakeCurrent(nullptr, nullptr, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(context_);
  }

  void makeCurrent() override {
    bindContext();
    framebuffer_->bind();
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void swapBuffers() override {}
  GLADloadfunc getProcAddress() const override { return &osmesaGetProc; }
  GLuint drawFramebuffer() const override { return framebuffer_->id(); }

 private:
  void bindContext() {
    if (!OSMesaMakeCurrent(context_, &pixel_, GL_UNSIGNED_BYTE, 1, 1))
      throw std::runtime_error("cannot create an OSMesa context: OSMesaMakeCurrent failed");
    if (!detail::glFunctionsLoadedFor(this)) {
      loadGlFunctions(&osmesaGetProc);
      detail::setGlFunctionsLoadedFor(this);
    }
  }

  OSMesaContext context_ = nullptr;
  alignas(4) unsigned char pixel_[4] = {0, 0, 0, 0};
  std::unique_ptr<Framebuffer> framebuffer_;
  int width_, height_;
};

}  // namespace

namespace detail {
std::unique_ptr<GlContext> createOsMesaContext(int width, int height, int samples) {
  return std::make_unique<OsMesaContext>(width, height, samples);
}
}  // namespace detail

}  // namespace gs::render
