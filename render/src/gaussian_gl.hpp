// Private to render/: the GL path of anisotropic 3D Gaussians (splats/gaussian.hpp;
// docs/splats.md), used where GL runs on a GPU. One instanced quad per Gaussian: the vertex
// shader makes the EWA projection of splats::projectGaussian (Sigma' = J W Sigma W^T J^T
// + 0.3 px, 3-sigma square), the fragment shader the profile alpha = min(0.99,
// o exp(power)) with alpha < 1/255 discarded, blended back to front (ONE,
// ONE_MINUS_SRC_ALPHA) in the order the CPU radix sort gives, depth-tested at the
// centre's depth against the scene (no depth writes), into a float layer composited over
// the framebuffer once (splat_layer_gl.hpp). The same picture as the CPU path up to
// rounding.
//
// Data: the cloud's centres, opacities and covariances in one texture buffer (three
// RGBA32F texels per Gaussian, uploaded once per cloud), the colours of this view
// (spherical harmonics evaluated on the CPU, or on the GPU by GpuShColors for the
// GPU-sorted path, RGBA8) in another, refreshed when the view moves and the cloud has SH
// bands; the order as an instanced attribute.
#pragma once

#include <glad/gl.h>

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "gpu_sort.hpp"
#include "qnv/decoder.hpp"
#include "render/splat_model.hpp"
#include "sh_colors_gl.hpp"
#include "splat_layer_gl.hpp"
#include "splats/gaussian.hpp"

namespace gs::render::detail {

class GaussianGlPass {
 public:
  GaussianGlPass() = default;
  GaussianGlPass(const GaussianGlPass&) = delete;
  GaussianGlPass& operator=(const GaussianGlPass&) = delete;

  /// The fog every later draw's splat colours go through (by each centre's eye distance;
  /// SplatFog's default: none).
  void setFog(const SplatFog& fog) { fog_ = fog; }

  /// Draws `order` (indices into `cloud`, farthest first) into the current framebuffer's
  /// viewport (`viewport`: x, y, width, height in pixels), the cloud placed by `modelView`,
  /// projected by `projection`, its SH evaluated from `eye` (the camera in cloud
  /// coordinates). Builds its program at the first call (throws std::runtime_error when it
  /// does not compile). GL state: blending and the depth mask are restored as the splat
  /// pass leaves them. The cloud's data are uploaded again when its address, size or
  /// `revision` changed.
  void draw(const splats::GaussianCloud& cloud, std::span<const std::uint32_t> order,
            const glm::mat4& modelView, const glm::mat4& projection, const glm::vec3& eye,
            const int viewport[4], float nearClip, float opacityScale, std::uint64_t revision = 0);
  /// As draw(), the order sorted on the GPU instead (GpuDepthSort, OpenGL 4.3): the first
  /// `count` splats of the cloud, back to front; or, with a `subset` (indices into the
  /// cloud: a level-of-detail cut of a cloud that holds the tree's every node), those
  /// splats (`count` unused), the cloud uploaded once and the subset's indices again when
  /// its address, size or `subsetRevision` changed.
  void drawGpuSorted(const splats::GaussianCloud& cloud, std::size_t count,
                     const glm::mat4& modelView, const glm::mat4& projection, const glm::vec3& eye,
                     const int viewport[4], float nearClip, float opacityScale,
                     std::uint64_t revision = 0, std::span<const std::uint32_t> subset = {},
                     std::uint64_t subsetRevision = 0);
  /// Draws the QNV vectors `order` (indices into `vectors`, farthest first) as the
  /// flat-disc Gaussians of vectorGaussian under `style`, shaded by shadeSplat with
  /// `lights` (world directions, at most 8) and normals turned by `normalMatrix` (model to
  /// world), each peak scaled by the projection's low-pass keep (as the cpu path does),
  /// fragments below half an 8-bit level not drawn. The vectors are uploaded again when
  /// their address, `revision` or the style changed, only the new tail when the set grew
  /// (a progressive stream); their colours when the lights or `normalMatrix` changed. An empty
  /// `order` draws the first `count` vectors in the order the GPU sort makes (GpuDepthSort).
  /// Otherwise as draw().
  void drawVectors(std::span<const qnv::DecodedVector> vectors, std::uint64_t revision,
                   std::span<const std::uint32_t> order, std::size_t count, const SplatStyle& style,
                   std::span<const SplatLight> lights, const glm::mat3& normalMatrix,
                   const glm::mat4& modelView, const glm::mat4& projection, const int viewport[4],
                   float nearClip);
  /// Whether the GPU sort can run here (GpuDepthSort::available). Context current.
  static bool gpuSortAvailable() { return GpuDepthSort::available(); }
  /// Frees every GL object (context current).
  void release();

 private:
  SplatFog fog_;
  void create();
  /// staging_ (colors_) to the splat (colour) texture buffer, from splat `from` on when
  /// the buffer already holds the rest (a grown set), else whole.
  void uploadSplats(std::size_t from);
  void uploadColors(std::size_t from);
  /// The cloud's texels (again when it changed) and this view's colours: with
  /// `gpuColors` and SH bands, evaluated on the GPU (GpuShColors), else on the CPU.
  void uploadCloud(const splats::GaussianCloud& cloud, const glm::vec3& eye, std::uint64_t revision,
                   bool gpuColors);
  /// Draws `count` instances in `order`, or, when `order` is empty, in the order the GPU
  /// sort makes of the first `count` splats (of the `count` named by the buffer `subset`
  /// when it is not 0).
  void drawUploaded(std::span<const std::uint32_t> order, std::size_t count,
                    const glm::mat4& modelView, const glm::mat4& projection, const int viewport[4],
                    float nearClip, float opacityScale, float minAlpha, bool keepIntegral,
                    GLuint subset = 0);
  GpuDepthSort gpuSort_;
  GpuShColors shColors_;
  FloatSplatLayer layer_;
  bool shOnGpu_ = false;  // shColors_ holds the uploaded cloud's coefficients

  GLuint program_ = 0, vao_ = 0, orderBuffer_ = 0;
  GLuint splatBuffer_ = 0, splatTexture_ = 0, colorBuffer_ = 0, colorTexture_ = 0;
  GLuint subsetBuffer_ = 0;           // the last cut's indices (drawGpuSorted)
  const void* subsetSent_ = nullptr;  // ... sent from this array
  std::size_t subsetSize_ = 0;        // ... of this many
  std::uint64_t subsetRevision_ = 0;  // ... at this revision
  const void* uploaded_ = nullptr;
  std::size_t uploadedSize_ = 0;
  std::uint64_t uploadedRevision_ = 0;
  SplatStyle uploadedStyle_;
  glm::vec3 colorEye_{NAN};
  std::vector<float> colorKey_;      // what the uploaded colours were made for (empty: none)
  std::vector<float> nextColorKey_;  // this draw's key, built in place
  std::size_t coloredSize_ = 0;      // vectors whose colours are uploaded under colorKey_
  std::size_t splatCapacity_ = 0, colorCapacity_ = 0;  // bytes of the buffers' stores
  std::vector<float> staging_;
  std::vector<std::uint8_t> colors_;
};

}  // namespace gs::render::detail
