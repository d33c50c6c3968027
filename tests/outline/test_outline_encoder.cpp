// The outline-group encoder (paper section 1.1): grouping, outlines, area order.
#include "outline/outline_encoder.hpp"
#include "qnv/error.hpp"

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <numbers>

using gs::outline::encodeOutlineGroups;
using gs::outline::OutlineOptions;
using gs::outline::OutlineSummary;
using gs::outline::PolygonGroup;
using gs::outline::PolygonSoup;

namespace {

void addQuad(PolygonSoup& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d,
             std::uint32_t material = 0) {
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  s.positions.insert(s.positions.end(), {a, b, c, d});
  s.indices.insert(s.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
  s.material.insert(s.material.end(), {material, material});
}

PolygonSoup unitCube() {
  PolygonSoup s;
  const glm::vec3 p[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  addQuad(s, p[0], p[3], p[2], p[1]);  // -z
  addQuad(s, p[4], p[5], p[6], p[7]);  // +z
  addQuad(s, p[0], p[1], p[5], p[4]);  // -y
  addQuad(s, p[3], p[7], p[6], p[2]);  // +y
  addQuad(s, p[0], p[4], p[7], p[3]);  // -x
  addQuad(s, p[1], p[2], p[6], p[5]);  // +x
  return s;
}

PolygonSoup uvSphere(int slices, int stacks) {
  PolygonSoup s;
  auto at = [&](int i, int j) {
    const double th = std::numbers::pi * j / stacks, ph = 2 * std::numbers::pi * i / slices;
    if (j == 0 || j == stacks) return glm::vec3(0.0f, j == 0 ? 1.0f : -1.0f, 0.0f);  // poles
    return glm::vec3(static_cast<float>(std::sin(th) * std::cos(ph)),
                     static_cast<float>(std::cos(th)),
                     static_cast<float>(std::sin(th) * std::sin(ph)));
  };
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i <= slices; ++i) s.positions.push_back(at(i % slices, j));
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (slices + 1) + i); };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      s.indices.insert(s.indices.end(), {id(i, j), id(i + 1, j + 1), id(i + 1, j)});
      s.indices.insert(s.indices.end(), {id(i, j), id(i, j + 1), id(i + 1, j + 1)});
    }
  return s;
}

}  // namespace

TEST_CASE("a flat square of two triangles is one group with one 4-point loop", "[qnv][outline]") {
  PolygonSoup s;
  addQuad(s, {0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0});
  const auto groups = encodeOutlineGroups(s);
  REQUIRE(groups.size() == 1);
  const PolygonGroup& g = groups[0];
  CHECK(g.area == Approx(4.0));
  CHECK(g.triangleCount() == 2);
  CHECK(g.positions.size() == 4);
  REQUIRE(g.outlineLengths.size() == 1);
  CHECK(g.outlineLengths[0] == 4);
  CHECK(g.outline.size() == 4);
  CHECK(g.normal.z == Approx(1.0f));
}

TEST_CASE("a unit cube gives six groups of area 1 with 4-point outlines", "[qnv][outline]") {
  OutlineSummary sum;
  const auto groups = encodeOutlineGroups(unitCube(), {}, &sum);
  REQUIRE(groups.size() == 6);
  for (const PolygonGroup& g : groups) {
    CHECK(g.area == Approx(1.0));
    REQUIRE(g.outlineLengths.size() == 1);
    CHECK(g.outlineLengths[0] == 4);
    CHECK(g.positions.size() == 4);  // own vertex list, nothing shared
  }
  CHECK(sum.weldedVertices == 8);
  CHECK(sum.outlineVertices == 24);
  CHECK(sum.nonManifoldEdges == 0);
}

TEST_CASE("a square with a square hole has an outer loop and a hole", "[qnv][outline]") {
  // A 3x3 frame around a 1x1 hole, as 8 quads.
  PolygonSoup s;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) {
      if (x == 1 && y == 1) continue;
      const auto fx = static_cast<float>(x), fy = static_cast<float>(y);
      addQuad(s, {fx, fy, 0}, {fx + 1, fy, 0}, {fx + 1, fy + 1, 0}, {fx, fy + 1, 0});
    }
  const auto groups = encodeOutlineGroups(s);
  REQUIRE(groups.size() == 1);
  const PolygonGroup& g = groups[0];
  CHECK(g.area == Approx(8.0));
  REQUIRE(g.outlineLengths.size() == 2);
  CHECK(g.outlineLengths[0] == 12);  // outer: every grid point of the 3x3 border
  CHECK(g.outlineLengths[1] == 4);   // the hole
  // The outer loop encloses the hole: all of its points lie on the 3x3 border.
  for (std::size_t i = 0; i < 12; ++i) {
    const glm::vec3 p = g.outline[i];
    CHECK((p.x == 0 || p.x == 3 || p.y == 0 || p.y == 3));
  }
}

