// OpenGL contexts: an off-screen one (OSMesa, rendering on the CPU, or EGL on a GPU) and a
// window one (GLFW). After creation both are used the same way: every GL entry point is a function
// pointer loaded by glad through the context's own GetProcAddress (docs/architecture.md, "One
// renderer for window and snapshot": libGL and libOSMesa both export gl*, so a direct call could
// reach the wrong library).
#pragma once

#include <glad/gl.h>

#include <memory>
#include <string>

struct GLFWwindow;

namespace gs::render {

/// A current-able OpenGL 3.3 (or later) core-profile context with a drawing surface.
class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  /// Makes the context current on the calling thread, (re)loads the GL function pointers
  /// when another context was the last one loaded, and binds the context's drawing
  /// framebuffer (the off-screen FBO, or the window's default framebuffer 0).
  /// Throws std::runtime_error when the platform refuses.
  virtual void makeCurrent() = 0;
  /// Width of the drawing surface in pixels (a window's framebuffer, not its screen size).
  virtual int width() const = 0;
  /// Height of the drawing surface in pixels.
  virtual int height() const = 0;
  /// Presents the back buffer of a window; a no-op off-screen.
  virtual void swapBuffers() = 0;
  /// The platform's GetProcAddress in glad's form (OSMesaGetProcAddress or
  /// glfwGetProcAddress), for loaders of other libraries (e.g. an ImGui backend).
  virtual GLADloadfunc getProcAddress() const = 0;
  /// The framebuffer object that makeCurrent() binds for drawing: the off-screen FBO, or 0
  /// for a window. Code that binds other framebuffers rebinds this one afterwards.
  virtual GLuint drawFramebuffer() const = 0;

 protected:
  GlContext() = default;
};

/// An off-screen context of `width` x `height` pixels (each 1..16384), OpenGL 3.3 core
/// requested. Made with OSMesa (llvmpipe, which gives 4.5, on the CPU) unless the
/// environment says GHOSTSPACE_GL=egl: then with EGL on the first EGL device (a GPU's
/// driver, no window system; GHOSTSPACE_EGL_DEVICE=N picks device N), libEGL.so.1 opened
/// at run time. Drawing goes to a framebuffer object of that size with an RGBA8 colour and
/// a 24-bit depth (+8 stencil) buffer; the renderer is the same either way. `samples` > 1
/// makes that FBO multisampled (anti-aliasing, clamped to GL_MAX_SAMPLES; docs/rendering.md,
/// "Anti-aliasing"): readFramebufferPixels resolves it. The context is
/// current and its FBO bound when this returns. Throws std::runtime_error ("cannot create
/// an OSMesa context: ...", "cannot create an EGL context (GHOSTSPACE_GL=egl): ...", or
/// "GHOSTSPACE_GL=X: expected osmesa or egl") when the context or the FBO cannot be made.
std::unique_ptr<GlContext> createOffscreenContext(int width, int height, int samples = 1);

/// A context owned by a GLFW window.
class WindowContext : public GlContext {
 public:
  /// The GLFW window, for input callbacks and the ImGui GLFW backend.
  virtual GLFWwindow* glfwHandle() const = 0;
};

/// Opens a visible window titled `title` with a client area of `width` x `height` screen
/// coordinates and an OpenGL 3.3 core forward-compatible context, initializing GLFW on
/// first use (it stays initialized until terminateWindowSystem()). `samples` > 1 asks for
/// a multisampled window framebuffer (GLFW_SAMPLES, a soft constraint: a display without
/// one gives fewer). The context is current and its functions loaded when this returns;
/// vsync is on. Throws std::runtime_error ("cannot open a window: ...", e.g. when there is
/// no display: set DISPLAY or run under Xvfb, or use createOffscreenContext).
std::unique_ptr<WindowContext> createWindowContext(const std::string& title, int width, int height,
                                                   int samples = 1);

/// Samples per pixel of the draw framebuffer bound in the current context (GL_SAMPLES of
/// a multisampled FBO or window; 1 for one sample, the driver's 0 included): what a
/// context made with `samples` actually got (Browser.getRenderingProperty("Antialiased")).
int drawFramebufferSamples();

/// Terminates GLFW when no window context is alive (returns false and does nothing
/// otherwise). Optional: the process may simply exit. Terminating unloads Mesa's GLX
/// driver, whose own allocations LeakSanitizer then reports as leaks from an unloaded
/// module, so sanitizer runs should leave GLFW initialized.
bool terminateWindowSystem();

/// Loads every GL entry point through `getProcAddress` for the context current on this
/// thread (the window path calls it after glfwMakeContextCurrent with glfwGetProcAddress;
/// GlContext::makeCurrent does it for you). Throws std::runtime_error when the context is
/// older than OpenGL 3.3 or the loader finds no functions.
void loadGlFunctions(GLADloadfunc getProcAddress);

/// Strings describing the current context (GL_VENDOR, GL_RENDERER, GL_VERSION,
/// GL_SHADING_LANGUAGE_VERSION); empty strings when a query fails.
struct GlInfo {
  std::string vendor, renderer, version, shadingLanguageVersion;
};
/// Queries GlInfo from the current context (functions must be loaded).
GlInfo glInfo();

/// A framebuffer object with an RGBA8 colour and a depth24/stencil8 renderbuffer: the
/// off-screen context draws into one, and a window can render a screenshot of any size
/// into one. Needs a current context for its whole life (the destructor frees the GL
/// objects in the context current then).
class Framebuffer {
 public:
  /// Creates the FBO of `width` x `height` pixels (1..16384 each); does not bind it.
  /// `samples` > 1: multisampled renderbuffers of that many samples per pixel, clamped to
  /// GL_MAX_SAMPLES (0 and 1: one sample). Throws std::runtime_error when the size is
  /// invalid or the FBO is incomplete.
  Framebuffer(int width, int height, int samples = 1);
  ~Framebuffer();
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  /// Binds the FBO for drawing and reading and sets the viewport to its full size.
  void bind() const;
  /// Reallocates the renderbuffers at a new size (contents are undefined afterwards).
  void resize(int width, int height);
  GLuint id() const { return fbo_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  void allocate();
  GLuint fbo_ = 0, color_ = 0, depth_ = 0;
  int width_ = 0, height_ = 0, samples_ = 1;
};

/// glReadPixels of the rectangle (`x`, `y` >= 0: bottom-left corner, window pixels; `width`
/// x `height` >= 1) of the bound read framebuffer into `pixels`, rows bottom to top. A
/// multisampled read framebuffer (GL_SAMPLE_BUFFERS > 0, an anti-aliased window or FBO,
/// which glReadPixels cannot read) is first resolved into a single-sample one by
/// glBlitFramebuffer: colour averaged over the samples, GL_DEPTH_COMPONENT one sample per
/// pixel. `format` and `type` as glReadPixels takes them (GL_RGBA or GL_DEPTH_COMPONENT).
/// The read framebuffer binding is restored. GL errors are left for the caller's
/// glGetError (e.g. a window's depth format that the blit cannot copy).
void readFramebufferPixels(int x, int y, int width, int height, GLenum format, GLenum type,
                           void* pixels);

}  // namespace gs::render
