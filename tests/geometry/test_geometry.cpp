// Tessellation of the VRML97 geometry nodes (geometry/geometry.hpp); Extrusion's are in
// test_geometry_extrusion.cpp.
#include "geometry_checks.hpp"

using namespace gs::vrml;
using namespace gs::vrml::geometry_tests;

// ---- primitives -----------------------------------------------------------------------

TEST_CASE("Box: 12 triangles, exact area, outward flat normals, per-face texture", "[geometry]") {
  const Mesh m = mesh("Box { size 2 3 4 }");
  checkMesh(m);
  CHECK(m.triangleCount() == 12);
  CHECK(m.positions.size() == 24);
  CHECK(m.solid);
  CHECK(m.colors.empty());
  CHECK(area(m) == Approx(2.0 * (2 * 3 + 3 * 4 + 4 * 2)));
  CHECK(m.bounds.min == glm::vec3(-1, -1.5, -2));
  CHECK(m.bounds.max == glm::vec3(1, 1.5, 2));
  checkOutward(m, glm::dvec3(0.0));
  // Right side up seen from outside: on the front face (+Z) s grows with x and t with y;
  // on the back face s grows towards -X; on the top t grows towards -Z.
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3 p = m.positions[i], n = m.normals[i];
    const glm::vec2 tc = m.texCoords[i];
    if (n.z > 0.5f) CHECK(tc == glm::vec2(p.x > 0 ? 1 : 0, p.y > 0 ? 1 : 0));
    if (n.z < -0.5f) CHECK(tc == glm::vec2(p.x < 0 ? 1 : 0, p.y > 0 ? 1 : 0));
    if (n.x > 0.5f) CHECK(tc == glm::vec2(p.z < 0 ? 1 : 0, p.y > 0 ? 1 : 0));
    if (n.x < -0.5f) CHECK(tc == glm::vec2(p.z > 0 ? 1 : 0, p.y > 0 ? 1 : 0));
    if (n.y > 0.5f) CHECK(tc == glm::vec2(p.x > 0 ? 1 : 0, p.z < 0 ? 1 : 0));
    if (n.y < -0.5f) CHECK(tc == glm::vec2(p.x > 0 ? 1 : 0, p.z > 0 ? 1 : 0));
  }
  CHECK(mesh("Box { }").bounds.max == glm::vec3(1, 1, 1));
}

TEST_CASE("Sphere: area near 4 pi r^2, smooth outward normals, texture seam at -Z", "[geometry]") {
  const Mesh m = mesh("Sphere { radius 2 }");
  checkMesh(m);
  const int n = kRoundSegments, rings = kRoundSegments / 2;
  CHECK(m.triangleCount() == static_cast<std::size_t>(2 * n * (rings - 1)));
  CHECK(area(m) == Approx(4 * kPi * 4).epsilon(0.02));
  CHECK(area(m) < 4 * kPi * 4);
  checkOutward(m, glm::dvec3(0.0));
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    CHECK(glm::length(m.positions[i]) == Approx(2.0f));
    CHECK(glm::dot(m.normals[i], m.positions[i] / 2.0f) == Approx(1.0f));
    const glm::vec3 p = m.positions[i];
    const glm::vec2 tc = m.texCoords[i];
    CHECK(tc.y == Approx(0.5f + std::asin(std::clamp(p.y / 2.0f, -1.0f, 1.0f)) / kPi).margin(1e-5));
    // s = 0.25 at -X, 0.75 at +X (counterclockwise from the back, seen from +Y).
    if (p.x < -1e-3f && std::abs(p.z) < 1e-4f) CHECK(tc.x == Approx(0.25f));
    if (p.x > 1e-3f && std::abs(p.z) < 1e-4f) CHECK(tc.x == Approx(0.75f));
    if (p.z > 1e-3f && std::abs(p.x) < 1e-4f) CHECK(tc.x == Approx(0.5f));
  }
}

