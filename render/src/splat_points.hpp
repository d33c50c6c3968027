// Private to render/: the point-sprite splat path (SplatPath::points, splat_renderer.hpp).
//
// Each vector is one GL point. The vertex shader finds the exact screen bounding box of
// the projected 3-sigma disk of the vector's patch (splat_model.hpp: outside the disk the
// profile is cut to zero), clips it to the viewport and makes the point a sprite that
// covers that box plus a quarter pixel each side; a patch outside the view is culled
// there. The fragment shader intersects its pixel's ray with the patch plane (as the CPU
// reference of equation (1) does, splat_reference.hpp), discards what falls outside the
// disk, the clip range or the viewport, and writes the patch's depth, so it shades the
// fragments the geometry path's two triangles shade. One point per splat instead of a
// geometry-shader invocation and two triangles; but a square sprite over an oblique
// ellipse covers more pixels than the patch, and on llvmpipe the covered pixel blocks
// dominate the cost: measured in docs/rendering.md, it is not the default anywhere.
//
// A sprite cannot cross the near plane nor exceed the largest point size, so the pass
// checks the view first (pointsFit) and draws with the geometry path when some splat
// would need either.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "qnv/decoder.hpp"
#include "render/splat_model.hpp"

namespace gs::render::detail {

/// The point path's vertex shader after splatVertexShader's shared part (splat_glsl.hpp).
extern const char* const kSplatPointsVertexBody;
extern const char* const kSplatPointsFragmentShader;

/// What pointsFit needs of the view: `modelView` (model to eye), the projection's x and y
/// scales (projection[0][0], projection[1][1]), the viewport in pixels, the near clip
/// distance (eye units, > 0) and the largest point size (pixels, GL_POINT_SIZE_RANGE).
struct PointView {
  glm::mat4 modelView{1.0f};
  float scaleX = 1.0f, scaleY = 1.0f;
  int width = 1, height = 1;
  float nearClip = 0.1f;
  float maxPointSize = 1.0f;
};

/// True when every vector of `vectors` is drawn exactly by a point sprite: its square
/// patch lies wholly in front of the near plane (or wholly behind it: culled by both
/// paths) and its sprite, clipped to the viewport, fits the largest point size. A
/// conservative bound (the patch's circumscribed sphere); non-finite vectors pass (both
/// paths draw nothing for them). O(n), no allocation.
bool pointsFit(std::span<const qnv::DecodedVector> vectors, const SplatStyle& style,
               const PointView& view);

}  // namespace gs::render::detail
