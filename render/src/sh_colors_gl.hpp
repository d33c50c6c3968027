// Private to render/: the colours of a Gaussian cloud's view evaluated on the GPU (issue 40:
// the gpu path keeps a capture on the GPU): its spherical harmonics (splats/gaussian.hpp,
// shColor: degree 0..3, Kerbl et al. 2023's basis and constants) along the ray from the
// eye to each centre, plus 0.5, clamped at 0, a linear cloud turned into sRGB, stored as
// RGBA8 (alpha 255) in the colour buffer that GaussianGlPass's vertex shader reads. One
// OpenGL 4.3 compute shader thread per splat, run when the eye moves; the coefficients
// are uploaded once per cloud (3 (degree + 1)^2 floats per splat).
#pragma once

#include <glad/gl.h>

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "splats/gaussian.hpp"

namespace gs::render::detail {

class GpuShColors {
 public:
  GpuShColors() = default;
  GpuShColors(const GpuShColors&) = delete;
  GpuShColors& operator=(const GpuShColors&) = delete;

  /// Sends `cloud`'s SH coefficients (DC and rest, splat-major) to the GPU, replacing
  /// what was there. Builds the program at the first call (throws std::runtime_error
  /// when it does not compile). Context current, OpenGL 4.3 (GpuDepthSort::available).
  void upload(const splats::GaussianCloud& cloud);

  /// Writes the colours of the first `count` splats (at most the uploaded cloud's size)
  /// seen from `eye` (cloud coordinates) into `colorBuffer` (at least count * 4 bytes,
  /// packed RGBA8), reading the centres from `splatTexture` (GaussianGlPass's texture
  /// buffer, the centre in texel 3 i's xyz). Ends with the barrier for texture fetches.
  void evaluate(GLuint splatTexture, GLuint colorBuffer, std::size_t count, const glm::vec3& eye);

  /// Frees every GL object (context current).
  void release();

 private:
  GLuint program_ = 0, coefficients_ = 0;
  std::size_t size_ = 0;  // splats uploaded
  int degree_ = 0;
  bool linear_ = false;
  std::vector<float> staging_;
};

}  // namespace gs::render::detail