TEST_CASE("Cylinder: counts, area, caps flat and sides smooth", "[geometry]") {
  const float r = 1.5f, h = 3.0f;
  const Mesh m = mesh("Cylinder { radius 1.5 height 3 }");
  checkMesh(m);
  CHECK(m.triangleCount() == 4 * kRoundSegments);
  const double n = kRoundSegments;
  const double polygon = 0.5 * n * r * r * std::sin(2 * kPi / n);  // inscribed polygon
  const double side = n * 2 * r * std::sin(kPi / n) * h;
  CHECK(area(m) == Approx(2 * polygon + side));
  CHECK(area(m) == Approx(2 * kPi * r * r + 2 * kPi * r * h).epsilon(0.01));
  checkOutward(m, glm::dvec3(0.0));
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3 nn = m.normals[i], p = m.positions[i];
    if (std::abs(nn.y) > 0.5f) {
      CHECK(std::abs(p.y) == Approx(h / 2));
      // Caps: a circle cut from the texture, top right side up when tilted towards +Z.
      const float t = nn.y > 0 ? 0.5f - p.z / (2 * r) : 0.5f + p.z / (2 * r);
      CHECK(m.texCoords[i].x == Approx(0.5f + p.x / (2 * r)));
      CHECK(m.texCoords[i].y == Approx(t));
    } else {
      CHECK(nn.y == 0.0f);
      CHECK(m.texCoords[i].y == (p.y > 0 ? 1.0f : 0.0f));
    }
  }
  CHECK(mesh("Cylinder { top FALSE bottom FALSE }").triangleCount() == 2 * kRoundSegments);
  const Mesh capsOnly = mesh("Cylinder { side FALSE }");
  CHECK(capsOnly.triangleCount() == 2 * kRoundSegments);
  checkOutward(capsOnly, glm::dvec3(0.0));
}

TEST_CASE("Cone: counts, area, outward normals", "[geometry]") {
  const float r = 1.0f, h = 2.0f;
  const Mesh m = mesh("Cone { }");
  checkMesh(m);
  constexpr int side = (2 * (kConeStacks - 1) + 1) * kRoundSegments;
  CHECK(m.triangleCount() == side + kRoundSegments);
  CHECK(area(m) == Approx(kPi * r * (r + std::sqrt(r * r + h * h))).epsilon(0.01));
  checkOutward(m, glm::dvec3(0.0, -0.5, 0.0));
  CHECK(m.bounds.min.y == -1.0f);
  CHECK(m.bounds.max.y == 1.0f);
  CHECK(mesh("Cone { bottom FALSE }").triangleCount() == side);
  CHECK(mesh("Cone { side FALSE bottomRadius 3 }").bounds.max.x == Approx(3.0f));
}

TEST_CASE("Primitives with invalid sizes give an empty mesh and a warning", "[geometry]") {
  Diagnostics d;
  CHECK(mesh("Sphere { radius -1 }", &d).positions.empty());
  const NodePtr box = parseGeometry("Box { }");
  set<FieldType::SFVec3f>(box, "size", glm::vec3(1, NAN, 1));
  CHECK(tessellate(*box, &d).positions.empty());
  const NodePtr cone = parseGeometry("Cone { }");
  set<FieldType::SFFloat>(cone, "height", INFINITY);
  CHECK(tessellate(*cone, &d).positions.empty());
  CHECK(d.warningCount() == 3);
  CHECK(d.errorCount() == 0);
  CHECK(d.items[0].location.file == "test.wrl");
  CHECK(d.items[0].location.line == 2);
  CHECK(mesh("Cylinder { radius 0 }", &d).positions.empty());  // nothing to draw, no warning
  CHECK(d.warningCount() == 3);
}

TEST_CASE("Text and non-geometry nodes give an empty mesh", "[geometry]") {
  CHECK(mesh("Text { string \"hello\" }").positions.empty());
  CHECK(mesh("IndexedFaceSet { }").positions.empty());  // no coord
  CHECK(mesh("IndexedFaceSet { }").bounds.empty());
  CHECK(mesh("PointSet { }").positions.empty());
  const Scene scene = parseVrml("#VRML V2.0 utf8\nTransform { }", "t.wrl");
  REQUIRE(scene.rootNodes.size() == 1);
  CHECK(tessellate(*scene.rootNodes[0]).positions.empty());
}

