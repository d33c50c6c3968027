// Tessellation of VRML97's Extrusion (clause 6.18; geometry/src/geometry_grid.cpp).
#include "geometry_checks.hpp"

using namespace gs::vrml;
using namespace gs::vrml::geometry_tests;

// ---- Extrusion --------------------------------------------------------------------------

TEST_CASE("Extrusion: the default is a closed box with outward normals", "[geometry]") {
  const Mesh m = mesh("Extrusion { }");
  checkMesh(m);
  CHECK(m.triangleCount() == 12);
  CHECK(area(m) == Approx(4 * 2.0 + 2 * 4.0));
  CHECK(closedSurface(m));
  checkOutward(m, glm::dvec3(0, 0.5, 0));
  CHECK(m.bounds.min == glm::vec3(-1, 0, -1));
  CHECK(m.bounds.max == glm::vec3(1, 1, 1));
  // Texture: s along the crossSection, t along the spine; caps from the crossSection box.
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const glm::vec3 p = m.positions[i];
    if (std::abs(m.normals[i].y) > 0.5f)
      CHECK(m.texCoords[i] == glm::vec2((p.x + 1) / 2, (p.z + 1) / 2));
    else
      CHECK(m.texCoords[i].y == p.y);
  }
  const Mesh flipped = mesh("Extrusion { ccw FALSE }");
  checkMesh(flipped);
  for (std::size_t t = 0; t < flipped.triangleCount(); ++t) {
    glm::dvec3 c(0.0);
    for (int k = 0; k < 3; ++k) c += P(flipped, flipped.indices[3 * t + k]) / 3.0;
    CHECK(glm::dot(triangleNormal(flipped, t), c - glm::dvec3(0, 0.5, 0)) < 0.0);
  }
  CHECK(mesh("Extrusion { beginCap FALSE endCap FALSE }").triangleCount() == 8);
}

TEST_CASE("Extrusion: the caps are never smoothed with the sides", "[geometry]") {
  // creaseAngle 3 smooths the box's sides across their corners; the caps keep their flat
  // normals (X_ITE refines the body's normals only: create3000's Extrusion/gears42P.x3d).
  const Mesh m = mesh("Extrusion { creaseAngle 3 }");
  checkMesh(m);
  std::size_t capCorners = 0, sideCorners = 0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::dvec3 n = glm::normalize(triangleNormal(m, t));
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 v = m.normals[m.indices[3 * t + k]];
      if (std::abs(n.y) > 0.99) {  // a cap triangle: its corners' normals are its own
        ++capCorners;
        CHECK(std::abs(v.y) == Approx(1.0f));
      } else {  // a side: smoothed across the corners, never towards the caps
        ++sideCorners;
        CHECK(v.y == Approx(0.0f).margin(1e-6));
        CHECK(std::abs(v.x) == Approx(std::sqrt(0.5f)).margin(1e-5));
      }
    }
  }
  CHECK(capCorners == 4 * 3);
  CHECK(sideCorners == 8 * 3);
}

TEST_CASE("Extrusion: bent spine, scale, orientation, non-convex caps", "[geometry]") {
  // An L-shaped crossSection (counterclockwise seen from +Y), swept along a bent spine.
  const Mesh m = mesh(
      "Extrusion { crossSection [0 0, 0 2, 1 2, 1 1, 2 1, 2 0, 0 0] "
      "spine [0 0 0, 0 2 0, 2 4 0, 2 6 0] convex FALSE }");
  checkMesh(m);
  CHECK(closedSurface(m));
  // The two caps are 3 square units each.
  double capArea = 0.0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::dvec3 n = triangleNormal(m, t);
    const double y = P(m, m.indices[3 * t]).y;
    if (std::abs(std::abs(n.y) - glm::length(n)) < 1e-6 && (y == 0.0 || y == 6.0))
      capArea += glm::length(n);
  }
  CHECK(capArea == Approx(6.0));

  // Scale to a point (a pyramid) and a quarter turn of orientation.
  const Mesh pyramid =
      mesh("Extrusion { scale [1 1, 0 0] orientation [0 1 0 0, 0 1 0 1.5707964] }");
  checkMesh(pyramid);
  CHECK(pyramid.triangleCount() == 4 + 2);  // side quads collapse to triangles, no end cap
  CHECK(closedSurface(pyramid));
  checkOutward(pyramid, glm::dvec3(0, 0.25, 0));
}

TEST_CASE("Extrusion: closed spine and crossSection make a torus", "[geometry]") {
  std::vector<glm::vec3> spine;
  std::vector<glm::vec2> circle;
  for (int k = 0; k <= 16; ++k) {
    const double a = 2 * kPi * k / 16;
    spine.emplace_back(static_cast<float>(3 * std::cos(a)), 0.0f,
                       static_cast<float>(-3 * std::sin(a)));
    circle.emplace_back(static_cast<float>(std::cos(-a)), static_cast<float>(std::sin(-a)));
  }
  spine.back() = spine.front();
  circle.back() = circle.front();
  for (const char* crease : {"0", "1"}) {
    const Mesh m = mesh("Extrusion { spine " + list(spine) + " crossSection " + list(circle) +
                        " beginCap FALSE endCap FALSE creaseAngle " + crease + " }");
    checkMesh(m);
    CHECK(m.triangleCount() == 2 * 16 * 16);
    CHECK(closedSurface(m));
    CHECK(area(m) == Approx(4 * kPi * kPi * 3 * 1).epsilon(0.05));
    if (crease[0] == '1') {
      // Smooth: each normal points away from the tube's centre line.
      for (std::size_t i = 0; i < m.positions.size(); ++i) {
        const glm::vec3 p = m.positions[i];
        const glm::vec3 axis = glm::normalize(glm::vec3(p.x, 0, p.z)) * 3.0f;
        CHECK(glm::dot(m.normals[i], glm::normalize(p - axis)) > 0.98f);
      }
    }
  }
}

TEST_CASE("Extrusion: collinear spines, coincident points, bad data", "[geometry]") {
  // A spine along -Y, along X, diagonal, each with a repeated point: still boxes, outward.
  for (glm::vec3 end : {glm::vec3(0, -1, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 1)}) {
    const Mesh m =
        mesh("Extrusion { spine " +
             list(std::vector<glm::vec3>{{0, 0, 0}, end * 0.5f, end * 0.5f, end}) + " }");
    checkMesh(m);
    CHECK(closedSurface(m));
    CHECK(area(m) == Approx(4 * 2 * glm::length(end) + 2 * 4.0));
    checkOutward(m, glm::dvec3(end * 0.5f));
  }
  Diagnostics d;
  const NodePtr nan = parseGeometry("Extrusion { }");
  set<FieldType::MFVec3f>(nan, "spine", std::vector<glm::vec3>{{0, 0, 0}, {0, NAN, 0}});
  CHECK(tessellate(*nan, &d).positions.empty());
  CHECK(mesh("Extrusion { spine [0 0 0] }", &d).positions.empty());
  const Mesh fewScales = mesh("Extrusion { spine [0 0 0, 0 1 0, 0 2 0] scale [1 1, 2 2] }", &d);
  CHECK(fewScales.triangleCount() == 4 * 2 * 2 + 4);
  CHECK(d.warningCount() == 2);
}
