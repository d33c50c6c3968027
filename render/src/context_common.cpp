// Context-independent parts of context.hpp: the GL loader, GlInfo and Framebuffer.
#include <glad/gl.h>

#include "context_internal.hpp"
#include "render/context.hpp"

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

std::unique_ptr<GlContext> createOffscreenContext(int width, int height) {
  const char* choice = std::getenv("GHOSTSPACE_GL");
  const std::string gl = choice == nullptr ? std::string() : std::string(choice);
  if (gl.empty() || gl == "osmesa") return detail::createOsMesaContext(width, height);
  if (gl == "egl") return detail::createEglContext(width, height);
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

Framebuffer::Framebuffer(int width, int height) : width_(width), height_(height) {
  checkSize(width, height);
  if (glad_glGenFramebuffers == nullptr)
    throw std::runtime_error("cannot create a framebuffer: OpenGL functions are not loaded");
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
  glBindRenderbuffer(GL_RENDERBUFFER, color_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, width_, height_);
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

}  // namespace gs::render
