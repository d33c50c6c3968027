// Tessellation of VRML97 geometry nodes into triangle, line and point arrays (clause 6:
// Box 6.4, Cone 6.11, Cylinder 6.15, ElevationGrid 6.18, Extrusion 6.19,
// IndexedFaceSet 6.23, IndexedLineSet 6.24, PointSet 6.36, Sphere 6.43; Text 6.47 gives an
// empty mesh here: scene::tessellateText draws it, scene/text_mesh.hpp, so that vrml/
// needs no font library), and of the X3D 4.0 (ISO/IEC 19775-1) geometry the Immersive
// profile and CADGeometry add: the Rendering component's IndexedTriangleSet,
// IndexedTriangleFanSet, IndexedTriangleStripSet, TriangleSet, TriangleFanSet,
// TriangleStripSet and LineSet (X3D clause 11), CADGeometry's IndexedQuadSet and QuadSet
// (clause 32), and Geometry2D's Arc2D, ArcClose2D, Circle2D, Disk2D, Polyline2D,
// Polypoint2D, Rectangle2D and TriangleSet2D (clause 14). Pure computation in the node's
// local coordinates (metres).
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace gs::vrml {

/// Axis-aligned bounding box; empty when min > max.
struct Bounds {
  glm::vec3 min{1e30f};
  glm::vec3 max{-1e30f};
  bool empty() const { return min.x > max.x; }
  void extend(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Bounds& b) {
    if (!b.empty()) {
      extend(b.min);
      extend(b.max);
    }
  }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }
};

enum class Primitive : std::uint8_t { triangles, lines, points };

/// The per-vertex values of one X3D vertex attribute node of a geometry's `attrib` field
/// (X3D 4.0 clause 31.4: FloatVertexAttribute 31.4.1, Matrix3VertexAttribute 31.4.3,
/// Matrix4VertexAttribute 31.4.4), expanded to the mesh's vertices as its coordinates are.
struct VertexAttribute {
  std::string name;  // the GLSL attribute it feeds (the node's `name`)
  /// Floats per vertex: numComponents (1 to 4) of a FloatVertexAttribute, 9 of a
  /// Matrix3VertexAttribute, 16 of a Matrix4VertexAttribute (matrices column by column).
  int components = 1;
  std::vector<float> values;  // `components` per mesh vertex
};

/// Unindexed-or-indexed vertex arrays ready for a GPU buffer. Every array that is not
/// empty has one entry per vertex. Triangles are counter-clockwise seen from the front
/// (the side normals point to), whatever the node's `ccw` said.
struct Mesh {
  Primitive primitive = Primitive::triangles;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // unit length; empty for lines and points
  std::vector<glm::vec4> colors;     // RGBA in [0,1]; empty when the node has no Color
  std::vector<glm::vec2> texCoords;  // empty for lines and points
  /// The second texture coordinate set (the second TextureCoordinate of an X3D
  /// MultiTextureCoordinate, X3D 4.0 clause 18.4.3, as glTF's TEXCOORD_1 becomes), per
  /// vertex; empty when the geometry has none.
  std::vector<glm::vec2> texCoords1;
  /// X3D FogCoordinate depths (X3D 4.0 clause 24.4.2), per vertex: the distance the fog
  /// equation uses there instead of the distance to the viewer, in the geometry's length
  /// units; empty when the geometry has no FogCoordinate.
  std::vector<float> fogDepths;
  /// X3D TextureCoordinate3D / TextureCoordinate4D coordinates (X3D 4.0 clauses 33.4.6,
  /// 33.4.7) per vertex as (s, t, r, q), q = 1 for a TextureCoordinate3D: 3D textures read
  /// at (s, t, r) / q and 2D textures at (s, t) / q, divided per pixel (projective);
  /// texCoords then holds (s / q, t / q) for readers of 2D coordinates. Empty when the
  /// geometry's texCoord (or its MultiTextureCoordinate's first set) is neither node.
  std::vector<glm::vec4> texCoordsStrq;
  /// The vertex attribute nodes of the geometry's `attrib` field (X3D 4.0 clause 31.4), in
  /// their order; a node without a name or with an unusable numComponents is left out.
  std::vector<VertexAttribute> attributes;
  /// Per vertex, the coordinate point it was made from (the index into `coord`, or into
  /// ElevationGrid's grid, i + j * xDimension), when the geometry has an `attrib` node;
  /// else empty.
  std::vector<std::uint32_t> pointIndices;
  std::vector<std::uint32_t> indices;  // 3 per triangle, 2 per line segment, 1 per point
  bool solid = true;                   // back faces may be culled (the node's `solid` field)
  Bounds bounds;                       // of positions

  std::size_t triangleCount() const {
    return primitive == Primitive::triangles ? indices.size() / 3 : 0;
  }
};

