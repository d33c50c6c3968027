// Private to render/: the float layer of the GL splat paths. Thousands to millions of faint
// Gaussians blended back to front straight into an 8-bit framebuffer lose their light to
// rounding: dst = src + dst (1 - alpha) with alpha near 1/255 leaves dst unchanged and adds
// src rounded, so a CT volume's haze came out redder and speckled (CThead's whole stream,
// 5.9 M vectors: 29.8 dB from the cpu path's picture, which composites in float). The GL
// paths therefore draw into this layer (RGBA16F, the viewport's size, cleared to
// transparent black, the scene's depth copied in so that the depth test sees the scene)
// and composite it over the framebuffer once, premultiplied (ONE, ONE_MINUS_SRC_ALPHA):
// mathematically the same picture as blending into the framebuffer directly, rounded once.
// Measured (docs/rendering.md, "The GL paths' float layer"): CThead's whole stream 41.8 dB
// from the cpu path with RGBA16F, 67.3 dB with RGBA32F; on an H200, RGBA16F costs 2-10% of
// a frame (37% for a small scene at 1080p), RGBA32F 1.3-4.5x, so half floats it is.
// Where the scene's depth cannot be copied (a depth format other than DEPTH24_STENCIL8),
// begin() says so and the caller draws into the framebuffer as before.
#pragma once

#include <glad/gl.h>

namespace gs::render::detail {

/// The layer's colour format: GL_RGBA16F (the default), GL_RGBA32F with
/// GHOSTSPACE_SPLAT_LAYER=float32, GL_NONE (no layer: the splats blend straight into the
/// framebuffer, as before) with GHOSTSPACE_SPLAT_LAYER=off; read once per process (another
/// value: said on stderr, float16 used). A switch for measuring the layer
/// (docs/rendering.md), not an option for users.
GLenum splatLayerFormat();

/// The premultiplied layer-over-framebuffer program shared with the cpu path: a quad over
/// the viewport; pixel (x, y) of the framebuffer takes texel (x, y) - `u_origin` (ivec2,
/// pixels: the viewport's lower left corner) of `u_layer` (texture unit 0). Throws
/// std::runtime_error when it does not compile. Context current.
GLuint buildLayerProgram();

class FloatSplatLayer {
 public:
  FloatSplatLayer() = default;
  FloatSplatLayer(const FloatSplatLayer&) = delete;
  FloatSplatLayer& operator=(const FloatSplatLayer&) = delete;

  /// Makes the layer the draw target for the splats of `viewport` (x, y, width, height in
  /// pixels of the current draw framebuffer): grown to hold it (kept between frames and
  /// viewports; its lower left width x height used), that corner's colour cleared to 0,
  /// depth copied from the framebuffer (cleared to 1 where it has none),
  /// the GL viewport (0, 0, width, height), scissor test off. Returns false and changes
  /// nothing when the depth could not be copied, or when the driver refused the layer
  /// itself (said once on stderr; not tried again until release()). Context current.
  bool begin(const int viewport[4]);
  /// Binds the framebuffers, viewport and scissor test begin() found again and composites
  /// the layer over the viewport (inside any scissor box set), premultiplied; leaves
  /// blending off and the depth test on, as the splat pass does.
  void end();
  /// Frees the GL objects (context current).
  void release();

 private:
  GLuint framebuffer_ = 0, color_ = 0, depth_ = 0, program_ = 0, vao_ = 0;
  int width_ = 0, height_ = 0;
  GLint drawFramebuffer_ = 0, readFramebuffer_ = 0;
  GLint viewport_[4] = {0, 0, 0, 0};
  GLboolean scissored_ = GL_FALSE;
  bool refused_ = false;  // the driver refused the layer's storage
};

}  // namespace gs::render::detail
