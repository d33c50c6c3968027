// X3D NURBS geometry (X3D 4.0 clause 27; geometry/src/geometry_nurbs.cpp): curves and patches
// evaluated as rational B-splines, their knots, weights and tessellation counts.
#include <catch2/catch.hpp>

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"
#include "test_support.hpp"

#include <functional>
#include <set>

#include <string>

using namespace gs::vrml;

namespace {

/// The mesh of the only Shape's geometry in an X3D world made of `geometry`, with the
/// diagnostics of parsing and tessellating.
Mesh nurbsMesh(const std::string& geometry, Diagnostics& diag) {
  const Scene scene = parseVrml(
      "#X3D V4.0 utf8\nPROFILE Full\nShape { geometry " + geometry + " }\n", "nurbs.x3dv");
  diag.items = scene.diagnostics.items;
  REQUIRE(scene.rootNodes.size() == 1);
  const NodePtr& g = scene.rootNodes[0]->sfnode("geometry");
  REQUIRE(g != nullptr);
  return tessellate(*g, &diag);
}

}  // namespace

TEST_CASE("NurbsCurve of order 2 is the polyline of its control points", "[vrml][nurbs]") {
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsCurve { order 2 tessellation 4 controlPoint Coordinate { "
      "point [ 0 0 0, 1 0 0, 1 1 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  CHECK(m.primitive == Primitive::lines);
  REQUIRE(m.positions.size() == 5);  // 4 segments
  CHECK(m.indices.size() == 8);
  CHECK(m.positions[0].x == Approx(0.0f));
  CHECK(m.positions[2].x == Approx(1.0f));  // the middle control point, at u = 1 of 2
  CHECK(m.positions[2].y == Approx(0.0f).margin(1e-6));
  CHECK(m.positions[4].y == Approx(1.0f));
}

TEST_CASE("NurbsCurve: a rational quadratic with weight cos 45 degrees is a circle's quarter",
          "[vrml][nurbs]") {
  // Control points are homogeneous: the corner (1, 1, 0) of weight cos 45 degrees is written
  // (0.70710678, 0.70710678, 0), as castle's and X_ITE's test worlds write it.
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsCurve { order 3 tessellation 16 weight [ 1 0.70710678 1 ] "
      "controlPoint Coordinate { point [ 1 0 0, 0.70710678 0.70710678 0, 0 1 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(m.positions.size() == 17);
  for (const glm::vec3& p : m.positions) CHECK(glm::length(p) == Approx(1.0f).epsilon(1e-5));
}

TEST_CASE("NurbsCurve: control points are homogeneous coordinates, divided by their weight",
          "[vrml][nurbs]") {
  // castle's nurbs_weights.x3dv: a point of weight 1/4 written as a quarter of itself
  // draws the curve that the point itself draws with weight 1 ... and the same point
  // written whole is pulled four times further out. Quadratic, u = 0.5: the Bernstein
  // values 0.25 0.5 0.25; (0.25 x 0 + 0.5 x (0, 2) + 0.25 x (2, 0)) / (0.25 + 0.5 w + 0.25).
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsCurve { order 3 tessellation 2 weight [ 1 0.25 1 ] "
      "controlPoint Coordinate { point [ 0 0 0, 0 2 0, 2 0 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(m.positions.size() == 3);
  CHECK(m.positions[1].x == Approx(0.5f / 0.625f));
  CHECK(m.positions[1].y == Approx(1.0f / 0.625f));
}

TEST_CASE("NurbsPatchSurface: a pole's points take the surface's normal there, not a star",
          "[vrml][nurbs]") {
  // A cone: its first row of control points is the apex (0, 1, 0), its second a square
  // ring around the y axis. Along u the apex row has no tangent; its normals are the mean
  // of the next row's, the cone's axis.
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsPatchSurface { uDimension 5 vDimension 2 uOrder 2 vOrder 2 uTessellation 8 "
      "vTessellation 2 solid FALSE controlPoint Coordinate { point [ "
      "0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 1 0 0, 0 0 -1, -1 0 0, 0 0 1, 1 0 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(m.positions.size() == 27);  // 9 x 3
  for (std::size_t i = 0; i < 9; ++i) {
    INFO("apex point " << i);
    CHECK(std::abs(m.normals[i].y) == Approx(1.0f).margin(1e-5));
    CHECK(m.normals[i] == m.normals[0]);
  }
  // The ring's own normals lean out from the axis.
  CHECK(std::abs(m.normals[18].y) < 0.9f);

  // The apex twice: the grid's first three rows (v = 0, 0.25, 0.5) collapse; each takes the
  // normals of the nearest row that does not.
  const Mesh twice = nurbsMesh(
      "NurbsPatchSurface { uDimension 5 vDimension 3 uOrder 2 vOrder 2 uTessellation 8 "
      "vTessellation 4 solid FALSE controlPoint Coordinate { point [ "
      "0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, 0 1 0, "
      "1 0 0, 0 0 -1, -1 0 0, 0 0 1, 1 0 0 ] } }",
      diag);
  REQUIRE(twice.positions.size() == 45);  // 9 x 5
  for (std::size_t i = 0; i < 27; ++i) {
    INFO("apex point " << i);
    CHECK(std::abs(twice.normals[i].y) == Approx(1.0f).margin(1e-5));
  }
}

TEST_CASE("NurbsPatchSurface: a bilinear patch, its grid, normals and parameters",
          "[vrml][nurbs]") {
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsPatchSurface { uDimension 2 vDimension 2 uOrder 2 vOrder 2 uTessellation 4 "
      "vTessellation 2 controlPoint Coordinate { point [ 0 0 0, 2 0 0, 0 1 0, 2 1 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  CHECK(m.primitive == Primitive::triangles);
  CHECK(m.positions.size() == 15);  // 5 x 3
  CHECK(m.triangleCount() == 16);
  CHECK(m.bounds.max.x == Approx(2.0f));
  CHECK(m.bounds.max.y == Approx(1.0f));
  for (const glm::vec3& n : m.normals) CHECK(n.z == Approx(1.0f));  // u x v = +Z
  CHECK(m.texCoords.back().x == Approx(1.0f));
  CHECK(m.solid);
}

TEST_CASE("NURBS: wrong knots and weights are one warning and uniform values", "[vrml][nurbs]") {
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsCurve { order 2 tessellation 2 knot [ 0 1 ] weight [ 1 -1 ] "
      "controlPoint Coordinate { point [ 0 0 0, 4 0 0 ] } }",
      diag);
  REQUIRE(diag.items.size() == 1);
  CHECK(diag.items[0].message.find("knot") != std::string::npos);
  REQUIRE(m.positions.size() == 3);
  CHECK(m.positions[1].x == Approx(2.0f));
  // A patch with fewer control points than its dimensions ask for draws nothing.
  Diagnostics few;
  const Mesh none = nurbsMesh(
      "NurbsPatchSurface { uDimension 3 vDimension 3 controlPoint "
      "Coordinate { point [ 0 0 0, 1 0 0 ] } }",
      few);
  CHECK(none.positions.empty());
  CHECK(!few.items.empty());
}

// ---- NurbsTextureCoordinate (27.4.10) -------------------------------------------------------

namespace {

/// A 2 x 2 bilinear patch over [0, 2] x [0, 1] with tessellation su x sv and `texCoord`.
std::string nurbsTexPatch(const std::string& texCoord, int su = 2, int sv = 2) {
  return "NurbsPatchSurface { uDimension 2 vDimension 2 uOrder 2 vOrder 2 uTessellation " +
         std::to_string(su) + " vTessellation " + std::to_string(sv) +
         " controlPoint Coordinate { point [ 0 0 0, 2 0 0, 0 1 0, 2 1 0 ] } texCoord " + texCoord +
         " }";
}

}  // namespace

TEST_CASE("NurbsTextureCoordinate: a bilinear texture surface maps the grid linearly",
          "[vrml][nurbs]") {
  Diagnostics diag;
  // (s, t) = (2 u, 4 v) at the 3 x 3 grid's fractions (u, v), u fastest.
  const Mesh m = nurbsMesh(nurbsTexPatch("NurbsTextureCoordinate { uDimension 2 vDimension 2 "
                                         "uOrder 2 vOrder 2 controlPoint [ 0 0, 2 0, 0 4, 2 4 ] }"),
                           diag);
  CHECK(diag.items.empty());
  REQUIRE(m.texCoords.size() == 9);
  CHECK(m.texCoords[0] == glm::vec2(0.0f, 0.0f));
  CHECK(m.texCoords[1].x == Approx(1.0f));
  CHECK(m.texCoords[4].x == Approx(1.0f));
  CHECK(m.texCoords[4].y == Approx(2.0f));
  CHECK(m.texCoords[8].x == Approx(2.0f));
  CHECK(m.texCoords[8].y == Approx(4.0f));
  // Its own knots (range [0, 5]) change nothing: the same fraction of its range is taken.
  Diagnostics knotted;
  const Mesh k = nurbsMesh(
      nurbsTexPatch("NurbsTextureCoordinate { uDimension 2 vDimension 2 uOrder 2 vOrder 2 "
                    "uKnot [ 0 0 5 5 ] controlPoint [ 0 0, 2 0, 0 4, 2 4 ] }"),
      knotted);
  CHECK(knotted.items.empty());
  REQUIRE(k.texCoords.size() == 9);
  CHECK(k.texCoords[4].x == Approx(1.0f));
}

TEST_CASE("NurbsTextureCoordinate: a rational quadratic texture direction", "[vrml][nurbs]") {
  Diagnostics diag;
  // u: order 3 over s = 0, 1, 2 with weights 1 2 1 (v: order 2, t = 0 and 1). At u = 0.25
  // the Bernstein values are 0.5625, 0.375, 0.0625; weighted 0.5625, 0.75, 0.0625 (sum
  // 1.375): s = (0.75 x 1 + 0.0625 x 2) / 1.375 = 7 / 11. At 0.5 the symmetry gives s = 1.
  const Mesh m = nurbsMesh(nurbsTexPatch("NurbsTextureCoordinate { uDimension 3 vDimension 2 "
                                         "uOrder 3 vOrder 2 weight [ 1 2 1, 1 2 1 ] "
                                         "controlPoint [ 0 0, 1 0, 2 0, 0 1, 1 1, 2 1 ] }",
                                         4, 1),
                           diag);
  CHECK(diag.items.empty());
  REQUIRE(m.texCoords.size() == 10);  // 5 x 2
  CHECK(m.texCoords[1].x == Approx(7.0f / 11.0f));
  CHECK(m.texCoords[2].x == Approx(1.0f));
  CHECK(m.texCoords[4].x == Approx(2.0f));
  CHECK(m.texCoords[6].y == Approx(1.0f));
}

TEST_CASE("NurbsTextureCoordinate: bad fields are one warning and the (u, v) mapping",
          "[vrml][nurbs]") {
  for (const char* tc : {
           "NurbsTextureCoordinate { uDimension 2 vDimension 2 uOrder 2 vOrder 2 "
           "controlPoint [ 0 0, 2 0, 0 4 ] }",
           "NurbsTextureCoordinate { uDimension 2 vDimension 2 uOrder 2 vOrder 2 "
           "uKnot [ 0 1 0 1 ] controlPoint [ 0 0, 2 0, 0 4, 2 4 ] }",
           "NurbsTextureCoordinate { uDimension 2 vDimension 2 uOrder 2 vOrder 2 "
           "weight [ 1 0 1 1 ] controlPoint [ 0 0, 2 0, 0 4, 2 4 ] }",
           "NurbsTextureCoordinate { uDimension 2 vDimension 2 uOrder 1 vOrder 2 "
           "controlPoint [ 0 0, 2 0, 0 4, 2 4 ] }",
       }) {
    INFO(tc);
    Diagnostics diag;
    const Mesh m = nurbsMesh(nurbsTexPatch(tc), diag);
    REQUIRE(diag.items.size() == 1);
    CHECK(diag.items[0].message.find("NurbsTextureCoordinate") != std::string::npos);
    REQUIRE(m.texCoords.size() == 9);
    CHECK(m.texCoords[4] == glm::vec2(0.5f, 0.5f));
    CHECK(m.texCoords[8] == glm::vec2(1.0f, 1.0f));
  }
}

// ---- the castle corpus (optional) -----------------------------------------------------------

TEST_CASE("NURBS corpus worlds load and tessellate with no diagnostic", "[vrml][nurbs][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/nurbs")) return;
  const auto dir = gs::test::corpusDir() / "x3d/castle/nurbs";
  for (const char* name : {"nurbs_dune_primitives.x3dv", "nurbs_weights.x3dv"}) {
    INFO(name);
    const Scene scene = parseVrml(gs::test::readBytes(dir / name), name);
    std::string messages;
    for (const Diagnostic& d : scene.diagnostics.items) messages += d.format() + "\n";
    std::size_t shapes = 0;
    std::set<const Node*> seen;
    std::function<void(const NodePtr&)> visit = [&](const NodePtr& n) {
      if (n == nullptr || !seen.insert(n.get()).second) return;
      if (n->typeName() == "Shape")
        if (const NodePtr g = n->sfnode("geometry")) {
          Diagnostics d;
          const Mesh m = tessellate(*g, &d);
          for (const Diagnostic& x : d.items) messages += x.format() + "\n";
          if (!m.positions.empty()) ++shapes;
        }
      for (std::size_t i = 0; i < n->fieldCount(); ++i) {
        const FieldValue& f = n->fieldAt(i);
        if (f.type() == FieldType::SFNode) visit(f.get<FieldType::SFNode>());
        if (f.type() == FieldType::MFNode)
          for (const NodePtr& c : f.get<FieldType::MFNode>()) visit(c);
      }
    };
    for (const NodePtr& r : scene.rootNodes) visit(r);
    INFO(messages);
    CHECK(messages.empty());
    CHECK(shapes >= 3);
  }
}

TEST_CASE("NurbsCurve closed: periodic, smooth through the seam (as X_ITE makes it)",
          "[vrml][nurbs]") {
  Diagnostics diag;
  // A closed quadratic over the square's corners: it passes the edges' midpoints, not the
  // corners, and its ends meet.
  const Mesh m = nurbsMesh(
      "NurbsCurve { closed TRUE tessellation 40 controlPoint Coordinate { "
      "point [ 1 1 0, -1 1 0, -1 -1 0, 1 -1 0, 1 1 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(m.positions.size() == 41);
  CHECK(glm::length(m.positions.front() - m.positions.back()) < 1e-5f);
  for (const glm::vec3& p : m.positions) {
    CHECK(std::max(std::abs(p.x), std::abs(p.y)) <= 1.0f + 1e-5f);
    CHECK(glm::length(glm::vec2(p)) > 0.7f);                    // no corner cut to the centre
    CHECK(glm::length(glm::vec2(p) - glm::vec2(1, 1)) > 0.3f);  // the corner is cut
  }
  // Not closed: the same points give a curve from corner to corner.
  const Mesh open = nurbsMesh(
      "NurbsCurve { tessellation 40 controlPoint Coordinate { "
      "point [ 1 1 0, -1 1 0, -1 -1 0, 1 -1 0, 1 1 0 ] } }",
      diag);
  CHECK(open.positions.front() == glm::vec3(1, 1, 0));
}

TEST_CASE("NurbsPatchSurface uClosed: periodic around, as X_ITE makes it", "[vrml][nurbs]") {
  // A quadratic tube in u over the square's corners (first and last columns the same) at
  // z = 0 and 1: closed, its rings cut the corners and pass the edges' midpoints, as the
  // closed NurbsCurve does (create3000's NURBS/DefaultTextureCoordClosed.x3dv).
  const std::string points =
      "point [ 1 1 0, -1 1 0, -1 -1 0, 1 -1 0, 1 1 0,  1 1 1, -1 1 1, -1 -1 1, 1 -1 1, 1 1 1 ]";
  const auto tube = [&](const char* closed) {
    Diagnostics diag;
    const Mesh m = nurbsMesh(std::string("NurbsPatchSurface { ") + closed +
                                 " uDimension 5 vDimension 2 vOrder 2 uTessellation 40 "
                                 "vTessellation 1 controlPoint Coordinate { " +
                                 points + " } }",
                             diag);
    CHECK(diag.items.empty());
    return m;
  };
  const Mesh closed = tube("uClosed TRUE");
  REQUIRE(!closed.positions.empty());
  float nearest = 10.0f;
  for (const glm::vec3& p : closed.positions) {
    CHECK(std::max(std::abs(p.x), std::abs(p.y)) <= 1.0f + 1e-5f);
    CHECK(glm::length(glm::vec2(p)) > 0.7f);
    nearest = std::min(nearest, glm::length(glm::vec2(p) - glm::vec2(1, 1)));
  }
  CHECK(nearest > 0.3f);  // the corner is cut
  // Not closed: the surface starts at the corner.
  const Mesh open = tube("uClosed FALSE");
  float corner = 10.0f;
  for (const glm::vec3& p : open.positions)
    corner = std::min(corner, glm::length(glm::vec2(p) - glm::vec2(1, 1)));
  CHECK(corner < 1e-5f);
}

TEST_CASE("NurbsSweptSurface and NurbsSwungSurface: extrusions of their curves", "[vrml][nurbs]") {
  Diagnostics diag;
  // A 2 x 2 square (order 2: its polyline) swept along a straight 3D curve from y 0 to 4.
  const Mesh swept = nurbsMesh(
      "NurbsSweptSurface { solid FALSE"
      " crossSectionCurve NurbsCurve2D { order 2 controlPoint [ 1 1, 1 -1, -1 -1, -1 1, 1 1 ] }"
      " trajectoryCurve NurbsCurve { order 2 tessellation 2"
      "   controlPoint Coordinate { point [ 0 0 0, 0 4 0 ] } } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(swept.triangleCount() > 0);
  CHECK(swept.bounds.min.x == Approx(-1.0f));
  CHECK(swept.bounds.max.z == Approx(1.0f));
  CHECK(swept.bounds.min.y == Approx(0.0f));
  CHECK(swept.bounds.max.y == Approx(4.0f));
  CHECK_FALSE(swept.solid);
  // A profile (x, y) swung along a trajectory laid in XZ: a ring between radii 1 and 3.
  const Mesh swung = nurbsMesh(
      "NurbsSwungSurface {"
      " profileCurve ContourPolyline2D { controlPoint [ 1 -1, 1 1, -1 1, -1 -1, 1 -1 ] }"
      " trajectoryCurve NurbsCurve2D { closed TRUE tessellation 64"
      "   controlPoint [ 2 2, -2 2, -2 -2, 2 -2, 2 2 ] } }",
      diag);
  REQUIRE(swung.triangleCount() > 0);
  CHECK(swung.bounds.max.y == Approx(1.0f).margin(0.05));
  CHECK(swung.bounds.min.y == Approx(-1.0f).margin(0.05));
  CHECK(swung.bounds.max.x > 2.0f);
  CHECK(swung.bounds.max.x < 3.01f);
  // Without a trajectory: nothing.
  CHECK(nurbsMesh("NurbsSweptSurface { }", diag).triangleCount() == 0);
}

TEST_CASE("NurbsTrimmedSurface: kept inside an odd number of contours (as X_ITE trims)",
          "[vrml][nurbs]") {
  // A flat bilinear patch over [0, 1]^2 cut into 20 x 20 cells: an outer square contour
  // (0.2 .. 0.8, two polylines joined) and a hole (0.4 .. 0.6, a NurbsCurve2D of order 2).
  const std::string patch =
      "uDimension 2 vDimension 2 uOrder 2 vOrder 2 uTessellation 20 vTessellation 20 "
      "controlPoint Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] } ";
  Diagnostics diag;
  const Mesh whole = nurbsMesh("NurbsTrimmedSurface { " + patch + "}", diag);
  CHECK(whole.triangleCount() == 800);
  const Mesh m = nurbsMesh(
      "NurbsTrimmedSurface { " + patch +
          "trimmingContour [ Contour2D { children [ "
          "ContourPolyline2D { controlPoint [ 0.2 0.2, 0.8 0.2, 0.8 0.8 ] } "
          "ContourPolyline2D { controlPoint [ 0.8 0.8, 0.2 0.8, 0.2 0.2 ] } ] } "
          "Contour2D { children NurbsCurve2D { order 2 tessellation 8 controlPoint [ 0.4 0.4, "
          "0.6 0.4, 0.6 0.6, 0.4 0.6, 0.4 0.4 ] } } ] }",
      diag);
  CHECK(diag.items.empty());
  // 12 x 12 cells kept, less the 4 x 4 of the hole: 128 cells, 256 triangles.
  CHECK(m.triangleCount() == 256);
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    glm::vec3 c(0.0f);
    for (int k = 0; k < 3; ++k) c += m.positions[m.indices[3 * t + static_cast<std::size_t>(k)]];
    c /= 3.0f;
    CHECK((c.x > 0.2f && c.x < 0.8f && c.y > 0.2f && c.y < 0.8f));
    CHECK_FALSE((c.x > 0.4f && c.x < 0.6f && c.y > 0.4f && c.y < 0.6f));
  }
}