// ---- IndexedFaceSet ---------------------------------------------------------------------

namespace {

/// Every triangle counterclockwise about `n` (positive area along it).
void checkFacing(const Mesh& m, glm::dvec3 n) {
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    REQUIRE(glm::dot(triangleNormal(m, t), n) > 0.0);
  for (const glm::vec3& v : m.normals) REQUIRE(glm::dot(glm::dvec3(v), n) == Approx(1.0));
}

// The unit cube's corners and faces, counterclockwise from outside.
const std::vector<glm::vec3> kCubePoints = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                            {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
const std::vector<std::int32_t> kCubeIndex = {0, 3, 2, 1, -1, 4, 5, 6, 7, -1, 0, 1, 5, 4, -1,
                                              2, 3, 7, 6, -1, 1, 2, 6, 5, -1, 0, 4, 7, 3, -1};

}  // namespace

TEST_CASE("IndexedFaceSet: concave L-shaped hexagon keeps its area", "[geometry]") {
  const std::vector<glm::vec3> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                    {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  for (const char* convex : {"TRUE", "FALSE"}) {
    // convex TRUE is a false claim here: the polygon must still be ear-clipped.
    const Mesh m = mesh(faceSet(l, {0, 1, 2, 3, 4, 5, -1}, std::string("convex ") + convex));
    checkMesh(m);
    CHECK(m.triangleCount() == 4);
    CHECK(area(m) == Approx(3.0).epsilon(1e-12));
    checkFacing(m, {0, 0, 1});
  }
  // The same in another plane, starting at the reflex vertex, without the final -1.
  const std::vector<glm::vec3> tilted = {{1, 1, 1}, {1, 2, 2}, {0, 2, 2},
                                         {0, 0, 0}, {2, 0, 0}, {2, 1, 1}};
  const Mesh m = mesh(faceSet(tilted, {0, 1, 2, 3, 4, 5}));
  checkMesh(m);
  CHECK(area(m) == Approx(3.0 * std::sqrt(2.0)));
  checkFacing(m, glm::normalize(glm::dvec3(0, -1, 1)));
}

TEST_CASE("IndexedFaceSet: collinear and repeated vertices", "[geometry]") {
  // A 2x2 square with a point in the middle of every side, and a repeated corner.
  const std::vector<glm::vec3> sq = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0},
                                     {2, 2, 0}, {1, 2, 0}, {0, 2, 0}, {0, 1, 0}};
  for (const char* convex : {"TRUE", "FALSE"}) {
    const Mesh m =
        mesh(faceSet(sq, {0, 1, 2, 2, 3, 4, 5, 6, 7, 0, -1}, std::string("convex ") + convex));
    checkMesh(m);
    CHECK(area(m) == Approx(4.0).epsilon(1e-12));
    CHECK(m.triangleCount() == 6);  // all 8 distinct vertices used, no sliver
    CHECK(m.positions.size() == 8);
    checkFacing(m, {0, 0, 1});
  }
  // A concave polygon with collinear points on its notch.
  const std::vector<glm::vec3> u = {{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {2, 3, 0}, {2, 2, 0},
                                    {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {1, 3, 0}, {0, 3, 0}};
  const Mesh m = mesh(faceSet(u, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, -1}, "convex FALSE"));
  checkMesh(m);
  CHECK(area(m) == Approx(9.0 - 2.0).epsilon(1e-12));
  checkFacing(m, {0, 0, 1});
}

TEST_CASE("IndexedFaceSet: degenerate polygons are skipped silently", "[geometry]") {
  Diagnostics d;
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  const Mesh m = mesh(faceSet(p, {0, 1, -1, 0, 1, 2, -1, 0, 0, 0, -1, -1, 0, 1, 3, -1}), &d);
  CHECK(m.triangleCount() == 1);
  CHECK(d.items.empty());
}

TEST_CASE("IndexedFaceSet: ccw FALSE flips the winding and the normals", "[geometry]") {
  const std::vector<glm::vec3> tri = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Mesh front = mesh(faceSet(tri, {0, 1, 2, -1}));
  checkMesh(front);
  checkFacing(front, {0, 0, 1});
  const Mesh back = mesh(faceSet(tri, {0, 1, 2, -1}, "ccw FALSE solid FALSE"));
  checkMesh(back);
  checkFacing(back, {0, 0, -1});
  CHECK_FALSE(back.solid);
  // A closed cube listed clockwise from outside becomes outward with ccw FALSE.
  std::vector<std::int32_t> reversed;
  for (std::size_t i = 0; i < kCubeIndex.size(); i += 5)
    reversed.insert(reversed.end(),
                    {kCubeIndex[i + 3], kCubeIndex[i + 2], kCubeIndex[i + 1], kCubeIndex[i], -1});
  const Mesh cube = mesh(faceSet(kCubePoints, reversed, "ccw FALSE"));
  checkMesh(cube);
  checkOutward(cube, glm::dvec3(0.5));
  CHECK(closedSurface(cube));
}

TEST_CASE("IndexedFaceSet: creaseAngle 0 gives 24 cube vertices, 3.14 gives 8", "[geometry]") {
  const Mesh flat = mesh(faceSet(kCubePoints, kCubeIndex));
  checkMesh(flat);
  CHECK(flat.triangleCount() == 12);
  CHECK(flat.positions.size() == 24);
  CHECK(distinct(flat.normals) == 6);
  checkOutward(flat, glm::dvec3(0.5));
  CHECK(closedSurface(flat));
  CHECK(area(flat) == Approx(6.0));
  CHECK(flat.texCoords.size() == 24);  // default texture coordinates

  const Mesh smooth = mesh(faceSet(kCubePoints, kCubeIndex, "creaseAngle 3.14"));
  checkMesh(smooth);
  CHECK(smooth.positions.size() == 8);  // default texture coordinates depend on position only
  CHECK(distinct(smooth.normals) == 8);
  for (std::size_t i = 0; i < smooth.positions.size(); ++i) {
    const glm::vec3 dir = glm::normalize(smooth.positions[i] - glm::vec3(0.5f));
    CHECK(glm::dot(smooth.normals[i], dir) == Approx(1.0f));
  }
  // 1.57 < pi/2: the cube's edges stay sharp.
  CHECK(distinct(mesh(faceSet(kCubePoints, kCubeIndex, "creaseAngle 1.57")).normals) == 6);
}

TEST_CASE("IndexedFaceSet: default and given texture coordinates", "[geometry]") {
  // A 4 (x) by 2 (z) rectangle at y = 1: S along X from 0 to 1, T along Z from 0 to 0.5.
  const std::vector<glm::vec3> p = {{0, 1, 0}, {0, 1, 2}, {4, 1, 2}, {4, 1, 0}};
  const Mesh m = mesh(faceSet(p, {0, 1, 2, 3, -1}));
  REQUIRE(m.texCoords.size() == m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    CHECK(m.texCoords[i].x == Approx(m.positions[i].x / 4));
    CHECK(m.texCoords[i].y == Approx(m.positions[i].z / 4));
  }
  // Given texture coordinates with texCoordIndex.
  const Mesh t = mesh(faceSet(p, {0, 1, 2, 3, -1},
                              "texCoord TextureCoordinate { point [0 0, 1 1] } "
                              "texCoordIndex [0 1 1 0 -1]"));
  for (std::size_t i = 0; i < t.positions.size(); ++i)
    CHECK(t.texCoords[i] == (t.positions[i].z == 2.0f ? glm::vec2(1, 1) : glm::vec2(0, 0)));
}

TEST_CASE("IndexedFaceSet: colours per face and per vertex", "[geometry]") {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> rgb = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::string colors = "color Color { color " + list(rgb) + " } ";
  SECTION("per face, in face order") {
    const Mesh m = mesh(faceSet(p, {0, 1, 2, -1, 0, 2, 3, -1}, colors + "colorPerVertex FALSE"));
    checkMesh(m);
    REQUIRE(m.colors.size() == m.positions.size());
    CHECK(m.positions.size() == 6);  // the shared diagonal is split by colour
    for (std::size_t t = 0; t < 2; ++t)
      for (int k = 0; k < 3; ++k) CHECK(m.colors[m.indices[3 * t + k]] == glm::vec4(rgb[t], 1.0f));
  }
  SECTION("per face, with colorIndex") {
    const Mesh m = mesh(
        faceSet(p, {0, 1, 2, -1, 0, 2, 3, -1}, colors + "colorPerVertex FALSE colorIndex [2 0]"));
    for (int k = 0; k < 3; ++k) CHECK(m.colors[m.indices[k]] == glm::vec4(0, 0, 1, 1));
    for (int k = 3; k < 6; ++k) CHECK(m.colors[m.indices[k]] == glm::vec4(1, 0, 0, 1));
  }
  SECTION("per vertex, through coordIndex and through colorIndex") {
    const std::vector<glm::vec3> four = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    const std::string fourColors = "color Color { color " + list(four) + " } ";
    const Mesh a = mesh(faceSet(p, {0, 1, 2, 3, -1}, fourColors));
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
      const auto k =
          static_cast<std::size_t>(std::find(p.begin(), p.end(), a.positions[i]) - p.begin());
      CHECK(a.colors[i] == glm::vec4(four[k], 1.0f));
    }
    const Mesh b = mesh(faceSet(p, {0, 1, 2, 3, -1}, fourColors + "colorIndex [3 3 3 0 -1]"));
    for (std::size_t i = 0; i < b.positions.size(); ++i)
      CHECK(b.colors[i] ==
            (b.positions[i] == p[3] ? glm::vec4(1, 0, 0, 1) : glm::vec4(1, 1, 1, 1)));
  }
  SECTION("colours are clamped and get alpha 1") {
    const NodePtr n = parseGeometry(
        faceSet(p, {0, 1, 2, -1}, "color Color { color [0 0 0] } colorPerVertex FALSE"));
    set<FieldType::MFColor>(n->sfnode("color"), "color", std::vector<glm::vec3>{{2, -1, NAN}});
    for (const glm::vec4& c : tessellate(*n).colors) CHECK(c == glm::vec4(1, 0, 0, 1));
  }
}

