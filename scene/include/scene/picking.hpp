// Picking on the CPU: which drawn triangle a ray (the pointing device's bearing, ISO/IEC
// 14772-1:1997 4.6.7.1) meets first, with the path of grouping nodes from the root to its
// Shape, for the pointing-device sensors of the execution model (runtime/pointer.hpp; the
// application converts, as render/ does not depend on runtime/).
#pragma once

#include "scene/camera.hpp"
#include "scene/traversal.hpp"

#include <glm/glm.hpp>

#include <limits>
#include <optional>
#include <vector>

namespace gs::scene {

/// A half line in world coordinates; the direction need not be unit length.
struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
};

/// What a ray hit first.
struct PickHit {
  std::vector<PathStep> path;  // the root (node null) first, ..., the Shape last
  const vrml::Node* shape = nullptr;
  const vrml::Node* geometry = nullptr;
  glm::vec3 point{0.0f};               // world coordinates
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // world coordinates, unit (the mesh's, interpolated)
  glm::vec2 texCoord{0.0f};            // interpolated; 0 0 when the mesh has none
  float distance = 0.0f;               // from the ray's origin, world units of `direction`
  std::uint32_t triangle = 0;          // index of the triangle in the geometry's mesh
};

/// The bearing through the point (x, y) of a viewport `width` x `height` pixels (x to the
/// right, y downwards from the top left; pixel centres at .5): from the camera's position,
/// through that point of the image plane of projectionMatrix(camera, width / height).
Ray rayThroughPixel(const Camera& camera, int width, int height, float x, float y);

/// The nearest triangle of the shapes drawn for `viewer` (SceneTraversal::collect: the
/// chosen Switch children and LOD levels, Billboards turned to the viewer, Inlines) that
/// `ray` meets in front of its origin (Moller-Trumbore, both sides of every triangle).
/// Lines and points are not picked; Text is (its glyph triangles). Tessellates the shapes whose
/// bounds the ray meets when their arrays were dropped (SceneTraversal::mesh).
///
/// In a world with a LayerSet (X3D 4.0 clause 35) the layers are picked as they are drawn,
/// each over the previous: the nearest hit of the topmost layer (the last in `order`) that
/// the ray meets wins, however near a lower layer's shape is. A layer is passed over when its
/// Layer's `pickable` (X3D 3: `isPickable`) or `pointerEvents` is FALSE, and when
/// `pointer` (the pointing device as fractions of the viewport: x from the left, y from the
/// bottom, each 0..1) lies outside its Viewport's clipBoundary. Without `pointer` the
/// clipBoundary is not tested.
std::optional<PickHit> pick(SceneTraversal& traversal, const Camera& viewer, const Ray& ray,
                            const std::optional<glm::vec2>& pointer = std::nullopt);

/// As pick() without layers, among the shapes of a frame already collected
/// (SceneTraversal::collect; with TraversalFrame::recordPaths for the paths,
/// TraversalFrame::collisionGeometry for what the avatar collides with), nearer than `maxT`
/// (in units of ray.direction): the nearest of every layer's shapes, or of layer `layer`'s
/// alone (ShapeInstance::layer) when given. Lets one collect serve several rays.
std::optional<PickHit> pickInFrame(SceneTraversal& traversal, const TraversalFrame& frame,
                                   const Ray& ray,
                                   float maxT = std::numeric_limits<float>::infinity(),
                                   std::optional<std::uint32_t> layer = std::nullopt);

/// Möller-Trumbore: the distance t along `direction` at which the ray meets the triangle
/// (a, b, c), with barycentric (u, v) of b and c; false when it misses or t <= `minT`.
bool intersectTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& a,
                       const glm::vec3& b, const glm::vec3& c, float& t, float& u, float& v,
                       float minT = 0.0f);

}  // namespace gs::scene
