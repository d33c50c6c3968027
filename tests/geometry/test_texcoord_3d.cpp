// X3D TextureCoordinate3D and TextureCoordinate4D (X3D 4.0 clauses 33.4.6, 33.4.7) in
// the meshes of IndexedFaceSet and the triangle sets (vrml::Mesh::texCoordsStrq), and
// castle-engine's extension fields on the primitives (Box.ccw, the primitives' and
// Text's texCoord): accepted in X3D worlds only, Box.ccw FALSE turning the box inside out.
#include <catch2/catch.hpp>

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"
#include "test_support.hpp"

#include <glm/glm.hpp>

#include <array>
#include <string>

using namespace gs::vrml;

namespace {

/// The geometry of `Shape { geometry <text> }` in an X3D Classic world; requires that the
/// world loads with no diagnostic.
NodePtr strqGeometry(const std::string& text) {
  const Scene scene =
      parseVrml("#X3D V3.2 utf8\nPROFILE Interchange\nCOMPONENT Texturing3D:2\nShape { geometry " +
                    text + " }\n",
                "strq.x3dv");
  std::string messages;
  for (const Diagnostic& d : scene.diagnostics.items) messages += d.format() + "\n";
  INFO(text << "\n" << messages);
  REQUIRE(scene.diagnostics.items.empty());
  REQUIRE(scene.rootNodes.size() == 1);
  NodePtr g = scene.rootNodes[0]->sfnode("geometry");
  REQUIRE(g != nullptr);
  return g;
}

/// Tessellates `text` (no warning allowed).
Mesh strqMesh(const std::string& text) {
  Diagnostics diag;
  Mesh m = tessellate(*strqGeometry(text), &diag);
  CHECK(diag.items.empty());
  return m;
}

/// The index of the mesh vertex at `p`, or -1.
int strqVertexAt(const Mesh& m, const glm::vec3& p) {
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (glm::all(glm::equal(m.positions[i], p))) return static_cast<int>(i);
  return -1;
}

const std::array<glm::vec3, 4> kQuad = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0),
                                        glm::vec3(0, 1, 0)};
const char* const kQuadCoord = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } ";

}  // namespace

TEST_CASE("TextureCoordinate3D: each IndexedFaceSet vertex carries its (s, t, r, 1)",
          "[geometry][x3d][texcoord3d]") {
  const Mesh m = strqMesh(std::string("IndexedFaceSet { ") + kQuadCoord +
                          "coordIndex [0 1 2 3 -1] texCoord TextureCoordinate3D { point [0.1 0.2 "
                          "0.3, 0.4 0.5 0.6, 0.7 0.8 0.9, 1 0 0.5] } }");
  REQUIRE(m.positions.size() == 4);
  REQUIRE(m.texCoordsStrq.size() == 4);
  REQUIRE(m.texCoords.size() == 4);
  const std::array<glm::vec4, 4> want = {glm::vec4(0.1f, 0.2f, 0.3f, 1),
                                         glm::vec4(0.4f, 0.5f, 0.6f, 1),
                                         glm::vec4(0.7f, 0.8f, 0.9f, 1), glm::vec4(1, 0, 0.5f, 1)};
  for (std::size_t k = 0; k < 4; ++k) {
    const int v = strqVertexAt(m, kQuad[k]);
    REQUIRE(v >= 0);
    CHECK(m.texCoordsStrq[static_cast<std::size_t>(v)] == want[k]);
    // 2D textures read (s, t).
    CHECK(m.texCoords[static_cast<std::size_t>(v)] == glm::vec2(want[k]));
  }
}

