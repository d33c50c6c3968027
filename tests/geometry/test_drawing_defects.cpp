// Issue 12 point 6: convex polygons split as a fan from their first vertex (as
// castle-model-viewer and OpenGL's GL_POLYGON do), Cone sides in stacks with normals
// that depend only on the angle, and EXTERNPROTO URLs "#Name".
#include <catch2/catch.hpp>

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"

#include <cmath>
#include <set>
#include <string>

using namespace gs::vrml;

namespace {

Mesh meshOf(const std::string& geometry) {
  const Scene scene =
      parseVrml("#VRML V2.0 utf8\nShape { geometry " + geometry + " }\n", "test.wrl");
  for (const Diagnostic& d : scene.diagnostics.items) INFO(d.format());
  REQUIRE(scene.diagnostics.items.empty());
  REQUIRE(scene.rootNodes.size() == 1);
  return tessellate(*scene.rootNodes[0]->sfnode("geometry"));
}

/// The triangles of `m` as sets of the indices of `points` their corners lie on.
std::set<std::set<int>> trianglesByPoint(const Mesh& m, const std::vector<glm::vec3>& points) {
  std::set<std::set<int>> out;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    std::set<int> tri;
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t p = 0; p < points.size(); ++p)
        if (m.positions[m.indices[t + k]] == points[p]) tri.insert(static_cast<int>(p));
    out.insert(tri);
  }
  return out;
}

const std::vector<glm::vec3> kQuad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<glm::vec3> kPentagon = {{0, 0, 0}, {2, 0, 0}, {3, 1, 0}, {1, 2, 0}, {-1, 1, 0}};

}  // namespace

TEST_CASE("a convex quad is split along the diagonal from its first vertex",
          "[geometry][polygon]") {
  const std::string coords = "coord Coordinate { point [ 0 0 0, 1 0 0, 1 1 0, 0 1 0 ] } ";
  // Fan from vertex 0: (0 1 2) and (0 2 3), the diagonal 0-2.
  const std::set<std::set<int>> expected = {{0, 1, 2}, {0, 2, 3}};
  CHECK(trianglesByPoint(meshOf("IndexedFaceSet { " + coords + "coordIndex [ 0 1 2 3 ] }"),
                         kQuad) == expected);
  // ccw FALSE reverses the winding, not the split (castle's normals.wrl: "should look just
  // like example above").
  CHECK(trianglesByPoint(
            meshOf("IndexedFaceSet { ccw FALSE " + coords + "coordIndex [ 0 1 2 3 ] }"), kQuad) ==
        expected);
  // Starting the face at vertex 1 moves the diagonal to 1-3.
  CHECK(trianglesByPoint(meshOf("IndexedFaceSet { " + coords + "coordIndex [ 1 2 3 0 ] }"),
                         kQuad) == std::set<std::set<int>>{{1, 2, 3}, {1, 3, 0}});
}

TEST_CASE("a convex pentagon is a fan around its first vertex", "[geometry][polygon]") {
  const std::string text =
      "IndexedFaceSet { coord Coordinate { point [ 0 0 0, 2 0 0, 3 1 0, 1 2 0, -1 1 0 ] } "
      "coordIndex [ 0 1 2 3 4 ] }";
  CHECK(trianglesByPoint(meshOf(text), kPentagon) ==
        std::set<std::set<int>>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}});
}

TEST_CASE("Cone side normals depend only on the angle around the axis", "[geometry][cone]") {
  const Mesh m = meshOf("Cone { bottomRadius 1 height 2 bottom FALSE }");
  REQUIRE(!m.indices.empty());
  std::size_t checked = 0;
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3 p = m.positions[i];
    const float radial = std::hypot(p.x, p.z);
    if (radial < 1e-4f) continue;  // apex vertices carry their slice's middle normal
    // Slant normal for height 2, radius 1: (d * 2 + (0, 1, 0)) / sqrt(5), d = (x, z) / r.
    const glm::vec3 expected =
        glm::normalize(glm::vec3(p.x / radial * 2.0f, 1.0f, p.z / radial * 2.0f));
    CHECK(glm::length(m.normals[i] - expected) < 1e-4f);
    ++checked;
  }
  // Several stacks: vertices at more than two heights.
  std::set<float> heights;
  for (const glm::vec3& p : m.positions) heights.insert(p.y);
  CHECK(heights.size() >= 5);
  CHECK(checked > 4 * static_cast<std::size_t>(kRoundSegments));
}

TEST_CASE("EXTERNPROTO \"#Name\" names a PROTO of the same file", "[parser][proto]") {
  const Scene s = parseVrml(R"(#VRML V2.0 utf8
PROTO Local [ field SFFloat r 1 ] { Sphere { radius IS r } }
EXTERNPROTO Alias [ field SFFloat r ] [ "#Local" ]
Shape { geometry Alias { r 3 } }
EXTERNPROTO Missing [ field SFFloat r ] "#Nowhere"
)",
                            "self.wrl");
  REQUIRE(s.rootNodes.size() == 1);
  const NodePtr g = s.rootNodes[0]->sfnode("geometry");
  REQUIRE(g != nullptr);
  CHECK(g->typeName() == "Sphere");
  CHECK(g->get<FieldType::SFFloat>("radius", 0.0f) == 3.0f);
  // The missing one is a warning naming the PROTO.
  REQUIRE(s.diagnostics.items.size() == 1);
  CHECK(s.diagnostics.items[0].message.find("Nowhere") != std::string::npos);
}
