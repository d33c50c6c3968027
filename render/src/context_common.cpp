// Context-independent parts of context.hpp: the GL loader, GlInfo, Framebuffer and reading
// the framebuffer (image.hpp's readPixels).
#include <glad/gl.h>

#include "context_internal.hpp"
#include "render/context.hpp"
#include "render/image.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

namespace gs::render {

namespace detail {
namespace {
const void* gLoadedFor = nullptr;
}  // namespace
bool glFunctionsLoadedFor(const void* context) {
  return gLoadedFor == context;
}
void setGlFunctionsLoadedFor(const void* context) {
  gLoadedFor = context;
}
}  // namespace detail

std::unique_ptr<GlContext> createOffscreenContext(int width, int height, int samples) {
  const char* choice = std::getenv("GHOSTSPACE_GL");
  const std::string gl = choice == nullptr ? std::string() : std::string(choice);
  if (gl.empty() || gl == "osmesa") return detail::createOsMesaContext(width, height, samples);
  if (gl == "egl") return detail::createEglContext(width, height, samples);
  throw std::runtime_error("GHOSTSPACE_GL=" + gl +
                           ": expected osmesa (the default, llvmpipe on the CPU) or egl (the "
                           "GPU's driver, no window system)");
}

void loadGlFunctions(GLADloadfunc getProcAddress) {
  detail::setGlFunctionsLoadedFor(nullptr);
  if (getProcAddress == nullptr)
    throw std::runtime_error("cannot load OpenGL functions: no GetProcAddress function given");
  const int version = gladLoadGL(getProcAddress);
  if (version == 0)
    throw std::runtime_error(
        "cannot load OpenGL functions: the loader found no OpenGL context current on this "
        "thread (make the context current first)");
  const int major = GLAD_VERSION_MAJOR(version), minor = GLAD_VERSION_MINOR(version);
  if (major < 3 || (major == 3 && minor < 3))
    throw std::runtime_error("OpenGL 3.3 core is required, the context gives " +
                             std::to_string(major) + "." + std::to_string(minor));
}

GlInfo glInfo() {
  auto str = [](GLenum name) {
    if (glad_glGetString == nullptr) return std::string();
    const GLubyte* s = glGetString(name);
    return s == nullptr ? std::string() : std::string(reinterpret_cast<const char*>(s));
  };
  return GlInfo{str(GL_VENDOR), str(GL_RENDERER), str(GL_VERSION),
                str(GL_SHADING_LANGUAGE_VERSION)};
}

namespace {
void checkSize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw std::runtime_error("invalid framebuffer size " + std::to_string(width) + "x" +
                             std::to_string(height) + " (each side must be 1..16384 pixels)");
}
}  // namespace

Framebuffer::Framebuffer(int width, int height, int samples)
    : width_(width), height_(height), samples_(std::max(1, samples)) {
  checkSize(width, height);
  if (glad_glGenFramebuffers == nullptr)
    throw std::runtime_error("cannot create a framebuffer: OpenGL functions are not loaded");
  if (samples_ > 1) {
    GLint most = 1;
    glGetIntegerv(GL_MAX_SAMPLES, &most);
    samples_ = std::clamp(samples_, 1, std::max(1, static_cast<int>(most)));
  }
  glGenFramebuffers(1, &fbo_);
  glGenRenderbuffers(1, &color_);
  glGenRenderbuffers(1, &depth_);
  allocate();
}

Framebuffer::~Framebuffer() {
  if (glad_glDeleteFramebuffers == nullptr) return;
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &color_);
  glDeleteRenderbuffers(1, &depth_);
}

void Framebuffer::allocate() {
  GLint previous = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  // 0 samples: a single-sample renderbuffer, as glRenderbufferStorage makes.
  const GLsizei samples = samples_ > 1 ? samples_ : 0;
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width_, height_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH24_STENCIL8, width_, height_);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("cannot create a " + std::to_string(width_) + "x" +
                             std::to_string(height_) + " framebuffer object: status 0x" + [&] {
                               char buf[16];
                               std::snprintf(buf, sizeof buf, "%x", status);
                               return std::string(buf);
                             }());
}

void Framebuffer::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
}

void Framebuffer::resize(int width, int height) {
  checkSize(width, height);
  width_ = width;
  height_ = height;
  allocate();
}

Image readPixels(int x, int y, int w, int h) {
  if (w <= 0 || h <= 0)
    throw std::runtime_error("readPixels: invalid size " + std::to_string(w) + "x" +
                             std::to_string(h));
  Image image(w, h);
  std::vector<std::uint8_t> bottomUp(image.rgba.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  readFramebufferPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bottomUp.data());
  const std::size_t row = static_cast<std::size_t>(w) * 4;
  for (int r = 0; r < h; ++r)
    std::copy_n(bottomUp.data() + static_cast<std::size_t>(h - 1 - r) * row, row,
                image.rgba.data() + static_cast<std::size_t>(r) * row);
  return image;
}

int drawFramebufferSamples() {
  GLint samples = 0;
  glGetIntegerv(GL_SAMPLES, &samples);
  return std::max(1, static_cast<int>(samples));
}

void readFramebufferPixels(int x, int y, int width, int height, GLenum format, GLenum type,
                           void* pixels) {
  GLint sampleBuffers = 0;
  glGetIntegerv(GL_SAMPLE_BUFFERS, &sampleBuffers);
  if (sampleBuffers <= 0 || x < 0 || y < 0) {  // (negative: GL's error, for the caller)
    glReadPixels(x, y, width, height, format, type, pixels);
    return;
  }
  // Resolve the rectangle into a single-sample FBO, at the same place (OpenGL ES and some
  // drivers resolve only between equal rectangles), then read it there.
  const bool depth = format == GL_DEPTH_COMPONENT;
  GLint read = 0, draw = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
  GLuint fbo = 0, buffer = 0;
  glGenFramebuffers(1, &fbo);
  glGenRenderbuffers(1, &buffer);
  glBindRenderbuffer(GL_RENDERBUFFER, buffer);
  glRenderbufferStorage(GL_RENDERBUFFER, depth ? GL_DEPTH24_STENCIL8 : GL_RGBA8, x + width,
                        y + height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER,
                            depth ? GL_DEPTH_STENCIL_ATTACHMENT : GL_COLOR_ATTACHMENT0,
                            GL_RENDERBUFFER, buffer);
  // The scissor test clips blits: the resolve copies the whole rectangle.
  const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
  glDisable(GL_SCISSOR_TEST);
  glBlitFramebuffer(x, y, x + width, y + height, x, y, x + width, y + height,
                    depth ? GL_DEPTH_BUFFER_BIT : GL_COLOR_BUFFER_BIT, GL_NEAREST);
  if (scissor == GL_TRUE) glEnable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glReadPixels(x, y, width, height, format, type, pixels);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(draw));
  glDeleteFramebuffers(1, &fbo);
  glDeleteRenderbuffers(1, &buffer);
}

}  // namespace gs::render