TEST_CASE("a tessellated sphere gives many groups at 10 degrees", "[qnv][outline]") {
  const PolygonSoup s = uvSphere(24, 12);
  OutlineOptions tenDegrees;
  tenDegrees.maxAngle = 0.17453293f;
  const auto groups = encodeOutlineGroups(s, tenDegrees);
  CHECK(groups.size() > 50);
  std::size_t triangles = 0;
  double area = 0.0;
  for (const PolygonGroup& g : groups) {
    triangles += g.triangleCount();
    area += g.area;
    // every triangle of a group is within 10 degrees of its seed normal
    for (std::size_t i = 0; i < g.indices.size(); i += 3) {
      const glm::vec3 n =
          glm::normalize(glm::cross(g.positions[g.indices[i + 1]] - g.positions[g.indices[i]],
                                    g.positions[g.indices[i + 2]] - g.positions[g.indices[i]]));
      CHECK(glm::dot(n, g.normal) >= std::cos(0.1746f));
    }
  }
  // The poles' degenerate triangles (two equal positions) are dropped.
  OutlineSummary sum;
  (void)encodeOutlineGroups(s, tenDegrees, &sum);
  CHECK(triangles + sum.droppedTriangles == s.triangleCount());
  CHECK(area == Approx(4.0 * std::numbers::pi).epsilon(0.05));
  // With no angle limit the sphere is one closed group: no boundary at all.
  OutlineOptions all;
  all.maxAngle = 4.0f;
  const auto one = encodeOutlineGroups(s, all);
  REQUIRE(one.size() == 1);
  CHECK(one[0].outline.empty());
}

TEST_CASE("groups are sorted by area, largest first, and keep their material", "[qnv][outline]") {
  PolygonSoup s;
  addQuad(s, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);
  addQuad(s, {5, 0, 0}, {8, 0, 0}, {8, 3, 0}, {5, 3, 0}, 1);
  addQuad(s, {1, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, 2);  // touches the first, other material
  const auto groups = encodeOutlineGroups(s);
  REQUIRE(groups.size() == 3);
  CHECK(groups[0].area == Approx(9.0));
  CHECK(groups[0].material == 1);
  CHECK(groups[1].area == Approx(2.0));
  CHECK(groups[1].material == 2);
  CHECK(groups[2].area == Approx(1.0));
  for (std::size_t i = 1; i < groups.size(); ++i) CHECK(groups[i - 1].area >= groups[i].area);
}

TEST_CASE("non-manifold and degenerate input neither crashes nor loops", "[qnv][outline]") {
  PolygonSoup s;
  // Five triangles on one edge (0,0,0)-(1,0,0), a repeated triangle, a zero-area one,
  // a non-finite one and inconsistent winding.
  s.positions = {{0, 0, 0},     {1, 0, 0},       {0.5f, 1, 0}, {0.5f, -1, 0}, {0.5f, 0, 1},
                 {0.5f, 0, -1}, {0.5f, 1, 0.1f}, {2, 0, 0},    {NAN, 0, 0}};
  s.indices = {0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 0, 5, 0, 1, 6, 0, 1, 2, 0, 1, 7, 0, 1, 8, 2, 1, 0};
  const auto groups = encodeOutlineGroups(s);
  OutlineSummary sum;
  (void)encodeOutlineGroups(s, {}, &sum);
  CHECK(sum.nonManifoldEdges >= 1);
  CHECK(sum.droppedTriangles == 2);
  std::size_t triangles = 0;
  for (const PolygonGroup& g : groups) triangles += g.triangleCount();
  CHECK(triangles == 7);
}

TEST_CASE("the outline encoder rejects broken soups", "[qnv][outline]") {
  PolygonSoup s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  s.indices = {0, 1, 3};
  CHECK_THROWS_AS(encodeOutlineGroups(s), gs::qnv::InputError);
  s.indices = {0, 1};
  CHECK_THROWS_AS(encodeOutlineGroups(s), gs::qnv::InputError);
  s.indices = {0, 1, 2};
  s.material = {0, 0};
  CHECK_THROWS_AS(encodeOutlineGroups(s), gs::qnv::InputError);
  CHECK(encodeOutlineGroups(PolygonSoup{}).empty());
}