TEST_CASE("TextureCoordinate3D follows texCoordIndex; a plain TextureCoordinate gives none",
          "[geometry][x3d][texcoord3d]") {
  // texCoordIndex turns the points around: corner k takes point 3 - k.
  const Mesh m = strqMesh(std::string("IndexedFaceSet { ") + kQuadCoord +
                          "coordIndex [0 1 2 3 -1] texCoordIndex [3 2 1 0 -1] texCoord "
                          "TextureCoordinate3D { point [0 0 0, 0 0 1, 0 0 2, 0 0 3] } }");
  REQUIRE(m.texCoordsStrq.size() == m.positions.size());
  for (std::size_t k = 0; k < 4; ++k) {
    const int v = strqVertexAt(m, kQuad[k]);
    REQUIRE(v >= 0);
    CHECK(m.texCoordsStrq[static_cast<std::size_t>(v)].z == static_cast<float>(3 - k));
  }
  const Mesh plain = strqMesh(std::string("IndexedFaceSet { ") + kQuadCoord +
                              "coordIndex [0 1 2 3 -1] texCoord TextureCoordinate { point [0 0, 1 "
                              "0, 1 1, 0 1] } }");
  CHECK(plain.texCoordsStrq.empty());
  CHECK(plain.texCoords.size() == plain.positions.size());
}

TEST_CASE("TextureCoordinate4D: (s, t, r, q) kept, 2D coordinates divided by q",
          "[geometry][x3d][texcoord3d]") {
  // A TriangleSet's vertex i takes point i; (2, 4, 6, 2) reads as (1, 2) in 2D.
  const Mesh m = strqMesh(
      "TriangleSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } texCoord "
      "TextureCoordinate4D { point [2 4 6 2, 1 1 1 4, 0 0 0 0] } }");
  REQUIRE(m.texCoordsStrq.size() == 3);
  const int a = strqVertexAt(m, {0, 0, 0}), b = strqVertexAt(m, {1, 0, 0}),
            c = strqVertexAt(m, {0, 1, 0});
  REQUIRE((a >= 0 && b >= 0 && c >= 0));
  CHECK(m.texCoordsStrq[static_cast<std::size_t>(a)] == glm::vec4(2, 4, 6, 2));
  CHECK(m.texCoords[static_cast<std::size_t>(a)] == glm::vec2(1, 2));
  CHECK(m.texCoords[static_cast<std::size_t>(b)] == glm::vec2(0.25f, 0.25f));
  // q = 0 is no point: it reads as (0, 0, 0, 1).
  CHECK(m.texCoordsStrq[static_cast<std::size_t>(c)] == glm::vec4(0, 0, 0, 1));
  CHECK(m.texCoords[static_cast<std::size_t>(c)] == glm::vec2(0, 0));
}

TEST_CASE("ElevationGrid: TextureCoordinate4D per grid point; a generator is no missing point",
          "[geometry][x3d][texcoord3d]") {
  // A 2 x 2 grid, 1 m apart: grid point k = i + 2 j at (i, 0, j).
  const std::string grid = "ElevationGrid { xDimension 2 zDimension 2 height [0 0 0 0] ";
  const std::array<glm::vec3, 4> at = {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 0, 1),
                                       glm::vec3(1, 0, 1)};
  {
    const Mesh m = strqMesh(grid +
                            "texCoord TextureCoordinate4D { point [0 0 0 1, 2 0 1 2, 0 4 0 2, "
                            "1 1 0.5 1] } }");
    REQUIRE(m.texCoordsStrq.size() == m.positions.size());
    const std::array<glm::vec4, 4> want = {glm::vec4(0, 0, 0, 1), glm::vec4(2, 0, 1, 2),
                                           glm::vec4(0, 4, 0, 2), glm::vec4(1, 1, 0.5f, 1)};
    for (std::size_t k = 0; k < 4; ++k) {
      const int v = strqVertexAt(m, at[k]);
      REQUIRE(v >= 0);
      CHECK(m.texCoordsStrq[static_cast<std::size_t>(v)] == want[k]);
      CHECK(m.texCoords[static_cast<std::size_t>(v)] == glm::vec2(want[k]) / want[k].w);
    }
  }
  {
    // Generated when drawn: no "fewer points" warning (strqMesh allows none); the grid's
    // own coordinates stay.
    const Mesh m = strqMesh(grid + "texCoord TextureCoordinateGenerator { mode \"COORD\" } }");
    const int v = strqVertexAt(m, at[3]);
    REQUIRE(v >= 0);
    CHECK(m.texCoords[static_cast<std::size_t>(v)] == glm::vec2(1.0f, 1.0f));
  }
}

