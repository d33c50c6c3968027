// Randomized robustness tests of tessellate(): hostile and inconsistent geometry nodes
// must give well-formed meshes (indices in range, finite unit normals), never crash,
// and report problems as warnings only. Run under ASan/UBSan in CI.
#include <catch2/catch.hpp>

#include "encodings/node_types.hpp"
#include "geometry/geometry.hpp"
#include "vrml/node_table.hpp"

#include <cmath>
#include <random>

using namespace gs::vrml;

namespace {

/// A node of the built-in type `type` (from the node table) with those of `fields` set
/// that the type has (so one field list can serve IndexedFaceSet and PointSet alike).
NodePtr makeNode(const std::string& type, std::vector<std::pair<std::string, FieldValue>> fields) {
  const std::shared_ptr<const NodeType> t = builtInNodeType(type);
  REQUIRE(t != nullptr);
  auto n = std::make_shared<Node>(t);
  for (auto& [name, value] : fields) {
    FieldValue* f = n->field(name);
    if (f == nullptr) continue;
    REQUIRE(f->type() == value.type());
    *f = std::move(value);
  }
  return n;
}

template <FieldType T, class V>
FieldValue fv(V v) {
  return FieldValue::make<T>(std::move(v));
}

struct Random {
  std::mt19937 gen{12345};
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(gen); }
  float real(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen); }
  bool chance(double p) { return std::bernoulli_distribution(p)(gen); }
  float value() {  // mostly ordinary numbers, sometimes hostile ones
    if (chance(0.02)) return NAN;
    if (chance(0.01)) return INFINITY;
    if (chance(0.05)) return 0.0f;
    return real(-3.0f, 3.0f);
  }
  glm::vec3 vec3() { return {value(), value(), value()}; }
  glm::vec2 vec2() { return {value(), value()}; }
  std::vector<glm::vec3> vec3s(int n) {
    std::vector<glm::vec3> v(static_cast<std::size_t>(n));
    for (auto& x : v) x = vec3();
    return v;
  }
  std::vector<std::int32_t> indices(int n, int range) {
    std::vector<std::int32_t> v;
    for (int i = 0; i < n; ++i) {
      if (chance(0.2))
        v.push_back(-1);
      else if (chance(0.03))
        v.push_back(integer(-5, -2));
      else if (chance(0.01))
        v.push_back(2147483647);
      else
        v.push_back(integer(0, range + 1));
    }
    return v;
  }
};

void checkWellFormed(const Mesh& m, const Diagnostics& d) {
  const std::size_t per = m.primitive == Primitive::triangles ? 3
                          : m.primitive == Primitive::lines   ? 2
                                                              : 1;
  REQUIRE(m.indices.size() % per == 0);
  for (std::uint32_t i : m.indices) REQUIRE(i < m.positions.size());
  for (const glm::vec3& p : m.positions) REQUIRE(std::isfinite(p.x + p.y + p.z));
  if (m.primitive == Primitive::triangles && !m.positions.empty()) {
    REQUIRE(m.normals.size() == m.positions.size());
    for (const glm::vec3& n : m.normals) REQUIRE(std::abs(glm::length(n) - 1.0f) < 1e-3f);
  }
  if (!m.colors.empty()) {
    REQUIRE(m.colors.size() == m.positions.size());
    for (const glm::vec4& c : m.colors)
      REQUIRE((c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1 && c.a == 1));
  }
  if (!m.texCoords.empty()) REQUIRE(m.texCoords.size() == m.positions.size());
  REQUIRE(d.errorCount() == 0);
  REQUIRE(d.warningCount() <= 1);
  for (const glm::vec3& p : m.positions) {
    REQUIRE(p.x >= m.bounds.min.x);
    REQUIRE(p.z <= m.bounds.max.z);
  }
}

}  // namespace

