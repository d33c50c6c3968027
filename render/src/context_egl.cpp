// The off-screen context on a real GPU: EGL (a device display, no window system) drawing
// into a framebuffer object, chosen by GHOSTSPACE_GL=egl (context.hpp). libEGL.so.1 is
// opened at run time, so the program neither links nor needs it until asked: the default
// off-screen context stays OSMesa's. glad's header must come before EGL's (it defines the
// GL types and gl.h's guard). This is the only file that includes an EGL header.
#include <glad/gl.h>
// (keep this order)
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>

#include "context_internal.hpp"
#include "render/context.hpp"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gs::render {
namespace {

[[noreturn]] void fail(const std::string& why) {
  throw std::runtime_error("cannot create an EGL context (GHOSTSPACE_GL=egl): " + why);
}

// The EGL entry points, looked up once in libEGL.so.1 (glvnd's dispatcher or Mesa's).
struct EglApi {
  void* library = nullptr;
  PFNEGLGETPROCADDRESSPROC getProcAddress = nullptr;
  PFNEGLGETDISPLAYPROC getDisplay = nullptr;
  PFNEGLINITIALIZEPROC initialize = nullptr;
  PFNEGLBINDAPIPROC bindApi = nullptr;
  PFNEGLCHOOSECONFIGPROC chooseConfig = nullptr;
  PFNEGLCREATECONTEXTPROC createContext = nullptr;
  PFNEGLDESTROYCONTEXTPROC destroyContext = nullptr;
  PFNEGLCREATEPBUFFERSURFACEPROC createPbufferSurface = nullptr;
  PFNEGLDESTROYSURFACEPROC destroySurface = nullptr;
  PFNEGLMAKECURRENTPROC makeCurrent = nullptr;
  PFNEGLGETCURRENTCONTEXTPROC getCurrentContext = nullptr;
  PFNEGLGETERRORPROC getError = nullptr;
  PFNEGLQUERYSTRINGPROC queryString = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;              // EGL_EXT_device_enumeration
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;  // EGL_EXT_platform_base
};

template <typename F>
void symbol(void* library, F& into, const char* name) {
  into = reinterpret_cast<F>(dlsym(library, name));
  if (into == nullptr) fail(std::string("libEGL.so.1 lacks ") + name);
}

const EglApi& egl() {
  static const EglApi api = [] {
    EglApi a;
    a.library = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (a.library == nullptr)
      fail(std::string("cannot open libEGL.so.1 (install libegl1 and the GPU's EGL driver): ") +
           dlerror());
    symbol(a.library, a.getProcAddress, "eglGetProcAddress");
    symbol(a.library, a.getDisplay, "eglGetDisplay");
    symbol(a.library, a.initialize, "eglInitialize");
    symbol(a.library, a.bindApi, "eglBindAPI");
    symbol(a.library, a.chooseConfig, "eglChooseConfig");
    symbol(a.library, a.createContext, "eglCreateContext");
    symbol(a.library, a.destroyContext, "eglDestroyContext");
    symbol(a.library, a.createPbufferSurface, "eglCreatePbufferSurface");
    symbol(a.library, a.destroySurface, "eglDestroySurface");
    symbol(a.library, a.makeCurrent, "eglMakeCurrent");
    symbol(a.library, a.getCurrentContext, "eglGetCurrentContext");
    symbol(a.library, a.getError, "eglGetError");
    symbol(a.library, a.queryString, "eglQueryString");
    a.queryDevices =
        reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(a.getProcAddress("eglQueryDevicesEXT"));
    a.getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        a.getProcAddress("eglGetPlatformDisplayEXT"));
    return a;
  }();
  return api;
}

GLADapiproc eglGetProc(const char* name) {
  return reinterpret_cast<GLADapiproc>(egl().getProcAddress(name));
}

std::string errorText() {
  return "EGL error 0x" + [] {
    char text[16];
    std::snprintf(text, sizeof text, "%04x", static_cast<unsigned>(egl().getError()));
    return std::string(text);
  }();
}