TEST_CASE("IndexedFaceSet: given normals per vertex and per face", "[geometry]") {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::string normals = "normal Normal { vector [0 0 2, 0 1 1] } ";
  const Mesh perFace = mesh(
      faceSet(p, {0, 1, 2, -1, 0, 2, 3, -1}, normals + "normalPerVertex FALSE normalIndex [1 0]"));
  checkMesh(perFace);
  for (int k = 0; k < 3; ++k)
    CHECK(perFace.normals[perFace.indices[k]] == glm::normalize(glm::vec3(0, 1, 1)));
  for (int k = 3; k < 6; ++k) CHECK(perFace.normals[perFace.indices[k]] == glm::vec3(0, 0, 1));
  const Mesh perVertex = mesh(faceSet(p, {0, 1, 2, -1}, normals + "normalIndex [0 1 0 -1]"));
  CHECK(distinct(perVertex.normals) == 2);
  // Huge vectors are normalized without overflow; vanishing ones are generated instead.
  const Mesh extreme = mesh(faceSet(p, {0, 1, 2, -1, 0, 2, 3, -1},
                                    "normal Normal { vector [0 0 1e30, 0 0 1e-30] } "
                                    "normalPerVertex FALSE"));
  checkMesh(extreme);
  for (const glm::vec3& n : extreme.normals) CHECK(n == glm::vec3(0, 0, 1));
}

