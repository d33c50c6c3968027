// X3D 4.0's bboxDisplay (X3DBoundedObject, clause 10.3.1) for the traversal: the box of a
// grouping node or Shape outlined in white, as X_ITE draws it, by a Shape, IndexedLineSet
// and Coordinate of the traversal's own (tessellated as any geometry, so its mesh comes
// back whenever the cache dropped or lost it).
#include "encodings/node_types.hpp"
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <cmath>

namespace gs::scene {

namespace {

bool finiteBox(const vrml::Bounds& b) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(b.min[k]) || !std::isfinite(b.max[k])) return false;
  return !b.empty();
}

}  // namespace

SceneTraversal::BoxOutline SceneTraversal::boxOutline(const vrml::Node& bounded,
                                                      const vrml::Bounds& box) {
  if (!finiteBox(box)) return {};
  BoxDraw& draw = boxDraws_[&bounded];
  if (!draw.shape) {
    const auto shapeType = vrml::x3dNodeType("Shape");
    const auto linesType = vrml::x3dNodeType("IndexedLineSet");
    const auto coordType = vrml::x3dNodeType("Coordinate");
    if (!shapeType || !linesType || !coordType) return {};
    auto shape = std::make_shared<vrml::Node>(shapeType);
    auto lines = std::make_shared<vrml::Node>(linesType);
    auto coord = std::make_shared<vrml::Node>(coordType);
    const int coordField = lines->type().findExact("coord");
    const int indexField = lines->type().findExact("coordIndex");
    if (coordField < 0 || indexField < 0 || coord->type().findExact("point") < 0) return {};
    // The 12 edges: the corners (x, y, z bits of their index) that differ in one bit.
    std::vector<std::int32_t> index;
    for (std::int32_t a = 0; a < 8; ++a)
      for (const std::int32_t bit : {1, 2, 4})
        if ((a & bit) == 0) index.insert(index.end(), {a, a | bit, -1});
    lines->setField(static_cast<std::size_t>(indexField),
                    vrml::FieldValue::make<vrml::FieldType::MFInt32>(std::move(index)));
    lines->setField(static_cast<std::size_t>(coordField),
                    vrml::FieldValue::make<vrml::FieldType::SFNode>(coord));
    shape->location = lines->location = coord->location = bounded.location;
    draw = BoxDraw{shape, lines, coord, vrml::Bounds{}};
  }
  if (box.min != draw.box.min || box.max != draw.box.max) {
    draw.box = box;
    std::vector<glm::vec3> corners;
    for (int corner = 0; corner < 8; ++corner)
      corners.emplace_back(corner & 1 ? box.max.x : box.min.x, corner & 2 ? box.max.y : box.min.y,
                           corner & 4 ? box.max.z : box.min.z);
    draw.coord->setField(static_cast<std::size_t>(draw.coord->type().findExact("point")),
                         vrml::FieldValue::make<vrml::FieldType::MFVec3f>(std::move(corners)));
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
