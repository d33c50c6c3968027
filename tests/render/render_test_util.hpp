// Helpers for the render tests: scene graphs built by hand (node types made on the fly
// with just the fields a test sets, so the tests do not depend on the parser or the node
// table) and a small tessellator for the test geometry types.
#pragma once

#include "geometry/geometry.hpp"
#include "render/scene_renderer.hpp"
#include "vrml/field.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gs::test {

using vrml::FieldType;
using vrml::FieldValue;
using vrml::NodePtr;

/// A node of type `type` whose interface is exactly the given fields (as exposedFields).
NodePtr makeNode(const std::string& type,
                 std::initializer_list<std::pair<const char*, FieldValue>> fields = {});

FieldValue sfBool(bool v);
FieldValue sfFloat(float v);
FieldValue sfInt(int v);
FieldValue sfVec3(float x, float y, float z);
FieldValue sfVec2(float x, float y);
FieldValue sfColor(float r, float g, float b);
FieldValue sfRotation(float x, float y, float z, float angle);
FieldValue sfString(const std::string& v);
FieldValue sfNode(NodePtr n);
FieldValue mfNode(std::vector<NodePtr> nodes);
FieldValue mfString(std::vector<std::string> v);
FieldValue mfFloat(std::vector<float> v);
FieldValue mfColor(std::vector<glm::vec3> v);

/// A scene with these root nodes, read from `url`.
std::shared_ptr<const vrml::Scene> makeScene(std::vector<NodePtr> roots,
                                             const std::string& url = "/tmp/test.wrl");

/// Geometry types understood by testTessellate:
/// - TestBox (field size, SFVec3f): an axis-aligned box centred at the origin, solid;
/// - TestQuad (fields size SFVec2f, solid SFBool, z SFFloat): a square in the plane
///   z = const facing +Z, texture coordinates 0..1;
/// - TestLines: two crossing segments; TestPoints: 3 points.
vrml::Mesh testTessellate(const vrml::Node& geometry, vrml::Diagnostics* diag);

/// Options whose tessellator is testTessellate.
render::SceneRendererOptions testRendererOptions();

/// Shape { appearance Appearance { material Material { <material fields> } } geometry g }.
NodePtr shapeWith(NodePtr geometry,
                  std::initializer_list<std::pair<const char*, FieldValue>> material,
                  NodePtr texture = nullptr);

}  // namespace gs::test
