// Private to render/: the CPU rasterizer of anisotropic 3D Gaussians (the splat model of
// splats/gaussian.hpp; docs/splats.md), the cpu path of SplatRenderer for every set: a
// splats::GaussianCloud, or QNV vectors as the flat-disc Gaussians of
// render/splat_model.hpp (vectorGaussian). It draws what Kerbl et al. 2023's rasterizer
// draws:
//
// 1. Setup (the splats split into one contiguous index range per thread, read in
//    sequence): each Gaussian's EWA projection (splats::projectGaussian: Sigma' = J W Sigma
//    W^T J^T + 0.3 px, 3-sigma box), its colour (a cloud: its spherical harmonics along the
//    ray from the camera; a vector: shadeSplat's flat two-sided lighting of its normal);
//    then binned to 32x32 pixel tiles in depth order (the order split into one contiguous
//    chunk per thread).
// 2. Compositing: threads take tiles; per pixel, front to back, alpha = min(0.99,
//    o exp(-0.5 d^T Sigma'^-1 d)), fragments with alpha < 1/255 skipped (vectors: below
//    half a level, 0.5/255, what an 8-bit framebuffer can still show), C += T alpha c,
//    T *= 1 - alpha (the paper's equation (1)); a pixel whose transmittance falls below
//    1e-4 is done. Four pixels at a time (vector extensions).
// 3. Output: premultiplied RGBA8 (C, 1 - T), rows bottom to top (OpenGL's order).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "qnv/decoder.hpp"
#include "render/splat_model.hpp"
#include "splats/gaussian.hpp"

namespace gs::render::detail {

/// A rectangle of a view's pixels: x in [x0, x1), y in [y0, y1), rows from the bottom;
/// empty when x0 >= x1 or y0 >= y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x0 >= x1 || y0 >= y1; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  /// The smallest rectangle holding this one and `o` (an empty one as {w, h, 0, 0}).
  PixelRect united(const PixelRect& o) const {
    return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
  }
};

/// The scene's depth under `rect` of the view: rect.width() * rect.height() window depths
/// (0..1, rows bottom to top, glReadPixels' order), or an empty span when there is none to
/// read (then nothing hides a splat). The rasterizer calls it at most once a frame, on the
/// thread that called draw or drawVectors (the one holding the GL context), with the
/// pixels its splats reach: a far cut reads a few tiles of depth, not the whole view.
/// The span must stay valid until the draw returns.
using SceneDepthReader = std::function<std::span<const float>(const PixelRect& rect)>;

/// The view of one CPU Gaussian frame.
struct CpuGaussianView {
  glm::mat4 modelView{1.0f};   // cloud to eye (OpenGL eye, looking down -Z)
  glm::mat4 projection{1.0f};  // a perspective projection (scene::projectionMatrix)
  glm::vec3 eye{0.0f};         // the camera's position in cloud coordinates (SH direction)
  int width = 0, height = 0;   // viewport, pixels
  float nearClip = 0.1f;       // eye depths drawn: [nearClip, farClip]
  float farClip = 100.0f;
  float opacityScale = 1.0f;  // multiplies every opacity (a node's opacityScale)
  SplatFog fog;               // what each splat's colour goes through (by its centre)
};

class CpuGaussianRasterizer {
 public:
  CpuGaussianRasterizer();
  ~CpuGaussianRasterizer();
  CpuGaussianRasterizer(const CpuGaussianRasterizer&) = delete;
  CpuGaussianRasterizer& operator=(const CpuGaussianRasterizer&) = delete;

  /// Composites the Gaussians `cloud[order[i]]`, order[0] nearest (indices outside the
  /// cloud skipped), into `out`: width * height * 4 bytes of premultiplied RGBA8, rows
  /// bottom to top, of which only touched() is written (the rest keeps what it held; a
  /// caller composites that rectangle alone). `depth`, when set, reads the scene's depth
  /// under the pixels the splats reach (SceneDepthReader): a Gaussian is drawn at a pixel
  /// when its centre's window depth is below the scene's there (GL_LESS). Covariances are cached
  /// per cloud (address, size and `revision`): a cloud that changes in place must come
  /// with a new revision.
  /// With a `subset` (indices into the cloud, best ascending: a level-of-detail cut of a
  /// cloud that holds the tree's every node), `order` holds places in the subset instead:
  /// the Gaussians cloud[subset[order[i]]] are drawn (places outside the subset skipped).
  void draw(const splats::GaussianCloud& cloud, std::span<const std::uint32_t> order,
            const CpuGaussianView& view, const SceneDepthReader& depth,
            std::vector<std::uint8_t>& out, std::uint64_t revision = 0,
            std::span<const std::uint32_t> subset = {});

  /// Composites the QNV vectors `vectors[order[i]]` (order[0] nearest; indices outside
  /// skipped) as the flat-disc Gaussians of vectorGaussian under `style`, shaded by
  /// shadeSplat with `lights` (world directions, at most 8 used) and each normal turned by
  /// `normalMatrix` (model to world), each opacity scaled by the projection's lowPassKeep.
  /// `view.eye` and `view.opacityScale` are not used (the style holds the opacity scale).
  /// Output and depth as draw().
  void drawVectors(std::span<const qnv::DecodedVector> vectors,
                   std::span<const std::uint32_t> order, const SplatStyle& style,
                   std::span<const SplatLight> lights, const glm::mat3& normalMatrix,
                   const CpuGaussianView& view, const SceneDepthReader& depth,
                   std::vector<std::uint8_t>& out);

  /// Threads a frame uses (at least 2).
  int threads() const { return threads_; }

  /// The pixels the last draw or drawVectors may have written something other than
  /// transparent black to: whole 32-pixel tiles clipped to the view, the smallest
  /// rectangle holding every tile a splat reached; empty when none reached a pixel. Every
  /// pixel of it is written (transparent black where no splat is).
  using PixelRect = detail::PixelRect;
  PixelRect touched() const { return touched_; }

  struct Scratch;

 private:
  template <typename Source>
  void rasterize(const Source& source, std::span<const std::uint32_t> order,
                 const CpuGaussianView& view, const SceneDepthReader& depth,
                 std::vector<std::uint8_t>& out, std::span<const std::uint32_t> subset);

  int threads_;
  std::unique_ptr<Scratch> scratch_;
  PixelRect touched_;
};

}  // namespace gs::render::detail
