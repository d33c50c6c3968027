// Private to render/: the CPU splat path (SplatPath::cpu, splat_renderer.hpp), a
// multi-threaded rasterizer of the splat model (splat_model.hpp) for machines whose GL is
// software (llvmpipe, softpipe), where it beats both GL paths (docs/rendering.md).
//
// It draws exactly the picture of the CPU reference of equation (1) (splat_reference.hpp)
// and of the geometry path: every vector is the square patch of +-3 spreads in the plane
// perpendicular to its normal (placed by the model-view matrix, so a scaled Transform
// scales it as the GPU's patch), with the Gaussian profile cut at 3 spreads, flat
// two-sided shading, composited front to back in the given order (DepthSorter's view
// order of the centres, one order for the whole image).
//
// Algorithm, one frame:
// 1. Setup (the order split into one contiguous chunk per thread): each splat's eye-space
//    patch, its pixel box (the patch clipped to the near plane, projected, one pixel of
//    margin, as the reference) and three linear forms in pixel coordinates: the ray
//    parameter's denominator d . N and the patch coordinates' numerators d . T*, d . B*
//    (T*, B* the dual basis of the patch axes): the ray of pixel (x, y) meets the plane at
//    eye depth t = (C . N) / (d . N), and its patch coordinates are t (d . T*) - C . T*.
//    That is the exact perspective intersection the GPU interpolates, evaluated per pixel
//    with a handful of multiplies and one division. Visible splats are binned to 32x32
//    pixel tiles (per chunk, in order).
// 2. Compositing: threads take tiles; per tile, the chunks' bins in order are front to
//    back. Per pixel C += T alpha c, T *= 1 - alpha; a pixel whose transmittance falls
//    below 1/2048 (less than an eighth of a level left) is saturated and skipped, and a
//    tile with no unsaturated pixel left stops. A fragment whose alpha is below half an
//    8-bit level (0.5/255), which RGBA8 blending in the GL paths cannot show, is dropped,
//    and a splat whose peak is below it is not set up. Four pixels at a time (vector extensions),
//    the Gaussian from a polynomial exp; each row only over its exact span of the disk.
// 3. Output: premultiplied RGBA8 (C, 1 - T), rows bottom to top (OpenGL's order), to be
//    blended over the framebuffer with (ONE, ONE_MINUS_SRC_ALPHA).
//
// Threads: max(2, std::thread::hardware_concurrency()) (the calling thread is one),
// started per frame. Scratch buffers live in the object and only grow.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "qnv/decoder.hpp"
#include "render/splat_model.hpp"

namespace gs::render::detail {

/// The view of one CPU splat frame.
struct CpuSplatView {
  glm::mat4 modelView{1.0f};     // model to eye
  glm::mat4 projection{1.0f};    // a perspective projection (projectionMatrix)
  glm::mat3 normalMatrix{1.0f};  // model normals to world normals (the lights' space)
  int width = 0, height = 0;     // viewport, pixels
  float nearClip = 0.1f;         // eye depths drawn: [nearClip, farClip]
  float farClip = 100.0f;
};

class CpuSplatRasterizer {
 public:
  CpuSplatRasterizer();
  ~CpuSplatRasterizer();
  CpuSplatRasterizer(const CpuSplatRasterizer&) = delete;
  CpuSplatRasterizer& operator=(const CpuSplatRasterizer&) = delete;

  /// Composites `vectors[order[i]]`, order[0] nearest (indices outside `vectors` are
  /// skipped), into `out`: width * height * 4 bytes of premultiplied RGBA8, rows bottom to
  /// top. `depth` is empty (nothing hides the splats) or width * height window depths of
  /// the scene (0..1, glDepthRange(0, 1), rows bottom to top, as glReadPixels gives them):
  /// a splat fragment is drawn where its window depth is below the scene's (GL_LESS).
  /// At most 8 lights are used. Nothing happens for a viewport without pixels.
  void draw(std::span<const qnv::DecodedVector> vectors, std::span<const std::uint32_t> order,
            const SplatStyle& style, std::span<const SplatLight> lights, const CpuSplatView& view,
            std::span<const float> depth, std::vector<std::uint8_t>& out);

  /// Threads a frame uses (at least 2).
  int threads() const { return threads_; }

  struct Scratch;  // per-thread setup results and bins (splat_cpu.cpp)

 private:
  int threads_;
  std::unique_ptr<Scratch> scratch_;
};

}  // namespace gs::render::detail
