// VRML97 worlds flattened into triangles for the QNV surface encoder.
#include <catch2/catch.hpp>

#include <glm/geometric.hpp>

#include "encodings/parser.hpp"
#include "qnv/encoder.hpp"
#include "scene/world_triangles.hpp"

namespace {

std::shared_ptr<const gs::vrml::Scene> parse(const std::string& text) {
  return std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(text, "test.wrl"));
}

}  // namespace

TEST_CASE("world triangles carry the Transform and the Material colour", "[app][qnv]") {
  const auto mesh = gs::scene::worldTriangles(parse(R"(#VRML V2.0 utf8
Transform { translation 10 0 0 children Shape {
  appearance Appearance { material Material { diffuseColor 1 0 0 transparency 0.5 } }
  geometry Box { size 2 2 2 } } }
Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 2] } }
Shape { geometry PointSet { coord Coordinate { point [0 0 0] } } }
)"));
  REQUIRE(mesh.triangleCount() == 12 + 1);  // the PointSet adds nothing
  REQUIRE(mesh.vertexColors.size() == mesh.positions.size());
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (std::size_t i = 0; i < 12 * 3; ++i) {
    const glm::vec3 p = mesh.positions[mesh.indices[i]];
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
    CHECK(mesh.vertexColors[mesh.indices[i]] == gs::qnv::Rgba8(255, 0, 0, 128));
  }
  CHECK(lo == glm::vec3(9, -1, -1));
  CHECK(hi == glm::vec3(11, 1, 1));
  // No Material: unlit white (clause 6.3).
  CHECK(mesh.vertexColors[mesh.indices[36]] == gs::qnv::Rgba8(255, 255, 255, 255));
}

TEST_CASE("a mirroring Transform keeps triangle normals facing out", "[app][qnv]") {
  const auto mesh = gs::scene::worldTriangles(parse(R"(#VRML V2.0 utf8
Transform { scale -1 1 1 children Shape { geometry IndexedFaceSet {
  coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 2] } } }
)"));
  REQUIRE(mesh.triangleCount() == 1);
  const glm::vec3 a = mesh.positions[mesh.indices[0]], b = mesh.positions[mesh.indices[1]],
                  c = mesh.positions[mesh.indices[2]];
  CHECK(glm::cross(b - a, c - a).z > 0.0f);  // mirrored in x, the face still points to +Z
  const auto encoded = gs::qnv::encodeSurface(mesh, {});
  REQUIRE(encoded.records.size() == 1);
  CHECK(gs::qnv::unpackRecord(encoded.records[0]).theta == 0);
}
