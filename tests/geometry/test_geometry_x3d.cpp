// Tessellation of the X3D geometry nodes (geometry/geometry.hpp): the Rendering component's
// triangle sets and LineSet (X3D 4.0 clause 11), CADGeometry's quad sets (clause 32),
// Geometry2D (clause 14), ColorRGBA wherever colours are read and `solid` on the
// primitives.
#include <catch2/catch.hpp>

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"
#include "geometry_checks.hpp"
#include "test_support.hpp"

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <set>
#include <tuple>

using namespace gs::vrml;
using gs::test::corpusDir;
using gs::test::haveCorpus;
using gs::test::readBytes;
using gs::vrml::geometry_tests::area;
using gs::vrml::geometry_tests::checkMesh;
using gs::vrml::geometry_tests::P;
using gs::vrml::geometry_tests::triangleNormal;

namespace {

/// The geometry node of `Shape { geometry <text> }`, parsed as an X3D Classic VRML file
/// (which must give no diagnostics).
NodePtr parseGeometry(const std::string& text) {
  const Scene scene =
      parseVrml("#X3D V4.0 utf8\nPROFILE Full\nShape { geometry " + text + " }\n", "test.x3dv");
  INFO(text);
  std::string messages;
  for (const Diagnostic& d : scene.diagnostics.items) messages += d.format() + "\n";
  INFO(messages);
  REQUIRE(scene.diagnostics.items.empty());
  REQUIRE(scene.rootNodes.size() == 1);
  NodePtr g = scene.rootNodes[0]->sfnode("geometry");
  REQUIRE(g != nullptr);
  return g;
}

/// Tessellates `text`; requires no warning unless `diag` is given.
Mesh mesh(const std::string& text, Diagnostics* diag = nullptr) {
  Diagnostics own;
  Mesh m = tessellate(*parseGeometry(text), diag != nullptr ? diag : &own);
  if (diag == nullptr) {
    std::string messages;
    for (const Diagnostic& d : own.items) messages += d.format() + "\n";
    INFO(messages);
    CHECK(own.items.empty());
  }
  return m;
}

/// Lines or points: indices in range, no normals or texture coordinates, not solid.
void checkLines(const Mesh& m, Primitive p) {
  REQUIRE(m.primitive == p);
  REQUIRE(m.indices.size() % (p == Primitive::lines ? 2 : 1) == 0);
  for (std::uint32_t i : m.indices) REQUIRE(i < m.positions.size());
  CHECK(m.normals.empty());
  CHECK(m.texCoords.empty());
  CHECK_FALSE(m.solid);
}

std::size_t segmentCount(const Mesh& m) {
  return m.primitive == Primitive::lines ? m.indices.size() / 2 : 0;
}

/// Every triangle's geometric normal points to +Z (or -Z with `sign` -1).
void allFacing(const Mesh& m, double sign) {
  for (std::size_t t = 0; t < m.triangleCount(); ++t) REQUIRE(triangleNormal(m, t).z * sign > 0.0);
}

/// The colour of the vertex at `pos` (the first one there).
glm::vec4 colorAt(const Mesh& m, const glm::vec3& pos) {
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    if (m.positions[i] == pos) return m.colors.at(i);
  FAIL("no vertex at the position");
  return {};
}

const std::string kTri = "coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] }";
const std::string kSquare = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0] }";

}  // namespace

// ---- Rendering component: triangle sets -------------------------------------------------

TEST_CASE("IndexedTriangleSet: one triangle, +Z normal, ccw and solid", "[x3d][geometry]") {
  const Mesh m = mesh("IndexedTriangleSet { index [0 1 2] " + kTri + " }");
  checkMesh(m);
  CHECK(m.triangleCount() == 1);
  CHECK(m.positions.size() == 3);
  CHECK(m.solid);
  for (const glm::vec3& n : m.normals) CHECK(n == glm::vec3(0, 0, 1));
  CHECK(area(m) == Approx(0.5));
  CHECK_FALSE(m.texCoords.empty());  // default (bounding box) texture coordinates

  const Mesh back = mesh("IndexedTriangleSet { ccw FALSE solid FALSE index [0 1 2] " + kTri + " }");
  checkMesh(back);
  CHECK_FALSE(back.solid);
  for (const glm::vec3& n : back.normals) CHECK(n == glm::vec3(0, 0, -1));
  allFacing(back, -1.0);
}