TEST_CASE("IndexedFaceSet: bad indices are skipped with one warning", "[geometry]") {
  const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}};
  const NodePtr n = parseGeometry(
      faceSet(p, {0, 1, 2, -1, 0, 1, 99, -1, 0, -5, 2, -1, 0, 1, 3, -1, 2, 1, 0},
              "color Color { color [1 0 0] } colorIndex [0 0 7] "
              "normal Normal { vector [] } "
              "texCoord TextureCoordinate { point [0 0] } texCoordIndex [0 0 0 -1 1000000]"));
  set<FieldType::MFVec3f>(n->sfnode("coord"), "point",
                          std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {NAN, 0, 0}});
  Diagnostics d;
  const Mesh m = tessellate(*n, &d);
  checkMesh(m);
  CHECK(m.triangleCount() == 2);  // the first and the last polygon
  REQUIRE(d.items.size() == 1);
  CHECK(d.items[0].severity == Severity::warning);
  CHECK(d.items[0].location.line == 2);
  CHECK(d.items[0].message.find("IndexedFaceSet") == 0);
  // Without diagnostics it must not crash either.
  CHECK(tessellate(*n).triangleCount() == 2);
}

TEST_CASE("IndexedFaceSet: large concave polygons keep their area", "[geometry]") {
  // Star polygons (every other vertex pulled in) and a comb: many reflex vertices, over
  // 64 vertices so the accelerated ear test is used too.
  for (int spikes : {5, 17, 200}) {
    std::vector<glm::vec3> p;
    std::vector<std::int32_t> idx;
    double expected = 0.0;
    for (int k = 0; k < 2 * spikes; ++k) {
      const double a = kPi * k / spikes, r = (k % 2 == 0) ? 2.0 : 0.7;
      p.emplace_back(static_cast<float>(r * std::cos(a)), static_cast<float>(r * std::sin(a)),
                     0.0f);
      idx.push_back(k);
    }
    for (std::size_t k = 0; k < p.size(); ++k) {
      const glm::dvec3 a(p[k]), b(p[(k + 1) % p.size()]);
      expected += 0.5 * (a.x * b.y - b.x * a.y);
    }
    const Mesh m = mesh(faceSet(p, idx, "convex FALSE"));
    checkMesh(m);
    CHECK(m.triangleCount() == p.size() - 2);
    CHECK(area(m) == Approx(expected).epsilon(1e-5));
    checkFacing(m, {0, 0, 1});
  }
  std::vector<glm::vec3> comb;  // teeth along x, clockwise listing (normal -Z)
  const int teeth = 50;
  comb.emplace_back(0, 0, 0);
  for (int k = 0; k < teeth; ++k) {
    comb.emplace_back(2 * k, 3, 0);
    comb.emplace_back(2 * k + 1, 3, 0);
    comb.emplace_back(2 * k + 1, 1, 0);
    comb.emplace_back(2 * k + 2, 1, 0);
  }
  comb.emplace_back(2 * teeth, 0, 0);
  std::vector<std::int32_t> idx;
  for (std::size_t k = 0; k < comb.size(); ++k) idx.push_back(static_cast<std::int32_t>(k));
  const Mesh m = mesh(faceSet(comb, idx, "convex FALSE"));
  checkMesh(m);
  CHECK(area(m) == Approx(2.0 * teeth + 2.0 * teeth));
  checkFacing(m, {0, 0, -1});
}

