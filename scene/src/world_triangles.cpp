#include "scene/world_triangles.hpp"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/matrix.hpp>

#include "scene/traversal.hpp"

namespace gs::scene {

namespace {

qnv::Rgba8 toRgba8(const glm::vec4& c) {
  const glm::vec4 v = glm::clamp(c, 0.0f, 1.0f) * 255.0f + 0.5f;
  return qnv::Rgba8(static_cast<std::uint8_t>(v.r), static_cast<std::uint8_t>(v.g),
                    static_cast<std::uint8_t>(v.b), static_cast<std::uint8_t>(v.a));
}

glm::vec4 materialColor(const vrml::Node* appearance) {
  if (!appearance) return glm::vec4(1.0f);
  const vrml::NodePtr m = appearance->sfnode("material");
  if (!m || m->unresolved || m->typeId() != vrml::NodeTypeId::Material) return glm::vec4(1.0f);
  const glm::vec3 diffuse = m->get<vrml::FieldType::SFColor>("diffuseColor", glm::vec3(0.8f));
  const float transparency = m->get<vrml::FieldType::SFFloat>("transparency", 0.0f);
  return glm::vec4(diffuse, 1.0f - transparency);
}

}  // namespace

qnv::TriangleMesh worldTriangles(std::shared_ptr<const vrml::Scene> scene) {
  SceneTraversal traversal(std::move(scene));
  TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  qnv::TriangleMesh out;
  for (const ShapeInstance& shape : frame.shapes) {
    const vrml::Mesh& mesh = traversal.mesh(*shape.geometry);
    if (mesh.primitive != vrml::Primitive::triangles || mesh.indices.empty()) continue;
    const std::uint32_t base = static_cast<std::uint32_t>(out.positions.size());
    const qnv::Rgba8 color = toRgba8(materialColor(shape.appearance));
    const float alpha = materialColor(shape.appearance).a;
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      out.positions.push_back(glm::vec3(shape.model * glm::vec4(mesh.positions[i], 1.0f)));
      if (i < mesh.colors.size())
        out.vertexColors.push_back(toRgba8(glm::vec4(glm::vec3(mesh.colors[i]), alpha)));
      else
        out.vertexColors.push_back(color);
    }
    // A mirroring transform turns counter-clockwise into clockwise: swap to keep the
    // triangle normals pointing out of the front face.
    const bool mirrored = glm::determinant(glm::mat3(shape.model)) < 0.0f;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
      out.indices.push_back(base + mesh.indices[i]);
      out.indices.push_back(base + mesh.indices[mirrored ? i + 2 : i + 1]);
      out.indices.push_back(base + mesh.indices[mirrored ? i + 1 : i + 2]);
    }
  }
  // One colour per vertex is only needed when colours differ; a face colour per triangle
  // would be larger, so keep per-vertex colours.
  if (!out.vertexColors.empty() &&
      std::all_of(out.vertexColors.begin(), out.vertexColors.end(),
                  [&](const qnv::Rgba8& c) { return c == out.vertexColors.front(); })) {
    out.baseColor = out.vertexColors.front();
    out.vertexColors.clear();
  }
  return out;
}

}  // namespace gs::scene