TEST_CASE("IndexedTriangleSet: smooth normals at shared indices, flat when normalPerVertex FALSE",
          "[x3d][geometry]") {
  // A roof: two triangles meeting at the ridge x = 0 at right angles.
  const std::string roof =
      "coord Coordinate { point [0 1 0, 0 1 -1, -1 0 0, 1 0 0, 1 0 -1, -1 0 -1] } "
      "index [0 5 2, 0 1 5, 0 3 4, 0 4 1]";
  const Mesh smooth = mesh("IndexedTriangleSet { " + roof + " }");
  checkMesh(smooth);
  CHECK(smooth.triangleCount() == 4);
  CHECK(smooth.positions.size() == 6);  // ridge vertices shared, normal averaged
  for (std::size_t i = 0; i < smooth.positions.size(); ++i)
    if (smooth.positions[i].x == 0.0f) {
      CHECK(smooth.normals[i].x == Approx(0.0).margin(1e-6));
      CHECK(smooth.normals[i].y == Approx(1.0));
    }
  const Mesh flat = mesh("IndexedTriangleSet { normalPerVertex FALSE " + roof + " }");
  checkMesh(flat);
  CHECK(flat.triangleCount() == 4);
  CHECK(flat.positions.size() == 8);  // the ridge is split between the two slopes
  for (const glm::vec3& n : flat.normals) CHECK(std::abs(n.x) == Approx(std::sqrt(0.5)));
}

TEST_CASE("IndexedTriangleSet: given normals, per vertex and per face", "[x3d][geometry]") {
  const Mesh m = mesh("IndexedTriangleSet { index [0 1 2] " + kTri +
                      " normal Normal { vector [0 0 1, 0.6 0 0.8, 0 0.6 0.8] } }");
  checkMesh(m);
  std::set<std::tuple<float, float, float>> ns;
  for (const glm::vec3& n : m.normals) ns.emplace(n.x, n.y, n.z);
  CHECK(ns.size() == 3);
  CHECK(ns.count({0.6f, 0.0f, 0.8f}) == 1);
  const Mesh f = mesh("IndexedTriangleSet { normalPerVertex FALSE index [0 1 2] " + kTri +
                      " normal Normal { vector [0.6 0 0.8] } }");
  checkMesh(f);
  for (const glm::vec3& n : f.normals) CHECK(n == glm::vec3(0.6f, 0.0f, 0.8f));
}

TEST_CASE("IndexedTriangleSet: bad indices are skipped with one warning", "[x3d][geometry]") {
  Diagnostics d;
  const Mesh m = mesh("IndexedTriangleSet { index [0 1 7, 0 1 2, -1 0 1] " + kTri + " }", &d);
  checkMesh(m);
  CHECK(m.triangleCount() == 1);
  REQUIRE(d.warningCount() == 1);
  CHECK(d.items[0].severity == Severity::warning);
  CHECK(d.items[0].message.find("index[2] = 7") != std::string::npos);
  CHECK(d.items[0].message.find("IndexedTriangleSet") != std::string::npos);
  CHECK(d.items[0].message.find("1 more") != std::string::npos);
  // An incomplete last triangle: its indices "shall be ignored" (clause 11.4), silently.
  Diagnostics d2;
  const Mesh part = mesh("IndexedTriangleSet { index [0 1 2 0 1] " + kTri + " }", &d2);
  CHECK(part.triangleCount() == 1);
  CHECK(area(part) == Approx(0.5));
  CHECK(d2.items.empty());
}

TEST_CASE("TriangleSet: consecutive triples, flat normals, leftovers ignored", "[x3d][geometry]") {
  const Mesh m = mesh(
      "TriangleSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0, 0 0 0, 0 1 0, 0 0 -1] } }");
  checkMesh(m);
  CHECK(m.triangleCount() == 2);
  CHECK(m.positions.size() == 6);  // not shared between the two faces: flat normals
  CHECK(area(m) == Approx(1.0));
  // The 4th point makes no triangle: ignored (clause 11.4), without a diagnostic, and
  // it is not in the mesh (the bounds stop at the first triangle).
  Diagnostics d;
  const Mesh l =
      mesh("TriangleSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0, 5 5 5] } }", &d);
  CHECK(l.triangleCount() == 1);
  CHECK(l.positions.size() == 3);
  CHECK(l.bounds.max == glm::vec3(1, 1, 0));
  CHECK(d.items.empty());
}

