// The window context: a GLFW window with an OpenGL 3.3 core forward-compatible context.
#include <glad/gl.h>
// GLFW must not include any GL header of its own: glad's header is the only one.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "context_internal.hpp"
#include "render/context.hpp"

#include <stdexcept>
#include <string>

namespace gs::render {
namespace {

int gWindowCount = 0;           // live window contexts
bool gGlfwInitialized = false;  // GLFW stays initialized until terminateWindowSystem()

GLADapiproc glfwGetProc(const char* name) {
  return reinterpret_cast<GLADapiproc>(glfwGetProcAddress(name));
}

std::string glfwLastError() {
  const char* description = nullptr;
  const int code = glfwGetError(&description);
  if (code == GLFW_NO_ERROR) return "unknown GLFW error";
  return description != nullptr ? std::string(description) : "GLFW error " + std::to_string(code);
}

class GlfwContext final : public WindowContext {
 public:
  GlfwContext(const std::string& title, int width, int height, int samples) {
    if (width < 1 || height < 1)
      throw std::runtime_error("cannot open a window: invalid size " + std::to_string(width) + "x" +
                               std::to_string(height));
    if (!gGlfwInitialized) {
      if (glfwInit() != GLFW_TRUE)
        throw std::runtime_error("cannot open a window: GLFW initialization failed (" +
                                 glfwLastError() +
                                 "); is there a display? Set DISPLAY, run under Xvfb, or use "
                                 "the off-screen mode");
      gGlfwInitialized = true;
    }
    ++gWindowCount;
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    // Not forward-compatible: that would refuse glLineWidth above 1 (LineProperties).
    glfwWindowHint(GLFW_DEPTH_BITS, 24);
    glfwWindowHint(GLFW_STENCIL_BITS, 8);
    glfwWindowHint(GLFW_SAMPLES, samples > 1 ? samples : 0);  // anti-aliasing
    // OpenGL 4.5 core (the GPU sort's compute shaders need 4.3; a driver may give the
    // version asked for and no more), else 3.3 core.
    for (const int minor : {5, 3}) {
      glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, minor == 5 ? 4 : 3);
      glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
      window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
      if (window_ != nullptr) break;
    }
    if (window_ == nullptr) {
      const std::string reason = glfwLastError();
      release();
      throw std::runtime_error("cannot open a window with an OpenGL 3.3 core context: " + reason);
    }
    try {
      makeCurrent();
    } catch (...) {
      glfwDestroyWindow(window_);
      window_ = nullptr;
      release();
      throw;
    }
    glfwSwapInterval(1);
  }

  ~GlfwContext() override {
    if (detail::glFunctionsLoadedFor(this)) detail::setGlFunctionsLoadedFor(nullptr);
    if (window_ != nullptr) glfwDestroyWindow(window_);
    release();
  }

  void makeCurrent() override {
    if (!detail::glFunctionsLoadedFor(this)) {
      // Another context (e.g. OSMesa, which shares Mesa's dispatch) may have been made
      // current behind GLFW's and GLX's back; both skip a make-current of the context they
      // believe current, so release it first to force a real rebind.
      glfwMakeContextCurrent(nullptr);
    }
    glfwMakeContextCurrent(window_);
    if (!detail::glFunctionsLoadedFor(this)) {
      loadGlFunctions(&glfwGetProc);
      detail::setGlFunctionsLoadedFor(this);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
  }
  int width() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return w;
  }
  int height() const override {
    int w = 0, h = 0;
    glfwGetFramebufferSize(window_, &w, &h);
    return h;
  }
  void swapBuffers() override { glfwSwapBuffers(window_); }
  GLADloadfunc getProcAddress() const override { return &glfwGetProc; }
  GLuint drawFramebuffer() const override { return 0; }
  GLFWwindow* glfwHandle() const override { return window_; }

 private:
  static void release() { --gWindowCount; }
  GLFWwindow* window_ = nullptr;
};

}  // namespace

bool terminateWindowSystem() {
  if (gWindowCount > 0) return false;
  if (gGlfwInitialized) glfwTerminate();
  gGlfwInitialized = false;
  return true;
}

std::unique_ptr<WindowContext> createWindowContext(const std::string& title, int width, int height,
                                                   int samples) {
  return std::make_unique<GlfwContext>(title, width, height, samples);
}

}  // namespace gs::render
