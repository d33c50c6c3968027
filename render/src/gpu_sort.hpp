// Private to render/: the depth order of the GL splat path sorted on the GPU (issue 40
// item 1: "on a real GPU, a GPU sort with instanced quads"): a least-significant-digit
// radix sort in OpenGL 4.3 compute shaders, 4 passes of 8 bits over 32-bit keys, each pass
// a per-block digit histogram, one exclusive scan over (digit, block) and a stable scatter
// (each block's elements ranked in order, 256 at a time). Keys are the splats' eye-space z
// made order-preserving unsigned integers, so the result is back to front (farthest first,
// ascending eye z; a NaN depth farthest). Equal depths come in descending index order: the
// keys are laid out in reverse before the stable passes, so the order is the exact reverse
// of DepthSorter::sortFrontToBack's, the one the geometry path draws (reversed) and the cpu
// path composites (front to back). Ties are then blended in the same sequence on all three
// paths and on every GPU.
//
// Input: the splat texture buffer of GaussianGlPass (3 RGBA32F texels per splat, the centre
// in the first texel's xyz). Output: a GL buffer of uint32 indices, bound by the pass as
// its per-instance attribute, never read back to the CPU.
#pragma once

#include <glad/gl.h>

#include <cstddef>

#include <glm/glm.hpp>

namespace gs::render::detail {

/// Dispatches `groups` workgroups of the bound compute program over a 2D grid (at most
/// 65,535 in x, the least GL_MAX_COMPUTE_WORK_GROUP_COUNT), so a shader finds its
/// workgroup's index as gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x and
/// returns past the last. Nothing for 0 groups.
void dispatch(GLuint groups);

class GpuDepthSort {
 public:
  GpuDepthSort() = default;
  GpuDepthSort(const GpuDepthSort&) = delete;
  GpuDepthSort& operator=(const GpuDepthSort&) = delete;

  /// Whether the current context runs compute shaders and shader storage buffers (OpenGL
  /// 4.3 or later). Context current.
  static bool available();

  /// Sorts the first `count` splats of `splatTexture` (a GL_TEXTURE_BUFFER of RGBA32F,
  /// GaussianGlPass's layout) back to front as seen through `modelView` (splat
  /// coordinates to eye); with `subset` (a GL buffer of at least `count` uint32 splat
  /// indices, each inside the texture), the splats it names instead (a level-of-detail
  /// cut), equal depths in the subset's reverse order. Builds its programs at the first call
  /// (throws std::runtime_error when one does not compile); buffers grow to the largest
  /// count and are kept. Context current; leaves no program or storage binding that other
  /// code uses.
  void sort(GLuint splatTexture, std::size_t count, const glm::mat4& modelView, GLuint subset = 0);

  /// The buffer holding the last sort's order (count uint32 indices), 0 before a sort.
  GLuint order() const { return values_[0]; }

  /// Frees every GL object (context current).
  void release();

 private:
  void create();
  void reserve(std::size_t count);

  GLuint keysProgram_ = 0, histogramProgram_ = 0, scanProgram_ = 0, scatterProgram_ = 0;
  GLuint keys_[2] = {0, 0}, values_[2] = {0, 0}, counts_ = 0;
  std::size_t capacity_ = 0;  // splats the buffers hold
};

}  // namespace gs::render::detail