TEST_CASE("tessellate: random IndexedFaceSet, IndexedLineSet and PointSet", "[geometry]") {
  Random r;
  for (int iter = 0; iter < 400; ++iter) {
    const int np = r.integer(0, 12);
    const auto coord = makeNode("Coordinate", {{"point", fv<FieldType::MFVec3f>(r.vec3s(np))}});
    const auto color =
        makeNode("Color", {{"color", fv<FieldType::MFColor>(r.vec3s(r.integer(0, 6)))}});
    const auto normal =
        makeNode("Normal", {{"vector", fv<FieldType::MFVec3f>(r.vec3s(r.integer(0, 6)))}});
    std::vector<glm::vec2> tc(static_cast<std::size_t>(r.integer(0, 6)));
    for (auto& t : tc) t = r.vec2();
    const auto tex = makeNode("TextureCoordinate", {{"point", fv<FieldType::MFVec2f>(tc)}});
    const int ni = r.integer(0, 40);
    std::vector<std::pair<std::string, FieldValue>> f = {
        {"coord", fv<FieldType::SFNode>(coord)},
        {"coordIndex", fv<FieldType::MFInt32>(r.indices(ni, np))},
        {"ccw", fv<FieldType::SFBool>(r.chance(0.5))},
        {"convex", fv<FieldType::SFBool>(r.chance(0.5))},
        {"creaseAngle", fv<FieldType::SFFloat>(r.chance(0.1) ? NAN : r.real(-1.0f, 4.0f))},
        {"colorPerVertex", fv<FieldType::SFBool>(r.chance(0.5))},
        {"normalPerVertex", fv<FieldType::SFBool>(r.chance(0.5))}};
    if (r.chance(0.5)) f.push_back({"color", fv<FieldType::SFNode>(color)});
    if (r.chance(0.5)) f.push_back({"normal", fv<FieldType::SFNode>(normal)});
    if (r.chance(0.5)) f.push_back({"texCoord", fv<FieldType::SFNode>(tex)});
    if (r.chance(0.5))
      f.push_back({"colorIndex", fv<FieldType::MFInt32>(r.indices(r.integer(0, 40), 6))});
    if (r.chance(0.5))
      f.push_back({"normalIndex", fv<FieldType::MFInt32>(r.indices(r.integer(0, 40), 6))});
    if (r.chance(0.5))
      f.push_back({"texCoordIndex", fv<FieldType::MFInt32>(r.indices(r.integer(0, 40), 6))});
    for (const char* type : {"IndexedFaceSet", "IndexedLineSet", "PointSet"}) {
      Diagnostics d;
      const Mesh m = tessellate(*makeNode(type, f), &d);
      checkWellFormed(m, d);
    }
  }
}

TEST_CASE("tessellate: random polygons, including self-intersecting ones", "[geometry]") {
  Random r;
  for (int iter = 0; iter < 300; ++iter) {
    const int n = r.integer(3, 90);
    std::vector<glm::vec3> p;
    const bool planar = r.chance(0.7);
    for (int k = 0; k < n; ++k) {
      if (r.chance(0.1) && !p.empty())
        p.push_back(p[static_cast<std::size_t>(r.integer(0, k - 1))]);
      else
        p.emplace_back(r.real(-1, 1), r.real(-1, 1), planar ? 0.0f : r.real(-0.2f, 0.2f));
    }
    std::vector<std::int32_t> idx;
    for (int k = 0; k < n; ++k) idx.push_back(k);
    const auto node = makeNode(
        "IndexedFaceSet", {{"coord", fv<FieldType::SFNode>(makeNode(
                                         "Coordinate", {{"point", fv<FieldType::MFVec3f>(p)}}))},
                           {"coordIndex", fv<FieldType::MFInt32>(idx)},
                           {"convex", fv<FieldType::SFBool>(r.chance(0.5))}});
    Diagnostics d;
    const Mesh m = tessellate(*node, &d);
    checkWellFormed(m, d);
    CHECK(m.triangleCount() <= static_cast<std::size_t>(n - 2));
    CHECK(d.items.empty());
  }
}