TEST_CASE("TriangleFanSet and TriangleStripSet: counts split and winding kept", "[x3d][geometry]") {
  // A fan of 5 points around (0,0,0): 3 triangles; a strip of 6 points: 4 triangles.
  const Mesh fan = mesh(
      "TriangleFanSet { fanCount [5 3] coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, "
      "-1 1 0, 5 0 0, 6 0 0, 5 1 0] } }");
  checkMesh(fan);
  CHECK(fan.triangleCount() == 4);
  allFacing(fan, 1.0);
  CHECK(area(fan) == Approx(0.5 + 0.5 + 0.5 + 0.5));
  const Mesh strip = mesh(
      "TriangleStripSet { stripCount [6] coord Coordinate { point [0 0 0, 0 -1 0, 1 0 0, 1 -1 "
      "0, 2 0 0, 2 -1 0] } }");
  checkMesh(strip);
  CHECK(strip.triangleCount() == 4);
  allFacing(strip, 1.0);  // odd triangles turned round: all counter-clockwise like the first
  CHECK(area(strip) == Approx(2.0));
  CHECK(strip.positions.size() == 6);
  for (const glm::vec3& n : strip.normals) CHECK(n.z == Approx(1.0));

  Diagnostics d;
  const Mesh bad = mesh("TriangleFanSet { fanCount [2 3 9] " + kSquare + " }", &d);
  // fanCount 2 is too small (skips 2 points), 3 would need points 2..4: cut short to 2.
  CHECK(bad.triangleCount() == 0);
  CHECK(d.warningCount() == 1);
}

TEST_CASE("IndexedTriangleFanSet and IndexedTriangleStripSet: -1 separates fans and strips",
          "[x3d][geometry]") {
  const std::string pts = "coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, -1 1 0] }";
  const Mesh fan = mesh("IndexedTriangleFanSet { index [0 1 2 3 4 -1 0 1 2] " + pts + " }");
  checkMesh(fan);
  CHECK(fan.triangleCount() == 4);
  allFacing(fan, 1.0);
  // Strip 1 gives (0 1 3) and, turned round, (3 1 2); strip 2 (0 3 4). Without the -1 the
  // strip would give 5 triangles.
  const Mesh strip = mesh("IndexedTriangleStripSet { index [0 1 3 2 -1 0 3 4] " + pts + " }");
  checkMesh(strip);
  CHECK(strip.triangleCount() == 3);
  allFacing(strip, 1.0);
  CHECK(area(strip) == Approx(1.5));

  Diagnostics d;
  const Mesh bad = mesh("IndexedTriangleStripSet { index [0 1 -1 0 1 2 9] " + pts + " }", &d);
  CHECK(bad.triangleCount() == 1);  // the run of 2 and the triangle (1 2 9) are dropped
  CHECK(d.warningCount() == 1);
}

TEST_CASE("IndexedQuadSet and QuadSet: two triangles per quad", "[x3d][geometry]") {
  const Mesh q = mesh("IndexedQuadSet { index [0 1 2 3] " + kSquare + " }");
  checkMesh(q);
  CHECK(q.triangleCount() == 2);
  CHECK(area(q) == Approx(1.0));
  allFacing(q, 1.0);
  const Mesh qs = mesh(
      "QuadSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 0 0 0, 0 1 0, 0 1 -1, 0 "
      "0 -1] } }");
  checkMesh(qs);
  CHECK(qs.triangleCount() == 4);
  CHECK(area(qs) == Approx(2.0));
  // Index 4 is out of range (reported); the lone last index makes no quad and is ignored
  // silently (clause 32.4).
  Diagnostics d;
  const Mesh bad = mesh("IndexedQuadSet { index [0 1 2 4, 0 1 2 3, 0] " + kSquare + " }", &d);
  CHECK(bad.triangleCount() == 2);
  REQUIRE(d.warningCount() == 1);
  CHECK(d.items[0].message.find("= 4") != std::string::npos);
  // A QuadSet of 6 points: one quad; points 5 and 6 (far away) are not in the mesh.
  Diagnostics d3;
  const Mesh rest = mesh(
      "QuadSet { coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 0 1 0, 9 9 9, 8 8 8] } }", &d3);
  CHECK(rest.triangleCount() == 2);
  CHECK(area(rest) == Approx(1.0));
  CHECK(rest.bounds.max == glm::vec3(1, 1, 0));
  CHECK(d3.items.empty());
}