TEST_CASE("IndexedFaceSet: smoothing stays fast around a huge fan", "[geometry]") {
  // 20000 triangles sharing their first point, creaseAngle 0.5: clusters keep this linear.
  std::vector<glm::vec3> p = {{0, 0, 0}};
  std::vector<std::int32_t> idx;
  const int n = 20000;
  for (int k = 0; k <= n; ++k) {
    const double a = 2 * kPi * k / n;
    p.emplace_back(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)),
                   static_cast<float>(0.3 * std::sin(7 * a)));
  }
  for (int k = 0; k < n; ++k) idx.insert(idx.end(), {0, k + 1, k + 2, -1});
  const Mesh m = mesh(faceSet(p, idx, "creaseAngle 0.5"));
  checkMesh(m);
  CHECK(m.triangleCount() == static_cast<std::size_t>(n));
}

// ---- IndexedLineSet and PointSet --------------------------------------------------------

TEST_CASE("IndexedLineSet: polylines become segment pairs with colours", "[geometry]") {
  const std::string coord = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] } ";
  const Mesh m = mesh("IndexedLineSet { " + coord +
                      "coordIndex [0 1 2 -1 3 0] colorPerVertex FALSE "
                      "color Color { color [1 0 0, 0 0 1] } }");
  CHECK(m.primitive == Primitive::lines);
  REQUIRE(m.indices.size() == 6);  // 2 + 1 segments
  CHECK(m.normals.empty());
  CHECK(m.texCoords.empty());
  REQUIRE(m.colors.size() == m.positions.size());
  CHECK(m.colors[m.indices[0]] == glm::vec4(1, 0, 0, 1));
  CHECK(m.colors[m.indices[5]] == glm::vec4(0, 0, 1, 1));
  CHECK(m.positions[m.indices[4]] == glm::vec3(0, 1, 0));
  CHECK(m.positions[m.indices[5]] == glm::vec3(0, 0, 0));
  CHECK(m.bounds.max == glm::vec3(1, 1, 0));

  Diagnostics d;
  const Mesh bad = mesh("IndexedLineSet { " + coord + "coordIndex [0 1 9 2 3 -2] }", &d);
  CHECK(bad.indices.size() == 4);  // 0-1 and 2-3: the line breaks at the bad index
  CHECK(d.warningCount() == 1);
}

