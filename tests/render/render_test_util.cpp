#include "render_test_util.hpp"

namespace gs::test {

NodePtr makeNode(const std::string& type,
                 std::initializer_list<std::pair<const char*, FieldValue>> fields) {
  auto t = std::make_shared<vrml::NodeType>();
  t->name = type;
  t->builtIn = true;
  t->model = vrml::nodeModel(type);  // what the renderer decides the node's kind by
  for (const auto& [name, value] : fields)
    t->fields.push_back(vrml::FieldSpec{name, value.type(), vrml::AccessType::exposedField, value});
  return std::make_shared<vrml::Node>(t);
}

FieldValue sfBool(bool v) {
  return FieldValue::make<FieldType::SFBool>(v);
}
FieldValue sfFloat(float v) {
  return FieldValue::make<FieldType::SFFloat>(v);
}
FieldValue sfInt(int v) {
  return FieldValue::make<FieldType::SFInt32>(std::int32_t(v));
}
FieldValue sfVec3(float x, float y, float z) {
  return FieldValue::make<FieldType::SFVec3f>(glm::vec3(x, y, z));
}
FieldValue sfVec2(float x, float y) {
  return FieldValue::make<FieldType::SFVec2f>(glm::vec2(x, y));
}
FieldValue sfColor(float r, float g, float b) {
  return FieldValue::make<FieldType::SFColor>(glm::vec3(r, g, b));
}
FieldValue sfRotation(float x, float y, float z, float angle) {
  return FieldValue::make<FieldType::SFRotation>(vrml::Rotation(x, y, z, angle));
}
FieldValue sfString(const std::string& v) {
  return FieldValue::make<FieldType::SFString>(v);
}
FieldValue sfNode(NodePtr n) {
  return FieldValue::make<FieldType::SFNode>(std::move(n));
}
FieldValue mfNode(std::vector<NodePtr> nodes) {
  return FieldValue::make<FieldType::MFNode>(std::move(nodes));
}
FieldValue mfString(std::vector<std::string> v) {
  return FieldValue::make<FieldType::MFString>(std::move(v));
}
FieldValue mfFloat(std::vector<float> v) {
  return FieldValue::make<FieldType::MFFloat>(std::move(v));
}
FieldValue mfColor(std::vector<glm::vec3> v) {
  return FieldValue::make<FieldType::MFColor>(std::move(v));
}

std::shared_ptr<const vrml::Scene> makeScene(std::vector<NodePtr> roots, const std::string& url) {
  auto scene = std::make_shared<vrml::Scene>();
  scene->url = url;
  scene->rootNodes = std::move(roots);
  return scene;
}

namespace {
void addQuad(vrml::Mesh& m, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, glm::vec3 n) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  for (glm::vec3 p : {a, b, c, d}) {
    m.positions.push_back(p);
    m.normals.push_back(n);
    m.bounds.extend(p);
  }
  m.texCoords.insert(m.texCoords.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}
}  // namespace

vrml::Mesh testTessellate(const vrml::Node& g, vrml::Diagnostics*) {
  vrml::Mesh m;
  if (g.typeName() == "TestBox") {
    const glm::vec3 h = g.get<FieldType::SFVec3f>("size", glm::vec3(2.0f)) * 0.5f;
    auto p = [&](float x, float y, float z) { return glm::vec3(x * h.x, y * h.y, z * h.z); };
    addQuad(m, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1), {0, 0, 1});
    addQuad(m, p(1, -1, -1), p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1), {0, 0, -1});
    addQuad(m, p(1, -1, 1), p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), {1, 0, 0});
    addQuad(m, p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), {-1, 0, 0});
    addQuad(m, p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), p(-1, 1, -1), {0, 1, 0});
    addQuad(m, p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1), {0, -1, 0});
  } else if (g.typeName() == "TestQuad") {
    const glm::vec2 h = g.get<FieldType::SFVec2f>("size", glm::vec2(2.0f)) * 0.5f;
    const float z = g.get<FieldType::SFFloat>("z", 0.0f);
    addQuad(m, {-h.x, -h.y, z}, {h.x, -h.y, z}, {h.x, h.y, z}, {-h.x, h.y, z}, {0, 0, 1});
    m.solid = g.get<FieldType::SFBool>("solid", true);
  } else if (g.typeName() == "TestLines") {
    m.primitive = vrml::Primitive::lines;
    m.positions = {{-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}};
    m.indices = {0, 1, 2, 3};
    for (auto p : m.positions) m.bounds.extend(p);
  } else if (g.typeName() == "TestPoints") {
    m.primitive = vrml::Primitive::points;
    m.positions = {{-1, 0, 0}, {0, 0, 0}, {1, 0, 0}};
    m.indices = {0, 1, 2};
    for (auto p : m.positions) m.bounds.extend(p);
  }
  return m;
}

render::SceneRendererOptions testRendererOptions() {
  render::SceneRendererOptions o;
  o.traversal.tessellator = &testTessellate;
  return o;
}

NodePtr shapeWith(NodePtr geometry,
                  std::initializer_list<std::pair<const char*, FieldValue>> material,
                  NodePtr texture) {
  NodePtr appearance = makeNode("Appearance", {{"material", sfNode(makeNode("Material", material))},
                                               {"texture", sfNode(std::move(texture))}});
  return makeNode("Shape", {{"appearance", sfNode(appearance)}, {"geometry", sfNode(geometry)}});
}

}  // namespace gs::test
