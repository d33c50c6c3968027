// CPU picking: rays against the tessellations of the shapes collect() draws.
#include "scene/picking.hpp"

#include "geometry/intersect.hpp"
#include "scene/node_access.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs::scene {

Ray rayThroughPixel(const Camera& camera, int width, int height, float x, float y) {
  const float w = static_cast<float>(std::max(width, 1));
  const float h = static_cast<float>(std::max(height, 1));
  const float aspect = w / h;
  const float tanHalf = std::tan(verticalFieldOfView(camera.fieldOfView, aspect) * 0.5f);
  const float ndcX = 2.0f * x / w - 1.0f;
  const float ndcY = 1.0f - 2.0f * y / h;
  if (camera.orthographic) {  // parallel rays from the view plane through the pixel
    const glm::mat4 inverse = glm::inverse(projectionMatrix(camera, aspect));
    const glm::vec4 onPlane = inverse * glm::vec4(ndcX, ndcY, -1.0f, 1.0f);
    const glm::vec3 offset(onPlane.x / onPlane.w, onPlane.y / onPlane.w, 0.0f);
    return {camera.position + camera.orientation * (camera.deform * offset),
            glm::normalize(camera.orientation * (camera.deform * glm::vec3(0, 0, -1)))};
  }
  const glm::vec3 eye(ndcX * tanHalf * aspect, ndcY * tanHalf, -1.0f);
  return {camera.position, glm::normalize(camera.orientation * (camera.deform * eye))};
}

bool intersectTriangle(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& a,
                       const glm::vec3& b, const glm::vec3& c, float& t, float& u, float& v,
                       float minT) {
  return vrml::lineTriangle(origin, direction, a, b, c, t, u, v) && t > minT;
}

std::optional<PickHit> pick(SceneTraversal& traversal, const Camera& viewer, const Ray& ray,
                            const std::optional<glm::vec2>& pointer) {
  TraversalFrame frame;
  frame.recordPaths = true;
  traversal.collect(viewer, frame);
  if (frame.layerOrder.empty()) return pickInFrame(traversal, frame, ray);
  // Top layer first, as drawn (a layer listed twice is on top where it was last drawn).
  std::vector<std::uint32_t> tried;
  for (auto it = frame.layerOrder.rbegin(); it != frame.layerOrder.rend(); ++it) {
    const LayerInstance& layer = *it;
    if (std::find(tried.begin(), tried.end(), layer.number) != tried.end()) continue;
    tried.push_back(layer.number);
    if (layer.node != nullptr &&
        (!sfBool(*layer.node, "pickable", true) || !sfBool(*layer.node, "pointerEvents", true)))
      continue;
    const glm::vec4& clip = layer.clipBoundary;  // left, right, bottom, top
    if (pointer &&
        (pointer->x < clip.x || pointer->x > clip.y || pointer->y < clip.z || pointer->y > clip.w))
      continue;
    if (auto hit = pickInFrame(traversal, frame, ray, std::numeric_limits<float>::infinity(),
                               layer.number))
      return hit;
  }
  return std::nullopt;
}

std::optional<PickHit> pickInFrame(SceneTraversal& traversal, const TraversalFrame& frame,
                                   const Ray& ray, float maxT, std::optional<std::uint32_t> layer) {
  std::optional<PickHit> best;
  float bestT = maxT;
  for (const ShapeInstance& s : frame.shapes) {
    if (layer && s.layer != *layer) continue;
    // X3D 4.1's Shape.pointerEvents FALSE: the pointer passes through to what lies behind.
    if (s.shape != nullptr && !sfBool(*s.shape, "pointerEvents", true)) continue;
    const float det = glm::determinant(glm::mat3(s.model));
    if (!std::isfinite(det) || std::abs(det) < 1e-30f) continue;  // scaled flat: invisible
    const glm::mat4 inverse = glm::inverse(s.model);
    // The same parameter t in local and world coordinates (an affine map).
    const glm::vec3 o = glm::vec3(inverse * glm::vec4(ray.origin, 1.0f));
    const glm::vec3 d = glm::mat3(inverse) * ray.direction;
    const vrml::Bounds& bounds = traversal.meshBounds(*s.geometry);
    if (!vrml::lineMeetsBox(o, d, bounds, 0.0f, bestT)) continue;
    const vrml::Mesh& mesh = traversal.mesh(*s.geometry);
    if (mesh.primitive != vrml::Primitive::triangles) continue;
    const std::size_t count = mesh.indices.size() / 3;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t ia = mesh.indices[3 * i], ib = mesh.indices[3 * i + 1],
                          ic = mesh.indices[3 * i + 2];
      if (ia >= mesh.positions.size() || ib >= mesh.positions.size() || ic >= mesh.positions.size())
        continue;
      float t = 0.0f, u = 0.0f, v = 0.0f;
      if (!intersectTriangle(o, d, mesh.positions[ia], mesh.positions[ib], mesh.positions[ic], t, u,
                             v, 1e-7f) ||
          t >= bestT)
        continue;
      bestT = t;
      PickHit hit;
      hit.shape = s.shape;
      hit.geometry = s.geometry;
      hit.triangle = static_cast<std::uint32_t>(i);
      hit.point = ray.origin + t * ray.direction;
      hit.distance = t * glm::length(ray.direction);
      const float w = 1.0f - u - v;
      glm::vec3 n;
      if (mesh.normals.size() == mesh.positions.size())
        n = w * mesh.normals[ia] + u * mesh.normals[ib] + v * mesh.normals[ic];
      else
        n = glm::cross(mesh.positions[ib] - mesh.positions[ia],
                       mesh.positions[ic] - mesh.positions[ia]);
      n = glm::transpose(glm::mat3(inverse)) * n;
      hit.normal = glm::length(n) > 1e-30f ? glm::normalize(n) : glm::vec3(0.0f, 0.0f, 1.0f);
      if (mesh.texCoords.size() == mesh.positions.size())
        hit.texCoord = w * mesh.texCoords[ia] + u * mesh.texCoords[ib] + v * mesh.texCoords[ic];
      if (s.pathCount > 0)
        hit.path.assign(frame.paths.begin() + s.pathBegin,
                        frame.paths.begin() + s.pathBegin + s.pathCount);
      best = std::move(hit);
    }
  }
  return best;
}

}  // namespace gs::scene