TEST_CASE("PointSet: one point per coordinate, with colours", "[geometry]") {
  const NodePtr n = parseGeometry(
      "PointSet { coord Coordinate { point [0 0 0, 1 2 3, 4 4 4] } color Color { color [0 1 0] } "
      "}");
  set<FieldType::MFVec3f>(n->sfnode("coord"), "point",
                          std::vector<glm::vec3>{{0, 0, 0}, {1, 2, 3}, {NAN, 0, 0}});
  Diagnostics d;
  const Mesh m = tessellate(*n, &d);
  CHECK(m.primitive == Primitive::points);
  CHECK(m.positions.size() == 2);
  CHECK(m.indices == std::vector<std::uint32_t>{0, 1});
  CHECK(m.colors == std::vector<glm::vec4>{{0, 1, 0, 1}, {1, 1, 1, 1}});
  CHECK(m.bounds.max == glm::vec3(1, 2, 3));
  CHECK(d.warningCount() == 1);
}

// ---- ElevationGrid ----------------------------------------------------------------------

TEST_CASE("ElevationGrid: 3x3 flat grid, counts, normals up, texture", "[geometry]") {
  const Mesh m = mesh(
      "ElevationGrid { xDimension 3 zDimension 3 xSpacing 0.5 zSpacing 2 "
      "height [1 1 1, 1 1 1, 1 1 1] }");
  checkMesh(m);
  CHECK(m.triangleCount() == 8);
  CHECK(m.positions.size() == 9);
  CHECK(area(m) == Approx(1.0 * 4.0));
  for (const glm::vec3& n : m.normals) CHECK(n == glm::vec3(0, 1, 0));
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    CHECK(m.texCoords[i] == glm::vec2(m.positions[i].x / 1.0f, m.positions[i].z / 4.0f));
  CHECK(m.bounds.min == glm::vec3(0, 1, 0));
  CHECK(m.bounds.max == glm::vec3(1, 1, 4));

  const Mesh down =
      mesh("ElevationGrid { xDimension 3 zDimension 3 ccw FALSE height [0 0 0 0 0 0 0 0 0] }");
  checkMesh(down);
  for (const glm::vec3& n : down.normals) CHECK(n == glm::vec3(0, -1, 0));
}

