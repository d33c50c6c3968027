// X3D NURBS geometry (X3D 4.0 clause 27; vrml/src/geometry_nurbs.cpp): curves and patches
// evaluated as rational B-splines, their knots, weights and tessellation counts.
#include <catch2/catch.hpp>

#include "vrml/geometry.hpp"
#include "vrml/parser.hpp"

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
  Diagnostics diag;
  const Mesh m = nurbsMesh(
      "NurbsCurve { order 3 tessellation 16 weight [ 1 0.70710678 1 ] "
      "controlPoint Coordinate { point [ 1 0 0, 1 1 0, 0 1 0 ] } }",
      diag);
  CHECK(diag.items.empty());
  REQUIRE(m.positions.size() == 17);
  for (const glm::vec3& p : m.positions) CHECK(glm::length(p) == Approx(1.0f).epsilon(1e-5));
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