TEST_CASE("tessellate: random ElevationGrid and Extrusion", "[geometry]") {
  Random r;
  for (int iter = 0; iter < 300; ++iter) {
    Diagnostics d;
    std::vector<float> h(static_cast<std::size_t>(r.integer(0, 30)));
    for (float& x : h) x = r.value();
    std::vector<std::pair<std::string, FieldValue>> g = {
        {"xDimension", fv<FieldType::SFInt32>(r.chance(0.05) ? 2147483647 : r.integer(-2, 7))},
        {"zDimension", fv<FieldType::SFInt32>(r.chance(0.05) ? 2147483647 : r.integer(-2, 7))},
        {"xSpacing", fv<FieldType::SFFloat>(r.value())},
        {"zSpacing", fv<FieldType::SFFloat>(r.chance(0.8) ? 1.0f : r.value())},
        {"height", fv<FieldType::MFFloat>(h)},
        {"creaseAngle", fv<FieldType::SFFloat>(r.real(0, 3))},
        {"colorPerVertex", fv<FieldType::SFBool>(r.chance(0.5))},
        {"normalPerVertex", fv<FieldType::SFBool>(r.chance(0.5))}};
    if (r.chance(0.3))
      g.push_back(
          {"color", fv<FieldType::SFNode>(makeNode(
                        "Color", {{"color", fv<FieldType::MFColor>(r.vec3s(r.integer(0, 40)))}}))});
    if (r.chance(0.3))
      g.push_back(
          {"normal",
           fv<FieldType::SFNode>(makeNode(
               "Normal", {{"vector", fv<FieldType::MFVec3f>(r.vec3s(r.integer(0, 40)))}}))});
    checkWellFormed(tessellate(*makeNode("ElevationGrid", g), &d), d);

    Diagnostics d2;
    std::vector<glm::vec3> spine = r.vec3s(r.integer(0, 8));
    if (spine.size() > 2 && r.chance(0.3)) spine.back() = spine.front();
    if (spine.size() > 2 && r.chance(0.2)) spine[1] = spine[0];
    std::vector<glm::vec2> cs(static_cast<std::size_t>(r.integer(0, 9)));
    for (auto& c : cs) c = r.vec2();
    if (cs.size() > 2 && r.chance(0.5)) cs.back() = cs.front();
    std::vector<glm::vec2> scale(static_cast<std::size_t>(r.integer(0, 9)));
    for (auto& s : scale) s = r.vec2();
    std::vector<Rotation> orient(static_cast<std::size_t>(r.integer(0, 9)));
    for (auto& o : orient) o = {r.value(), r.value(), r.value(), r.value()};
    const auto e = makeNode("Extrusion", {{"spine", fv<FieldType::MFVec3f>(spine)},
                                          {"crossSection", fv<FieldType::MFVec2f>(cs)},
                                          {"scale", fv<FieldType::MFVec2f>(scale)},
                                          {"orientation", fv<FieldType::MFRotation>(orient)},
                                          {"ccw", fv<FieldType::SFBool>(r.chance(0.5))},
                                          {"convex", fv<FieldType::SFBool>(r.chance(0.5))},
                                          {"creaseAngle", fv<FieldType::SFFloat>(r.real(0, 3))}});
    checkWellFormed(tessellate(*e, &d2), d2);
  }
}

TEST_CASE("tessellate: oversized inputs are bounded", "[geometry]") {
  // 10^5 spine points times 6 * 10^5 crossSection points would be 6 * 10^10 grid points.
  std::vector<glm::vec3> spine(100000);
  for (std::size_t i = 0; i < spine.size(); ++i) spine[i] = {0.0f, static_cast<float>(i), 0.0f};
  std::vector<glm::vec2> cs(600000);
  for (std::size_t i = 0; i < cs.size(); ++i) cs[i] = {static_cast<float>(i), 0.0f};
  Diagnostics d;
  const Mesh m = tessellate(*makeNode("Extrusion", {{"spine", fv<FieldType::MFVec3f>(spine)},
                                                    {"crossSection", fv<FieldType::MFVec2f>(cs)}}),
                            &d);
  CHECK(m.positions.empty());
  CHECK(d.warningCount() == 1);
}