/// Builds the mesh of a geometry node. Unknown or non-geometry nodes and geometry with
/// no usable data give an empty mesh. Out-of-range indices are skipped and reported once
/// per node as a warning in `diag` (when not null) at the node's location; the result
/// never reads outside the node's arrays. IndexedFaceSet polygons that are not convex
/// (or when convex is FALSE) are triangulated by ear clipping in their best-fit plane;
/// normals follow creaseAngle (radians) when the file gives none.
///
/// Details a caller may rely on:
/// - The result is indexed; a vertex is shared between triangles exactly when its position,
///   normal, colour and texture coordinate are all equal (and its coordinate point, when
///   the geometry has vertex attributes).
/// - Vertex attributes (X3D 4.0 clause 31.4; the `attrib` field of IndexedFaceSet,
///   ElevationGrid, the X3D triangle and quad sets, IndexedLineSet, LineSet and PointSet):
///   vertex v takes value pointIndices[v] of each node (FloatVertexAttribute: numComponents
///   floats from there; the matrices: one matrix), as the coordinates are indexed; a
///   missing value is 0, reported once per node; numComponents outside 1 to 4 leaves the
///   node out with a warning.
/// - Box, Cone, Cylinder and Sphere: kRoundSegments around the Y axis (Sphere: half as
///   many latitude bands, Cone kConeStacks stacks), flat caps, smooth sides, texture coordinates as
///   clause 6 says; solid unless X3D's `solid` field (X3D clause 13) is FALSE. A Box whose
///   `ccw` (castle-engine's extension field, X3D worlds only) is FALSE is turned inside
///   out: normals point in and the triangles face the inside.
/// - IndexedLineSet gives Primitive::lines (a polyline breaks at a bad index), PointSet
///   Primitive::points; both without normals or texture coordinates, solid = false.
/// - Colours come from a Color node or an X3D ColorRGBA node (X3D clause 11, its alpha goes to
///   Mesh::colors' w), in every node with a `color` field.
/// - The X3D triangle and quad sets (X3D clauses 11, 32) honour ccw, solid, colorPerVertex,
///   normalPerVertex, color, normal and texCoord (a TextureCoordinate, or the first of a
///   MultiTextureCoordinate; a TextureCoordinateGenerator gives no texture coordinates;
///   a TextureCoordinate3D or TextureCoordinate4D, here and in IndexedFaceSet, gives
///   Mesh::texCoordsStrq, a point with q = 0 or not finite reading as (0, 0, 0, 1);
///   NULL gives IndexedFaceSet's bounding-box default). Per face means per triangle (per
///   quad). Without a Normal node, normals are generated as X3D clause 11 says: with
///   normalPerVertex TRUE the average of the faces sharing the vertex (the same
///   coordinate index: non-indexed TriangleSet and QuadSet faces share none, so they come
///   out flat), with FALSE flat per face. Fans and strips (fanCount, stripCount, or -1
///   separated index runs) split into triangles keeping the first triangle's winding;
///   quads into two triangles. LineSet gives Primitive::lines, a polyline per vertexCount.
///   Counts below the minimum, counts past the end of coord and incomplete last faces are
///   skipped and reported. Coordinates may also be X3D CoordinateDouble.
/// - Geometry2D (X3D clause 14) lies in the Z = 0 plane: Arc2D, Circle2D, Polyline2D (and
///   Disk2D with innerRadius = outerRadius) give lines, Polypoint2D points, the others
///   triangles counter-clockwise about +Z with normals +Z, solid only when their `solid`
///   field (default FALSE) says so. Arcs sweep counter-clockwise from startAngle to
///   endAngle (equal angles: a full circle), kRoundSegments segments per full turn.
///   Texture coordinates of the filled ones map the shape's bounding box onto [0,1]^2 (s
///   along X, t along Y; for Rectangle2D the front face of a Box).
/// - Degenerate polygons (fewer than 3 distinct points, zero area) are dropped silently;
///   ElevationGrid uses only the complete rows its height array holds; Extrusion caps are
///   made whenever beginCap / endCap ask for them (also on closed spines) and its grid is
///   limited to kMaxExtrusionPoints.
/// - Text gives an empty mesh (scene::tessellateGeometry draws it through FreeType).
/// Safe for untrusted nodes: time and memory stay proportional to the node's arrays.
/// `nurbsTessellationScale` (>= 0) multiplies a NurbsPatchSurface's or NurbsTrimmedSurface's
/// segments (rounded down, at least 1): the tessellationScale of the NurbsSet that holds it
/// (X3D 4.0 27.4.6, as X_ITE 15 applies it); other geometry ignores it.
Mesh tessellate(const Node& geometry, Diagnostics* diag = nullptr,
                float nurbsTessellationScale = 1.0f);

/// The filled polygon of an outline (the GhostSpace OutlineGroup extension node,
/// docs/vrml-extensions.md; tessellate() of an OutlineGroup node calls this with its
/// `outline` and `outlineLengths` fields). `points` holds closed loops concatenated;
/// `loopLengths` the number of points of each loop (empty: one loop of all points; a
/// negative length counts as 0; lengths past the end of `points` are cut short and
/// reported as a warning in `diag`, when not null, at `where`). The first loop is the
/// outer boundary, later loops are holes: each hole is joined to the outer loop by a
/// bridge and the result ear-clipped in the outer loop's best-fit plane (the same ear
/// clipping as IndexedFaceSet). The mesh is flat-shaded with the plane's normal (Newell
/// normal of the outer loop), not solid (two-sided), indexed into `points`' positions;
/// degenerate loops give an empty mesh. Time O(h x n) for h holes and n points.
Mesh triangulateOutline(const std::vector<glm::vec3>& points,
                        const std::vector<std::int32_t>& loopLengths, Diagnostics* diag = nullptr,
                        const SourceLocation& where = {});

/// Number of segments used around the circumference of Cone, Cylinder and Sphere, and per
/// full turn of the Geometry2D arcs and circles.
inline constexpr int kRoundSegments = 32;

/// Number of stacks (rings up the side) of a Cone: 2 * (kConeStacks - 1) + 1 triangles per
/// segment, so that the side normal, which depends only on the angle, varies smoothly
/// (a Cylinder needs one stack: per-pixel lighting interpolates its normals exactly).
inline constexpr int kConeStacks = 8;

/// Most grid points (spine points x crossSection points) an Extrusion is tessellated with;
/// beyond it the spine is cut short (with a warning), so that a small file cannot ask for
/// gigabytes.
inline constexpr std::size_t kMaxExtrusionPoints = std::size_t{1} << 20;

}  // namespace gs::vrml