TEST_CASE("ElevationGrid: a ridge, colours per quad, creaseAngle", "[geometry]") {
  auto grid = [](const std::string& crease) {
    return mesh("ElevationGrid { xDimension 3 zDimension 2 height [0 1 0, 0 1 0] creaseAngle " +
                crease + " colorPerVertex FALSE color Color { color [1 0 0, 0 0 1] } }");
  };
  const Mesh sharp = grid("0");
  checkMesh(sharp);
  CHECK(sharp.triangleCount() == 4);
  CHECK(distinct(sharp.normals) == 2);
  CHECK(area(sharp) == Approx(2 * std::sqrt(2.0)));
  for (std::size_t i = 0; i < sharp.positions.size(); ++i)
    CHECK(sharp.colors[i] ==
          (sharp.normals[i].x < 0 ? glm::vec4(1, 0, 0, 1) : glm::vec4(0, 0, 1, 1)));
  const Mesh smooth = grid("2");
  checkMesh(smooth);
  for (std::size_t i = 0; i < smooth.positions.size(); ++i) {
    const glm::vec3 n = smooth.normals[i];
    if (smooth.positions[i].x == 1.0f) {  // the ridge vertices get (0, 1, 0)
      CHECK(n.x == Approx(0.0f).margin(1e-5));
      CHECK(n.y == Approx(1.0f).margin(1e-5));
    } else {  // the slopes keep their own
      CHECK(std::abs(n.x) == Approx(std::sqrt(0.5f)).margin(1e-5));
    }
  }
}

TEST_CASE("ElevationGrid: a cell whose heights are not in one plane is two facets", "[geometry]") {
  // Split across the diagonal from (0, 0) to (1, 1), as X_ITE splits it: the corner
  // raised at (1, 0) tilts one triangle only.
  const Mesh m = mesh("ElevationGrid { xDimension 2 zDimension 2 height [0 1 0 0] }");
  checkMesh(m);
  CHECK(m.triangleCount() == 2);
  REQUIRE(distinct(m.normals) == 2);
  bool flat = false;
  for (const glm::vec3& n : m.normals) flat = flat || n == glm::vec3(0.0f, 1.0f, 0.0f);
  CHECK(flat);
}

TEST_CASE("ElevationGrid: dimensions larger than the height array", "[geometry]") {
  Diagnostics d;
  const std::string nine = " height [0 0 0 0 0 0 0 0 0] }";
  CHECK(mesh("ElevationGrid { xDimension 3 zDimension 2147483647" + nine, &d).triangleCount() ==
        8);  // the 3 complete rows
  CHECK(mesh("ElevationGrid { xDimension 2147483647 zDimension 2147483647" + nine, &d)
            .positions.empty());
  CHECK(mesh("ElevationGrid { xDimension -4 zDimension 3" + nine, &d).positions.empty());
  CHECK(mesh("ElevationGrid { xDimension 1 zDimension 9" + nine, &d).positions.empty());
  CHECK(d.warningCount() == 3);  // the line (1 x 9) is no error, just nothing to draw
  const NodePtr holed = parseGeometry("ElevationGrid { xDimension 3 zDimension 3" + nine);
  std::vector<float> h(9, 0.0f);
  h[4] = NAN;
  set<FieldType::MFFloat>(holed, "height", h);
  CHECK(tessellate(*holed, &d).triangleCount() == 0);  // every quad touches the centre
  CHECK(d.warningCount() == 4);
  // A grid of a few million points or less takes its missing heights as 0 (X_ITE 15): no
  // height at all is a flat grid, without a warning; a short array, one warning.
  Diagnostics flat;
  const Mesh none = mesh("ElevationGrid { xDimension 20 zDimension 20 }", &flat);
  CHECK(none.triangleCount() == 2 * 19 * 19);
  CHECK(none.bounds.max.y == 0.0f);
  CHECK(flat.items.empty());
  const Mesh shortGrid =
      mesh("ElevationGrid { xDimension 3 zDimension 3 height [ 1 1 1 ] }", &flat);
  CHECK(shortGrid.triangleCount() == 8);
  CHECK(shortGrid.bounds.max.y == 1.0f);
  CHECK(flat.warningCount() == 1);
}
