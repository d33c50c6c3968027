// Helpers of the geometry tests (test_geometry.cpp, test_geometry_extrusion.cpp): VRML
// geometry nodes built from text, and the measures and checks of the meshes they give.
#pragma once

#include <catch2/catch.hpp>

#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace gs::vrml::geometry_tests {

inline constexpr double kPi = std::numbers::pi;

// ---- building nodes from VRML text ------------------------------------------------------

/// The geometry node of `Shape { geometry <text> }`, parsed as a VRML97 file (which must
/// give no diagnostics).
inline NodePtr parseGeometry(const std::string& text) {
  const Scene scene = parseVrml("#VRML V2.0 utf8\nShape { geometry " + text + " }\n", "test.wrl");
  INFO(text);
  for (const Diagnostic& d : scene.diagnostics.items) INFO(d.format());
  REQUIRE(scene.diagnostics.items.empty());
  REQUIRE(scene.rootNodes.size() == 1);
  NodePtr g = scene.rootNodes[0]->sfnode("geometry");
  REQUIRE(g != nullptr);
  return g;
}

inline Mesh mesh(const std::string& text, Diagnostics* diag = nullptr) {
  return tessellate(*parseGeometry(text), diag);
}

inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

template <int N, class T>
std::string list(const std::vector<glm::vec<N, T>>& v) {
  std::string s = "[";
  for (const auto& x : v) {
    for (int k = 0; k < N; ++k) s += num(x[k]) + ' ';
    s += ", ";
  }
  return s + ']';
}

inline std::string list(const std::vector<std::int32_t>& v) {
  std::string s = "[";
  for (std::int32_t i : v) s += std::to_string(i) + ' ';
  return s + ']';
}

/// `IndexedFaceSet { coord Coordinate { point [...] } coordIndex [...] <more> }`
inline std::string faceSet(const std::vector<glm::vec3>& points,
                           const std::vector<std::int32_t>& index, const std::string& more = "") {
  return "IndexedFaceSet { coord Coordinate { point " + list(points) + " } coordIndex " +
         list(index) + " " + more + " }";
}

/// Sets field `name` of `node` (for values VRML text cannot express, such as NaN).
template <FieldType T, class V>
void set(const NodePtr& node, const std::string& name, V value) {
  FieldValue* f = node->field(name);
  REQUIRE(f != nullptr);
  *f = FieldValue::make<T>(std::move(value));
}

// ---- measuring meshes -----------------------------------------------------------------

inline glm::dvec3 P(const Mesh& m, std::uint32_t i) {
  return glm::dvec3(m.positions[i]);
}

/// Area-weighted normal of triangle t (length = area).
inline glm::dvec3 triangleNormal(const Mesh& m, std::size_t t) {
  const glm::dvec3 a = P(m, m.indices[3 * t]), b = P(m, m.indices[3 * t + 1]),
                   c = P(m, m.indices[3 * t + 2]);
  return glm::cross(b - a, c - a) * 0.5;
}

inline double area(const Mesh& m) {
  double sum = 0.0;
  for (std::size_t t = 0; t < m.triangleCount(); ++t) sum += glm::length(triangleNormal(m, t));
  return sum;
}

/// Common checks: arrays consistent, indices in range, normals unit, bounds right, every
/// triangle counterclockwise with respect to its vertex normals.
inline void checkMesh(const Mesh& m) {
  REQUIRE(m.primitive == Primitive::triangles);
  REQUIRE(m.indices.size() % 3 == 0);
  REQUIRE(m.normals.size() == m.positions.size());
  if (!m.colors.empty()) REQUIRE(m.colors.size() == m.positions.size());
  if (!m.texCoords.empty()) REQUIRE(m.texCoords.size() == m.positions.size());
  for (std::uint32_t i : m.indices) REQUIRE(i < m.positions.size());
  for (const glm::vec3& n : m.normals) REQUIRE(glm::length(n) == Approx(1.0).margin(1e-4));
  Bounds b;
  for (const glm::vec3& p : m.positions) b.extend(p);
  REQUIRE(m.bounds.min == b.min);
  REQUIRE(m.bounds.max == b.max);
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::dvec3 fn = triangleNormal(m, t);
    REQUIRE(glm::length(fn) > 0.0);
    glm::dvec3 vn(0.0);
    for (int k = 0; k < 3; ++k) vn += glm::dvec3(m.normals[m.indices[3 * t + k]]);
    REQUIRE(glm::dot(fn, vn) > 0.0);
  }
}

/// For convex shapes: each vertex normal and each triangle faces away from `centre`.
inline void checkOutward(const Mesh& m, glm::dvec3 centre) {
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    glm::dvec3 c(0.0);
    for (int k = 0; k < 3; ++k) c += P(m, m.indices[3 * t + k]) / 3.0;
    REQUIRE(glm::dot(triangleNormal(m, t), c - centre) > 0.0);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m.indices[3 * t + k];
      REQUIRE(glm::dot(glm::dvec3(m.normals[v]), P(m, v) - centre) > -1e-6);
    }
  }
}

/// True when every edge (by position) is used exactly twice, once in each direction.
inline bool closedSurface(const Mesh& m) {
  using K = std::tuple<float, float, float>;
  auto key = [&](std::uint32_t i) {
    return K(m.positions[i].x, m.positions[i].y, m.positions[i].z);
  };
  std::map<std::pair<K, K>, int> edges;
  for (std::size_t t = 0; t < m.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k)
      ++edges[{key(m.indices[3 * t + k]), key(m.indices[3 * t + (k + 1) % 3])}];
  for (const auto& [e, n] : edges) {
    if (n != 1) return false;
    auto it = edges.find({e.second, e.first});
    if (it == edges.end() || it->second != 1) return false;
  }
  return true;
}

inline std::size_t distinct(const std::vector<glm::vec3>& v) {
  std::set<std::tuple<float, float, float>> s;
  for (const glm::vec3& x : v) s.emplace(x.x, x.y, x.z);
  return s.size();
}

}  // namespace gs::vrml::geometry_tests