TEST_CASE("Composed sets: Color and ColorRGBA, per vertex and per face", "[x3d][geometry]") {
  const Mesh m = mesh("IndexedTriangleSet { index [0 1 2] " + kTri +
                      " color ColorRGBA { color [1 0 0 0.5, 0 1 0 0.25, 0 0 1 1] } }");
  checkMesh(m);
  REQUIRE(m.colors.size() == m.positions.size());
  CHECK(colorAt(m, {1, 0, 0}) == glm::vec4(0, 1, 0, 0.25f));
  CHECK(colorAt(m, {0, 0, 0}) == glm::vec4(1, 0, 0, 0.5f));
  const Mesh f = mesh(
      "TriangleSet { colorPerVertex FALSE coord Coordinate { point [0 0 0, 1 0 0, 0 1 0, 0 0 0, "
      "0 1 0, -1 0 0] } color Color { color [1 0 0, 0 0 1] } }");
  checkMesh(f);
  CHECK(colorAt(f, {1, 0, 0}) == glm::vec4(1, 0, 0, 1));
  CHECK(colorAt(f, {-1, 0, 0}) == glm::vec4(0, 0, 1, 1));
  Diagnostics d;
  const Mesh few = mesh(
      "IndexedTriangleSet { index [0 1 2] " + kTri + " color ColorRGBA { color [1 0 0 0.5] } }",
      &d);
  CHECK(few.triangleCount() == 1);
  CHECK(colorAt(few, {0, 1, 0}) == glm::vec4(1.0f));  // missing colours are white
  CHECK(d.warningCount() == 1);
}

TEST_CASE("Composed sets: texture coordinates, MultiTextureCoordinate, generator",
          "[x3d][geometry]") {
  const std::string tc = "TextureCoordinate { point [0 0, 0.5 0, 0 0.25] }";
  const Mesh m = mesh("IndexedTriangleSet { index [0 1 2] " + kTri + " texCoord " + tc + " }");
  checkMesh(m);
  REQUIRE(m.texCoords.size() == 3);
  std::set<std::pair<float, float>> t;
  for (const glm::vec2& c : m.texCoords) t.emplace(c.x, c.y);
  CHECK(t == std::set<std::pair<float, float>>{{0, 0}, {0.5f, 0}, {0, 0.25f}});
  const Mesh multi =
      mesh("IndexedTriangleSet { index [0 1 2] " + kTri +
           " texCoord MultiTextureCoordinate { texCoord [" + tc + " TextureCoordinate {}] } }");
  std::set<std::pair<float, float>> tm;
  for (const glm::vec2& c : multi.texCoords) tm.emplace(c.x, c.y);
  CHECK(tm == t);
  const Mesh gen = mesh("IndexedTriangleSet { index [0 1 2] " + kTri +
                        " texCoord TextureCoordinateGenerator { mode \"COORD\" } }");
  checkMesh(gen);
  CHECK(gen.triangleCount() == 1);
  CHECK(gen.texCoords.empty());
}

TEST_CASE("LineSet: vertexCount polylines", "[x3d][geometry]") {
  const Mesh m = mesh(
      "LineSet { vertexCount [3 2] coord Coordinate { point [0 0 0, 1 0 0, 1 1 0, 5 0 0, 6 0 0] "
      "} color ColorRGBA { color [1 0 0 1, 0 1 0 1, 0 0 1 1, 1 1 1 0.5, 1 1 1 0.5] } }");
  checkLines(m, Primitive::lines);
  CHECK(segmentCount(m) == 3);
  REQUIRE(m.colors.size() == m.positions.size());
  CHECK(colorAt(m, {6, 0, 0}).a == 0.5f);
  CHECK(m.bounds.max == glm::vec3(6, 1, 0));
  Diagnostics d;
  const Mesh bad = mesh("LineSet { vertexCount [1 2 5] " + kSquare + " }", &d);
  // 1 is too small (skips point 0); 2 draws 1-2; 5 is cut short to point 3 alone.
  CHECK(segmentCount(bad) == 1);
  CHECK(d.warningCount() == 1);
}

