// X3D 4.0's bboxDisplay (X3DBoundedObject, clause 10.3.1) for the traversal: the box of a
// grouping node or Shape outlined in white, as X_ITE draws it, by a Shape and an
// IndexedLineSet of the traversal's own whose mesh is put in the tessellation cache.
#include "encodings/node_types.hpp"
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <array>

namespace gs::scene {

SceneTraversal::BoxOutline SceneTraversal::boxOutline(const vrml::Node& bounded,
                                                      const vrml::Bounds& box) {
  BoxDraw& draw = boxDraws_[&bounded];
  if (!draw.shape) {
    const auto shapeType = vrml::x3dNodeType("Shape");
    const auto linesType = vrml::x3dNodeType("IndexedLineSet");
    if (!shapeType || !linesType) return {};
    draw.shape = std::make_shared<vrml::Node>(shapeType);
    draw.geometry = std::make_shared<vrml::Node>(linesType);
    draw.shape->location = draw.geometry->location = bounded.location;
    draw.box = vrml::Bounds{};
  }
  if (box.min != draw.box.min || box.max != draw.box.max || draw.box.empty()) {
    draw.box = box;
    draw.geometry->markChanged();
    CachedMesh& cached = meshes_[draw.geometry.get()];
    vrml::Mesh& mesh = cached.mesh;
    mesh = vrml::Mesh{};
    mesh.primitive = vrml::Primitive::lines;
    for (int corner = 0; corner < 8; ++corner)
      mesh.positions.push_back(glm::vec3(corner & 1 ? box.max.x : box.min.x,
                                         corner & 2 ? box.max.y : box.min.y,
                                         corner & 4 ? box.max.z : box.min.z));
    // The 12 edges: corners that differ in one bit.
    for (std::uint32_t a = 0; a < 8; ++a)
      for (const std::uint32_t bit : {1u, 2u, 4u})
        if ((a & bit) == 0) mesh.indices.insert(mesh.indices.end(), {a, a | bit});
    mesh.bounds = box;
    cached.arraysDropped = false;
    cached.rotatedUse = false;
    cached.boundsPositions.clear();
    cached.revision = vrml::revisionWithFields(*draw.geometry);
  }
  return {draw.shape.get(), draw.geometry.get()};
}

vrml::Bounds SceneTraversal::boundedBox(const vrml::Node& n, std::span<const ShapeInstance> shapes,
                                        const glm::mat4& inner) {
  vrml::Bounds box;
  const glm::vec3 size = sfVec3(n, "bboxSize", glm::vec3(-1.0f));
  if (size.x >= 0.0f && size.y >= 0.0f && size.z >= 0.0f) {
    const glm::vec3 centre = sfVec3(n, "bboxCenter", glm::vec3(0.0f));
    box.extend(centre - size * 0.5f);
    box.extend(centre + size * 0.5f);
    return box;
  }
  const glm::mat4 toInner = glm::inverse(inner);
  for (const ShapeInstance& s : shapes) {
    if (s.geometry == nullptr) continue;
    const vrml::Bounds& local = meshBounds(*s.geometry);
    if (local.empty()) continue;
    const glm::mat4 m = toInner * s.model;
    for (int corner = 0; corner < 8; ++corner)
      box.extend(glm::vec3(m * glm::vec4(corner & 1 ? local.max.x : local.min.x,
                                         corner & 2 ? local.max.y : local.min.y,
                                         corner & 4 ? local.max.z : local.min.z, 1.0f)));
  }
  return box;
}

}  // namespace gs::scene