TEST_CASE("castle's Box.ccw FALSE turns the box inside out", "[geometry][x3d][castle]") {
  const Mesh out = strqMesh("Box { }");
  const Mesh in = strqMesh("Box { ccw FALSE }");
  REQUIRE(in.positions.size() == out.positions.size());
  REQUIRE(in.triangleCount() == 12);
  for (std::size_t t = 0; t < in.triangleCount(); ++t) {
    const glm::vec3 a = in.positions[in.indices[3 * t]], b = in.positions[in.indices[3 * t + 1]],
                    c = in.positions[in.indices[3 * t + 2]];
    const glm::vec3 n = in.normals[in.indices[3 * t]];
    // The normal points to the box's centre: for a face at +1 on some axis, n is -1 there.
    CHECK(glm::dot(n, (a + b + c) / 3.0f) < 0.0f);
    // Counter-clockwise seen from the side the normal points to (the inside).
    CHECK(glm::dot(glm::cross(b - a, c - a), n) > 0.0f);
  }
  // The default box is outward: same test, other sign.
  for (std::size_t t = 0; t < out.triangleCount(); ++t) {
    const glm::vec3 a = out.positions[out.indices[3 * t]];
    CHECK(glm::dot(out.normals[out.indices[3 * t]], a) > 0.0f);
  }
}

TEST_CASE("castle's primitive fields: X3D worlds accept them, VRML97 worlds do not",
          "[geometry][x3d][castle]") {
  for (const char* g :
       {"Box { ccw FALSE texCoord TextureCoordinateGenerator { mode \"COORD\" } }",
        "Sphere { texCoord TextureCoordinateGenerator { } }",
        "Cone { texCoord TextureCoordinateGenerator { } }",
        "Cylinder { texCoord TextureCoordinateGenerator { } }",
        "Text { string \"a\" texCoord TextureCoordinateGenerator { mode \"COORD-EYE\" } }"}) {
    const NodePtr n = strqGeometry(g);
    const NodePtr tc = n->sfnode("texCoord");
    REQUIRE(tc != nullptr);
    CHECK(tc->typeId() == NodeTypeId::TextureCoordinateGenerator);
  }
  // VRML97 has no such fields.
  const Scene vrml97 =
      parseVrml("#VRML V2.0 utf8\nShape { geometry Box { ccw FALSE } }\n", "b.wrl");
  REQUIRE(vrml97.diagnostics.items.size() == 1);
  CHECK(vrml97.diagnostics.items[0].message.find("ccw") != std::string::npos);
}

TEST_CASE("corpus: castle's Box.ccw, Text.texCoord and Texturing3D worlds load with no diagnostic",
          "[corpus][x3d][texcoord3d]") {
  if (!gs::test::haveCorpus("x3d/castle")) return;
  const auto dir = gs::test::corpusDir() / "x3d/castle";
  for (const char* world :
       {"texturing_advanced/tex3d_primitives_auto_gen.x3dv",
        "texturing_advanced/tex3d_repeat_modes.x3dv", "texturing_advanced/tex3d_simple_pixel.x3dv",
        "texturing_advanced/tex3d_simple_composed.x3dv", "text/text_textured.x3dv",
        "x3d/box_ccw.x3dv"}) {
    const Scene s = loadVrmlFile((dir / world).string());
    std::string messages;
    for (const Diagnostic& d : s.diagnostics.items) messages += d.format() + "\n";
    INFO(world << "\n" << messages);
    CHECK(s.diagnostics.items.empty());
    CHECK_FALSE(s.rootNodes.empty());
  }
}