// ---- ColorRGBA in the VRML97 nodes --------------------------------------------------------

TEST_CASE("ColorRGBA in IndexedFaceSet, IndexedLineSet, PointSet and ElevationGrid",
          "[x3d][geometry]") {
  const std::string rgba = "color ColorRGBA { color [1 0 0 0.5, 0 1 0 0.25, 0 0 1 0, 1 1 1 1] }";
  const Mesh ifs = mesh("IndexedFaceSet { coordIndex [0 1 2 3 -1] " + kSquare + " " + rgba + " }");
  checkMesh(ifs);
  REQUIRE(ifs.colors.size() == ifs.positions.size());
  CHECK(colorAt(ifs, {1, 0, 0}) == glm::vec4(0, 1, 0, 0.25f));
  CHECK(colorAt(ifs, {1, 1, 0}) == glm::vec4(0, 0, 1, 0));

  const Mesh ils = mesh("IndexedLineSet { coordIndex [0 1 2 3] colorIndex [3 2 1 0] " + kSquare +
                        " " + rgba + " }");
  checkLines(ils, Primitive::lines);
  CHECK(segmentCount(ils) == 3);
  CHECK(colorAt(ils, {0, 0, 0}) == glm::vec4(1.0f));
  CHECK(colorAt(ils, {0, 1, 0}) == glm::vec4(1, 0, 0, 0.5f));

  const Mesh ps = mesh("PointSet { " + kSquare + " " + rgba + " }");
  checkLines(ps, Primitive::points);
  CHECK(colorAt(ps, {0, 0, 0}).a == 0.5f);

  const Mesh eg = mesh("ElevationGrid { xDimension 2 zDimension 2 height [0 0 0 0] " + rgba + " }");
  checkMesh(eg);
  REQUIRE(eg.colors.size() == eg.positions.size());
  CHECK(colorAt(eg, {1, 0, 0}).a == 0.25f);
  CHECK(colorAt(eg, {0, 0, 1}).a == 0.0f);
}

// ---- solid on the primitives ----------------------------------------------------------------

TEST_CASE("X3D solid on Box, Cone, Cylinder and Sphere", "[x3d][geometry]") {
  for (const char* node : {"Box", "Cone", "Cylinder", "Sphere"}) {
    INFO(node);
    const Mesh def = mesh(std::string(node) + " {}");
    CHECK(def.solid);
    CHECK(def.triangleCount() > 0);
    const Mesh two = mesh(std::string(node) + " { solid FALSE }");
    CHECK_FALSE(two.solid);
    CHECK(two.triangleCount() == def.triangleCount());
  }
}

// ---- Geometry2D ----------------------------------------------------------------------------

TEST_CASE("Rectangle2D: two triangles in Z = 0 facing +Z, Box-face texture", "[x3d][geometry]") {
  const Mesh m = mesh("Rectangle2D { size 4 2 }");
  checkMesh(m);
  CHECK(m.triangleCount() == 2);
  CHECK(area(m) == Approx(8.0));
  CHECK_FALSE(m.solid);
  CHECK(m.bounds.min == glm::vec3(-2, -1, 0));
  CHECK(m.bounds.max == glm::vec3(2, 1, 0));
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    CHECK(m.normals[i] == glm::vec3(0, 0, 1));
    CHECK(m.texCoords[i].x == Approx((m.positions[i].x + 2.0) / 4.0));
    CHECK(m.texCoords[i].y == Approx((m.positions[i].y + 1.0) / 2.0));
  }
  CHECK(mesh("Rectangle2D { solid TRUE }").solid);
  Diagnostics d;
  CHECK(mesh("Rectangle2D { size -1 2 }", &d).positions.empty());
  CHECK(d.warningCount() == 1);
}

