// The outline-group encoder (paper section 1.1, "Outlines and priority sorting"; figure
// 1): a polygon world is cut into independent groups of neighbouring, near-coplanar
// triangles. Each group is described twice: by its outline (the positions of its boundary
// vertices, closed loops, no adjacency list), which is sent first, and by its own
// triangles over its own vertex list, sent later, largest group first. No index data is
// shared between groups, so a lost or late group costs only itself.
//
// Pure computation on the caller's buffers: no I/O, no OpenGL. The VRML97 writer that
// lays groups out as OutlineGroup nodes is outline_world.hpp; the node is documented
// in docs/vrml-extensions.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/error.hpp"

namespace gs::outline {

/// The error encodeOutlineGroups throws (shared with the codec: malformed input).
using qnv::InputError;

/// Triangles over shared positions, one material id per triangle. Units are the caller's
/// (metres for VRML worlds); triangles are counter-clockwise seen from their front.
///
/// Invariants checked by encodeOutlineGroups (InputError otherwise):
/// indices.size() % 3 == 0; every index < positions.size(); material.size() ==
/// indices.size() / 3, or material is empty (every triangle has material 0);
/// normals is empty or has positions.size() entries.
struct PolygonSoup {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;   // three per triangle
  std::vector<std::uint32_t> material;  // per triangle; an opaque id (e.g. an Appearance)
  /// Optional per-vertex shading normals, carried into each group's local vertex list
  /// (PolygonGroup::normals); they play no part in grouping.
  std::vector<glm::vec3> normals;

  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// How triangles are grouped.
struct OutlineOptions {
  /// Largest angle in radians between a triangle's normal and its group's seed normal
  /// (the normal of the group's first, largest triangle). Default 30 degrees (fewer,
  /// larger groups: a cylinder of 32 facets makes 12 groups, not 32). 0 keeps
  /// only exactly parallel triangles together; values >= pi put every connected
  /// triangle of one material in one group.
  float maxAngle = 0.52359878f;
};

/// One group: connected (across shared edges), one material, near-coplanar.
struct PolygonGroup {
  std::uint32_t material = 0;
  glm::vec3 normal{0.0f};  // unit normal of the seed triangle
  double area = 0.0;       // sum of the triangle areas, square units
  /// The group's own vertices (a copy: nothing is shared with other groups) and its
  /// triangles as index triples into them, in input order and winding. A vertex of the
  /// input appears once per group that uses it.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per local vertex when PolygonSoup::normals was given
  std::vector<std::uint32_t> indices;
  /// Input triangle number of each local triangle (indices.size() / 3 entries).
  std::vector<std::uint32_t> sourceTriangles;
  /// Boundary loops, vertex positions concatenated; loop i has outlineLengths[i] points
  /// (not repeating its first point). The boundary edges are the edges used by exactly
  /// one triangle of the group, chained head to tail, so loops turn counter-clockwise
  /// about `normal` for the outer boundary and clockwise for holes. Loops are sorted by
  /// the area they enclose (projected on `normal`), largest first: the first loop is the
  /// outer one (normally also the longest), the others are holes. Where the group is
  /// not a manifold surface (an edge used by 3+ triangles, inconsistent winding), a chain
  /// that cannot close is still emitted as a loop: a best effort, never an endless walk.
  std::vector<glm::vec3> outline;
  std::vector<std::uint32_t> outlineLengths;

  std::size_t triangleCount() const { return indices.size() / 3; }
};

/// Counts of an encoding run.
struct OutlineSummary {
  std::size_t triangles = 0;         // triangles in the input
  std::size_t droppedTriangles = 0;  // zero-area or non-finite triangles, in no group
  std::size_t weldedVertices = 0;    // distinct positions after welding
  std::size_t nonManifoldEdges = 0;  // edges used by 3 or more triangles
  std::size_t outlineVertices = 0;   // sum of the groups' outline.size()
};

/// Cuts `soup` into outline groups.
///
/// 1. Vertices are welded by exact position (bitwise-equal coordinates, -0 == +0).
/// 2. Triangles with zero area (after welding) or non-finite positions are dropped.
/// 3. Region growing, seeds taken largest triangle first: a triangle joins the group
///    of a neighbour across a shared edge when it has the same material and its unit
///    normal is within options.maxAngle of the group's seed normal. Only manifold edges
///    (used by exactly two triangles) connect; an edge used by 3+ triangles is a border.
/// 4. Each group's outline is traced from its boundary edges (see PolygonGroup).
/// 5. Groups are sorted by area, largest first (ties: lowest seed triangle first), so
///    every prefix of the result is the best picture of its size.
///
/// Time O(n log n) and memory O(n) in the number of triangles, whatever the input
/// (non-manifold edges, repeated triangles, inconsistent winding): safe for untrusted
/// input. Throws InputError when the soup breaks its invariants.
std::vector<PolygonGroup> encodeOutlineGroups(const PolygonSoup& soup,
                                              const OutlineOptions& options = {},
                                              OutlineSummary* summary = nullptr);

}  // namespace gs::outline
