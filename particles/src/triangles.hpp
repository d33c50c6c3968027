// Private to particles/: the triangles of an emitter's or a bounding model's geometry, with
// a bounding volume hierarchy for line queries and an area table for uniform sampling.
#pragma once

#include "random.hpp"

#include "geometry/geometry.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <vector>

namespace gs::particles {

/// One triangle with its vertex normals (not normalized: a bounding model's carry the
/// damping as their length).
struct Triangle {
  glm::vec3 p[3];
  glm::vec3 n[3];
};

class Triangles {
 public:
  /// The triangles of `mesh` (Primitive::triangles; others give none), at most
  /// `maxTriangles`; vertex normals scaled by `normalScale`. Returns false when the mesh
  /// had more (then none are kept).
  bool assign(const vrml::Mesh& mesh, float normalScale, std::size_t maxTriangles);
  /// Appends another set (their hierarchy is built again).
  void append(const Triangles& other);
  bool empty() const { return triangles_.empty(); }
  std::size_t size() const { return triangles_.size(); }

  /// A point uniform over the surface (triangles chosen by area, X_ITE's SurfaceEmitter)
  /// and the normal interpolated there (unit length). False when the area is 0.
  bool sample(Random& random, glm::vec3& point, glm::vec3& normal) const;

  /// Every intersection of the infinite line origin + t dir (dir need not be unit) with
  /// the triangles, both faces: visit(t, point, interpolated normal) in no particular order.
  /// Each triangle tested takes one from `budget`; at 0 the search stops (a hostile mesh
  /// and particle count cannot stall a step).
  void intersectLine(
      const glm::vec3& origin, const glm::vec3& dir, std::size_t& budget,
      const std::function<void(float, const glm::vec3&, const glm::vec3&)>& visit) const;

 private:
  struct Node {
    vrml::Bounds box;
    std::uint32_t first = 0, count = 0;  // a leaf's triangles (count > 0)
    std::uint32_t left = 0, right = 0;   // an inner node's children
  };
  void build();
  std::uint32_t buildNode(std::uint32_t first, std::uint32_t count, int depth);

  std::vector<Triangle> triangles_;
  std::vector<float> cumulativeArea_;  // cumulativeArea_[i]: area of triangles 0..i
  std::vector<Node> nodes_;
};

}  // namespace gs::particles