TEST_CASE("Circle2D and Arc2D: lines on the circle", "[x3d][geometry]") {
  const Mesh c = mesh("Circle2D { radius 2 }");
  checkLines(c, Primitive::lines);
  CHECK(segmentCount(c) == static_cast<std::size_t>(kRoundSegments));
  CHECK(c.positions.size() == static_cast<std::size_t>(kRoundSegments));
  for (const glm::vec3& p : c.positions) {
    CHECK(glm::length(p) == Approx(2.0));
    CHECK(p.z == 0.0f);
  }
  CHECK(c.bounds.max.x == Approx(2.0));
  CHECK(c.bounds.min.y == Approx(-2.0));

  const Mesh a = mesh("Arc2D {}");  // a quarter circle from +X to +Y
  checkLines(a, Primitive::lines);
  CHECK(segmentCount(a) == static_cast<std::size_t>(kRoundSegments / 4));
  CHECK(a.positions.size() == static_cast<std::size_t>(kRoundSegments / 4 + 1));
  CHECK(a.bounds.min.x == Approx(0.0).margin(1e-6));
  CHECK(a.bounds.min.y == Approx(0.0).margin(1e-6));
  CHECK(a.bounds.max.x == Approx(1.0));
  // endAngle < startAngle: counter-clockwise the long way round (three quarters).
  const Mesh longWay = mesh("Arc2D { startAngle 1.5707963 endAngle 0 }");
  CHECK(segmentCount(longWay) == static_cast<std::size_t>(3 * kRoundSegments / 4));
  const Mesh full = mesh("Arc2D { startAngle 1 endAngle 1 }");  // equal angles: a circle
  CHECK(segmentCount(full) == static_cast<std::size_t>(kRoundSegments));
}

TEST_CASE("Disk2D: filled disc, annulus, and circle when the radii are equal", "[x3d][geometry]") {
  const double polygon = 0.5 * kRoundSegments * std::sin(2.0 * std::numbers::pi / kRoundSegments);
  const Mesh d = mesh("Disk2D { outerRadius 2 }");
  checkMesh(d);
  CHECK(d.triangleCount() == static_cast<std::size_t>(kRoundSegments));
  CHECK(area(d) == Approx(4.0 * polygon));
  allFacing(d, 1.0);
  CHECK_FALSE(d.solid);
  for (std::size_t i = 0; i < d.positions.size(); ++i) {
    CHECK(d.texCoords[i].x == Approx((d.positions[i].x + 2.0) / 4.0).margin(1e-6));
    CHECK(d.texCoords[i].y == Approx((d.positions[i].y + 2.0) / 4.0).margin(1e-6));
  }
  const Mesh ring = mesh("Disk2D { innerRadius 1 outerRadius 2 }");
  checkMesh(ring);
  CHECK(ring.triangleCount() == static_cast<std::size_t>(2 * kRoundSegments));
  CHECK(area(ring) == Approx(3.0 * polygon));
  allFacing(ring, 1.0);
  const Mesh circle = mesh("Disk2D { innerRadius 1 outerRadius 1 }");
  checkLines(circle, Primitive::lines);
  CHECK(segmentCount(circle) == static_cast<std::size_t>(kRoundSegments));
  Diagnostics diag;
  CHECK(mesh("Disk2D { innerRadius 3 outerRadius 1 }", &diag).positions.empty());
  CHECK(diag.warningCount() == 1);
}

TEST_CASE("ArcClose2D: PIE and CHORD", "[x3d][geometry]") {
  const Mesh pie = mesh("ArcClose2D { }");  // quarter pie
  checkMesh(pie);
  CHECK(pie.triangleCount() == static_cast<std::size_t>(kRoundSegments / 4));
  allFacing(pie, 1.0);
  CHECK(pie.bounds.min == glm::vec3(0.0f));
  const Mesh chord = mesh("ArcClose2D { closureType \"CHORD\" endAngle 3.14159265 }");
  checkMesh(chord);
  CHECK(chord.triangleCount() == static_cast<std::size_t>(kRoundSegments / 2 - 1));
  allFacing(chord, 1.0);
  for (const glm::vec2& t : chord.texCoords) {
    CHECK(t.x >= 0.0f);
    CHECK(t.x <= 1.0f);
    CHECK(t.y >= 0.0f);
    CHECK(t.y <= 1.0f);
  }
  Diagnostics d;
  const Mesh odd = mesh("ArcClose2D { closureType \"ROUND\" }", &d);
  CHECK(odd.triangleCount() == pie.triangleCount());
  CHECK(d.warningCount() == 1);
}