// A display without a window system: the first EGL device (GHOSTSPACE_EGL_DEVICE=N picks
// another), else the default display.
EGLDisplay openDisplay() {
  const EglApi& a = egl();
  if (a.queryDevices != nullptr && a.getPlatformDisplay != nullptr) {
    EGLint count = 0;
    if (a.queryDevices(0, nullptr, &count) && count > 0) {
      std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
      a.queryDevices(count, devices.data(), &count);
      int pick = 0;
      if (const char* n = std::getenv("GHOSTSPACE_EGL_DEVICE")) pick = std::atoi(n);
      if (pick < 0 || pick >= count)
        fail("GHOSTSPACE_EGL_DEVICE=" + std::to_string(pick) + " but there are " +
             std::to_string(count) + " EGL devices (0.." + std::to_string(count - 1) + ")");
      EGLDisplay display = a.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT,
                                                devices[static_cast<std::size_t>(pick)], nullptr);
      if (display != EGL_NO_DISPLAY) return display;
    }
  }
  EGLDisplay display = a.getDisplay(EGL_DEFAULT_DISPLAY);
  if (display == EGL_NO_DISPLAY) fail("no EGL device and no default display");
  return display;
}

class EglContext final : public GlContext {
 public:
  EglContext(int width, int height, int samples) : width_(width), height_(height) {
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
      fail("invalid size " + std::to_string(width) + "x" + std::to_string(height) +
           " (each side must be 1..16384 pixels)");
    const EglApi& a = egl();
    display_ = openDisplay();
    EGLint eglMajor = 0, eglMinor = 0;
    if (!a.initialize(display_, &eglMajor, &eglMinor)) fail("eglInitialize failed, " + errorText());
    try {
      if (!a.bindApi(EGL_OPENGL_API)) fail("the display has no desktop OpenGL, " + errorText());
      const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_NONE};
      EGLConfig config = nullptr;
      EGLint configs = 0;
      if (!a.chooseConfig(display_, configAttribs, &config, 1, &configs) || configs < 1)
        fail("no RGB8 OpenGL pbuffer config, " + errorText());
      // OpenGL 4.5 core (the GPU sort's compute shaders need 4.3; a driver may give the
      // version asked for and no more), else 3.3 core.
      for (const EGLint minor : {5, 3}) {
        const EGLint major = minor == 5 ? 4 : 3;
        const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                         major,
                                         EGL_CONTEXT_MINOR_VERSION,
                                         minor,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                         EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
        context_ = a.createContext(display_, config, EGL_NO_CONTEXT, contextAttribs);
        if (context_ != EGL_NO_CONTEXT) break;
      }
      if (context_ == EGL_NO_CONTEXT)
        fail("eglCreateContext refused OpenGL 4.5 and 3.3 core profiles, " + errorText());
      // Drawing goes to our FBO: a 1x1 pbuffer only gives the context something current.
      const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
      surface_ = a.createPbufferSurface(display_, config, pbufferAttribs);
      if (surface_ == EGL_NO_SURFACE) fail("eglCreatePbufferSurface failed, " + errorText());
      bindContext();
      framebuffer_ = std::make_unique<Framebuffer>(width, height, samples);
      framebuffer_->bind();
    } catch (...) {
      release();
      throw;
    }
  }

  ~EglContext() override {
    if (egl().getCurrentContext() != context_) {
      try {
        bindContext();
      } catch (...) {
      }
    }
    framebuffer_.reset();
    release();
  }

  void makeCurrent() override {
    bindContext();
    framebuffer_->bind();
  }
  int width() const override { return width_; }
  int height() const override { return height_; }
  void swapBuffers() override {}
  GLADloadfunc getProcAddress() const override { return &eglGetProc; }
  GLuint drawFramebuffer() const override { return framebuffer_->id(); }

 private:
  void bindContext() {
    if (!egl().makeCurrent(display_, surface_, surface_, context_))
      fail("eglMakeCurrent failed, " + errorText());
    if (!detail::glFunctionsLoadedFor(this)) {
      loadGlFunctions(&eglGetProc);
      detail::setGlFunctionsLoadedFor(this);
    }
  }

  void release() {
    const EglApi& a = egl();
    if (detail::glFunctionsLoadedFor(this)) detail::setGlFunctionsLoadedFor(nullptr);
    a.makeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) a.destroySurface(display_, surface_);
    if (context_ != EGL_NO_CONTEXT) a.destroyContext(display_, context_);
    // The display is not terminated: EGL keeps one per device, shared by every context.
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
  std::unique_ptr<Framebuffer> framebuffer_;
  int width_, height_;
};

}  // namespace

namespace detail {
std::unique_ptr<GlContext> createEglContext(int width, int height, int samples) {
  return std::make_unique<EglContext>(width, height, samples);
}
}  // namespace detail

}  // namespace gs::render