TEST_CASE("Polyline2D, Polypoint2D and TriangleSet2D", "[x3d][geometry]") {
  const Mesh pl = mesh("Polyline2D { lineSegments [0 0, 1 0, 1 1, 0 1] }");
  checkLines(pl, Primitive::lines);
  CHECK(segmentCount(pl) == 3);
  CHECK(pl.bounds.max == glm::vec3(1, 1, 0));
  const Mesh pp = mesh("Polypoint2D { point [0 0, 1 0, 3 2] }");
  checkLines(pp, Primitive::points);
  CHECK(pp.indices.size() == 3);
  CHECK(pp.bounds.max == glm::vec3(3, 2, 0));
  // The second triangle is clockwise: turned round so that it faces +Z like the first.
  Diagnostics d;  // the 7th point is left over: ignored silently (clause 14.4)
  const Mesh ts = mesh("TriangleSet2D { vertices [0 0, 2 0, 0 1, 0 0, 2 0, 0 -1, 9 9] }", &d);
  CHECK(d.items.empty());
  checkMesh(ts);
  CHECK(ts.triangleCount() == 2);
  allFacing(ts, 1.0);
  CHECK(area(ts) == Approx(2.0));
  for (const glm::vec3& n : ts.normals) CHECK(n == glm::vec3(0, 0, 1));
  CHECK(ts.bounds.min == glm::vec3(0, -1, 0));
  CHECK(ts.bounds.max == glm::vec3(2, 1, 0));  // (9, 9) is not drawn
  for (std::size_t i = 0; i < ts.positions.size(); ++i) {
    CHECK(ts.texCoords[i].x == Approx(ts.positions[i].x / 2.0));
    CHECK(ts.texCoords[i].y == Approx((ts.positions[i].y + 1.0) / 2.0));
  }
}

// ---- the castle corpus (optional) -----------------------------------------------------------

TEST_CASE("X3D corpus worlds with X3D geometry tessellate without warnings", "[x3d][geometry]") {
  if (!haveCorpus("x3d/castle/x3d")) return;
  const std::filesystem::path dir = corpusDir() / "x3d/castle/x3d";
  std::size_t shapes = 0, triangles = 0, segments = 0, points = 0;
  for (const char* name : {"triangle_quad_sets.x3dv", "quad_colors.x3dv", "line_set.x3dv",
                           "points_colorrgba.x3dv", "elevation_grid_color_rgba.x3dv"}) {
    INFO(name);
    const Scene scene = parseVrml(readBytes(dir / name), name);
    std::set<const Node*> seen;
    std::function<void(const NodePtr&)> visit = [&](const NodePtr& n) {
      if (n == nullptr || !seen.insert(n.get()).second) return;
      if (n->typeName() == "Shape") {
        if (const NodePtr g = n->sfnode("geometry")) {
          Diagnostics d;
          const Mesh m = tessellate(*g, &d);
          INFO(g->typeName());
          // The QuadSets of triangle_quad_sets.x3dv have 10 points, the last 2 of which
          // make no quad: ignored as clause 32.4 says, with no diagnostic.
          std::string messages;
          for (const Diagnostic& x : d.items) messages += x.format() + "\n";
          INFO(messages);
          CHECK(messages.empty());
          ++shapes;
          triangles += m.triangleCount();
          segments += segmentCount(m);
          if (m.primitive == Primitive::points) points += m.indices.size();
        }
      }
      for (std::size_t i = 0; i < n->fieldCount(); ++i) {
        const FieldValue& f = n->fieldAt(i);
        if (f.type() == FieldType::SFNode) visit(f.get<FieldType::SFNode>());
        if (f.type() == FieldType::MFNode)
          for (const NodePtr& c : f.get<FieldType::MFNode>()) visit(c);
      }
    };
    for (const NodePtr& n : scene.rootNodes) visit(n);
  }
  CHECK(shapes >= 5);
  CHECK(triangles > 0);
  CHECK(segments > 0);
  CHECK(points > 0);
}
