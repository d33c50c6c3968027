// Private helpers shared by the tessellation sources (geometry*.cpp): field access,
// per-node problem reporting, a deduplicating mesh builder, the polygon-soup pipeline
// (IndexedFaceSet, ElevationGrid and Extrusion all go through it), ear clipping and
// crease-angle normals. Not part of the public interface.
#pragma once

#include "geometry/geometry.hpp"

#include <glm/glm.hpp>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace gs::vrml::geometry_detail {

// ---------------------------------------------------------------------------------------
// Field access

/// The value of field `name` of `node` when it exists with type T, else a static empty
/// (default) value of that type. Returns a reference: no copy of big arrays.
template <FieldType T>
const auto& fieldOr(const Node& node, std::string_view name) {
  using V = std::remove_cvref_t<decltype(std::declval<const FieldValue&>().get<T>())>;
  static const V kEmpty{};
  const FieldValue* f = node.field(name);
  if (f == nullptr || f->type() != T) return kEmpty;
  return f->get<T>();
}

/// As above, with `absent` returned when the node's type has no field `name` (a field
/// that exists with another type still gives the empty value).
template <FieldType T, class V>
const V& fieldOr(const Node& node, std::string_view name, const V& absent) {
  if (node.field(name) == nullptr) return absent;
  return fieldOr<T>(node, name);
}

/// The array field `arrayName` of the SFNode child `childName` (e.g. coord.point); empty
/// when the child is NULL or lacks the field.
template <FieldType T>
const auto& childArray(const Node& node, std::string_view childName, std::string_view arrayName) {
  using V = std::remove_cvref_t<decltype(std::declval<const FieldValue&>().get<T>())>;
  static const V kEmpty{};
  const NodePtr child = node.sfnode(childName);
  if (child == nullptr) return kEmpty;
  return fieldOr<T>(*child, arrayName);
}

bool finite(const glm::vec2& v);
bool finite(const glm::vec3& v);
/// Colour with components clamped to [0, 1] (NaN becomes 0) and alpha 1.
glm::vec4 rgba(const glm::vec3& c);
/// Colour with all four components clamped to [0, 1] (NaN becomes 0).
glm::vec4 rgba(const glm::vec4& c);

/// The colours of a geometry node's `color` field, whichever node it holds: a Color
/// (VRML97 6.12, MFColor `color`; alpha 1) or an X3D ColorRGBA (X3D 4.0 clause 11,
/// MFColorRGBA `color`). Does not copy the node's array.
class ColorSource {
 public:
  explicit ColorSource(const Node& geometry, std::string_view field = "color");
  /// True when the field holds a node (a Color or ColorRGBA, possibly empty).
  bool present() const { return present_; }
  std::size_t size() const { return rgb_ != nullptr ? rgb_->size() : rgba_->size(); }
  bool empty() const { return size() == 0; }
  /// Colour `i` (< size()), clamped to [0, 1].
  glm::vec4 operator[](std::size_t i) const {
    return rgb_ != nullptr ? rgba((*rgb_)[i]) : rgba((*rgba_)[i]);
  }

 private:
  bool present_ = false;
  const std::vector<glm::vec3>* rgb_ = nullptr;
  const std::vector<glm::vec4>* rgba_ = nullptr;
};

/// The texture coordinates of a geometry node's `texCoord` field: a TextureCoordinate's
/// `point`, or the first TextureCoordinate of a MultiTextureCoordinate (X3D 4.0 clause 18).
/// `kind` tells which case applies: none (NULL field: the node's default mapping),
/// points (the returned array, possibly empty), generated (TextureCoordinateGenerator,
/// X3D clause 18, or anything else: coordinates come from elsewhere, the mesh gets none).
enum class TexSource : std::uint8_t { none, points, generated };
const std::vector<glm::vec2>& texCoordPoints(const Node& geometry, TexSource& kind);

/// The `point` array of the second TextureCoordinate of a geometry's MultiTextureCoordinate
/// (X3D 4.0 clause 18.4.3), or null when it has none (Mesh::texCoords1).
const std::vector<glm::vec2>* secondTexCoordPoints(const Node& geometry);

/// X3D TextureCoordinate3D (MFVec3f `point`) or TextureCoordinate4D (MFVec4f `point`)
/// in a geometry's `texCoord`, or as the first set of its MultiTextureCoordinate (X3D 4.0
/// clauses 33.4.6, 33.4.7): `strq` holds each point as (s, t, r, q) (q = 1 for 3D; a point
/// with q = 0 or a non-finite component becomes (0, 0, 0, 1)), `st` its (s / q, t / q).
/// `present` is false (and both empty) when the field holds neither node (Mesh::texCoordsStrq).
struct StrqPoints {
  std::vector<glm::vec4> strq;
  std::vector<glm::vec2> st;
  bool present = false;
};
StrqPoints strqTexCoordPoints(const Node& geometry);

/// The points of a geometry node's `coord` field: a Coordinate's MFVec3f `point`, or an
/// X3D CoordinateDouble's MFVec3d `point` converted into `scratch` (rounded to float).
/// Empty when the field is NULL or holds something else.
std::span<const glm::vec3> coordPoints(const Node& geometry, std::vector<glm::vec3>& scratch);

/// True when the geometry's X3D `attrib` field holds a node (X3D 4.0 clause 31.4): its
/// mesh must record the point of each vertex (MeshBuilder::carryPoints).
bool hasVertexAttributes(const Node& geometry);

/// Fills m.attributes from the geometry's `attrib` nodes through m.pointIndices
/// (geometry_attributes.cpp); problems go to `log`.
class ProblemLog;
void assignVertexAttributes(const Node& geometry, Mesh& m, ProblemLog& log);

// ---------------------------------------------------------------------------------------
// Problems

/// Collects what was wrong with one node's data and reports it as a single warning (the
/// first problem, plus a count of the others) at the node's location.
class ProblemLog {
 public:
  ProblemLog(const Node& node, Diagnostics* diag) : node_(node), diag_(diag) {}
  /// Records one problem; only the first message is kept verbatim.
  void add(const std::string& message);
  /// As add, but calls `makeMessage()` only for the first problem (cheap in loops).
  template <class F>
  void addLazy(F&& makeMessage) {
    if (count_++ == 0) first_ = makeMessage();
  }
  /// Emits the warning, if any problem was recorded (once).
  void flush();
  std::size_t count() const { return count_; }

 private:
  const Node& node_;
  Diagnostics* diag_;
  std::string first_;
  std::size_t count_ = 0;
  bool flushed_ = false;
};

// ---------------------------------------------------------------------------------------
// Mesh building

/// One output vertex; attributes a mesh does not carry are left zero.
struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};
  glm::vec4 color{0.0f};
  glm::vec2 texCoord{0.0f};
  glm::vec2 texCoord1{0.0f};     // the second set (Mesh::texCoords1)
  glm::vec4 texCoordStrq{0.0f};  // X3D TextureCoordinate3D/4D (Mesh::texCoordsStrq)
  std::uint32_t point = 0;       // the coordinate point it comes from (Mesh::pointIndices)
};

/// Accumulates vertices and indices into a Mesh. `add` merges vertices whose attributes
/// are bit-for-bit equal, so vertices are split exactly where normals, colours or texture
/// coordinates differ.
class MeshBuilder {
 public:
  MeshBuilder(Primitive primitive, bool normals, bool colors, bool texCoords);
  /// Makes the mesh carry Vertex::texCoord1 too (before the first vertex).
  void carrySecondTexCoords() { texCoords1_ = true; }
  /// Makes the mesh carry Vertex::texCoordStrq too (before the first vertex).
  void carryStrqTexCoords() { texCoordsStrq_ = true; }
  /// Makes the mesh carry Vertex::point too (Mesh::pointIndices; before the first vertex).
  void carryPoints() { points_ = true; }
  /// Index of a vertex equal to `v`, appending it when new.
  std::uint32_t add(const Vertex& v);
  /// Appends `v` without looking for an equal vertex.
  std::uint32_t push(const Vertex& v);
  /// True when stored vertex `i` has exactly the attributes of `v`.
  bool sameAsStored(std::uint32_t i, const Vertex& v) const;
  void index(std::uint32_t i) { mesh_.indices.push_back(i); }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh_.indices.insert(mesh_.indices.end(), {a, b, c});
  }
  void reserve(std::size_t vertices, std::size_t indices);
  /// The finished mesh with bounds computed; the builder is left empty.
  Mesh finish(bool solid);

 private:
  /// 64-bit hash of the attributes this mesh carries (bit patterns, so -0 != +0).
  std::uint64_t hashOf(const Vertex& v) const;
  std::uint64_t hashOfStored(std::uint32_t i) const;
  void grow(std::size_t minSlots);

  Mesh mesh_;
  bool normals_, colors_, texCoords_, texCoords1_ = false, points_ = false;
  bool texCoordsStrq_ = false;
  /// Open-addressing table: (high 32 bits of the hash << 32) | (vertex index + 1); 0 = empty.
  std::vector<std::uint64_t> slots_;
};

// ---------------------------------------------------------------------------------------
// Polygons (geometry_polygon.cpp)

/// Newell's normal of the closed polygon `pts` (not normalized: its length is twice the
/// polygon's area, its direction the one about which the polygon turns counterclockwise).
glm::dvec3 newellNormal(std::span<const glm::vec3> pts);

/// Triangulates the polygon `pts` (in order, implicitly closed) in the plane through it
/// with unit normal `normal` (normally its Newell normal). Appends triangles to `out` as
/// index triples into `pts`, each counterclockwise about `normal` and of non-zero area.
/// When `assumeConvex` is true and the polygon really is convex (checked) every vertex is
/// kept and no containment test is made; otherwise the polygon is ear-clipped, which
/// handles concave polygons, collinear vertices and repeated positions. The triangles of
/// a simple polygon cover exactly its area; self-intersecting input gives a best effort.
/// A convex polygon is split as a fan from pts[fanApex] (the polygon's first vertex as the
/// file gives it; other browsers and OpenGL's GL_POLYGON split it so): triangles
/// (apex, apex+1, apex+2), (apex, apex+2, apex+3), ...; ear clipping starts there too.
void triangulatePolygon(std::span<const glm::vec3> pts, const glm::dvec3& normal, bool assumeConvex,
                        std::vector<std::uint32_t>& out, std::size_t fanApex = 0);

// ---------------------------------------------------------------------------------------
// Normals (geometry_normals.cpp)

/// Inputs of crease-angle smoothing, one entry per polygon corner.
struct CornerSet {
  std::span<const std::uint32_t> point;   // shared point index of the corner (< pointCount)
  std::span<const std::uint32_t> face;    // face of the corner
  std::span<const float> weight;          // its weight (the polygon's angle at the corner)
  std::span<const glm::vec3> faceNormal;  // unit normal of each face
  std::size_t pointCount = 0;
};

/// Vertex normals per corner (clause 6.23, creaseAngle): the weighted sum of the normals
/// of the faces around the corner's point whose angle to the corner's own face normal is
/// at most `creaseAngle` radians, normalized. 0 gives flat faces. Time is linear in the
/// number of corners times a bounded number of normal clusters per point.
std::vector<glm::vec3> creaseNormals(const CornerSet& corners, float creaseAngle);

// ---------------------------------------------------------------------------------------
// Polygon soup: the common path of IndexedFaceSet, ElevationGrid and Extrusion

/// Polygons over shared points with optional per-corner attributes.
struct PolygonSoup {
  std::span<const glm::vec3> points;        // positions (may be the node's own array)
  std::vector<std::uint32_t> corners;       // point index of each corner, faces concatenated
  std::vector<std::uint32_t> faceStart{0};  // face f is corners [faceStart[f], faceStart[f+1])
  /// Per corner, or empty. A non-finite or zero normal means "generate this one".
  std::vector<glm::vec3> normals;
  std::vector<glm::vec4> colors;      // per corner, or empty
  std::vector<glm::vec2> texCoords;   // per corner, or empty
  std::vector<glm::vec2> texCoords1;  // the second set per corner, or empty (Mesh::texCoords1)
  /// X3D TextureCoordinate3D/4D per corner (Mesh::texCoordsStrq), or empty; texCoords
  /// then holds their (s / q, t / q).
  std::vector<glm::vec4> texCoordsStrq;
  float creaseAngle = 0.0f;
  bool carryPoints = false;  // the mesh records each vertex's point (Mesh::pointIndices)
  bool ccw = true;
  bool convex = true;
  bool solid = true;

  std::size_t faceCount() const { return faceStart.size() - 1; }
  void endFace() { faceStart.push_back(static_cast<std::uint32_t>(corners.size())); }
};

/// Default IndexedFaceSet texture coordinates (6.23), appended per corner of `soup`: S
/// along the longest side of the corners' bounding box (0 to 1), T along the second
/// longest (0 to its length / the longest); ties prefer X, then Y, then Z.
void defaultTexCoords(PolygonSoup& soup);

/// Appends one corner's texture coordinates to `soup`: point `index` of `texPoints` (the
/// geometry's texCoord, or its 3D / 4D points' (s / q, t / q)) to texCoords, of `strq` to
/// texCoordsStrq when present, of `second` (a MultiTextureCoordinate's second set; null
/// when none) to texCoords1. An index past a list or a point that is not finite gives
/// (0, 0) (and (0, 0, 0, 1)).
void addTexCorner(PolygonSoup& soup, std::span<const glm::vec2> texPoints, const StrqPoints& strq,
                  const std::vector<glm::vec2>* second, std::size_t index);

/// A soup over `points` with the node's ccw, convex, solid and creaseAngle fields
/// (IndexedFaceSet 6.23, ElevationGrid 6.18, Extrusion 6.19; an absent field keeps its
/// VRML97 default: TRUE, TRUE, TRUE, 0 radians); carryPoints when the node has vertex
/// attributes.
PolygonSoup polygonSoupOf(const Node& node, std::span<const glm::vec3> points);

/// Triangulates the soup: reverses faces when ccw is FALSE, drops repeated consecutive
/// points and degenerate faces (fewer than 3 distinct points or zero area), ear-clips,
/// generates missing normals (Newell face normals smoothed by creaseAngle) and emits an
/// indexed triangle mesh. Corners must reference valid, finite points.
Mesh buildPolygonMesh(const PolygonSoup& soup);

// ---------------------------------------------------------------------------------------
// Node tessellators (one per geometry node type)

Mesh tessellateBox(const Node& node, ProblemLog& log);
Mesh tessellateCone(const Node& node, ProblemLog& log);
Mesh tessellateCylinder(const Node& node, ProblemLog& log);
Mesh tessellateSphere(const Node& node, ProblemLog& log);
Mesh tessellateIndexedFaceSet(const Node& node, ProblemLog& log);
Mesh tessellateIndexedLineSet(const Node& node, ProblemLog& log);
Mesh tessellatePointSet(const Node& node, ProblemLog& log);
Mesh tessellateElevationGrid(const Node& node, ProblemLog& log);
/// Point (i, j) of a plain ElevationGrid (VRML97 6.18; X3D 4.0 13.3.4): (xSpacing i,
/// height, zSpacing j), rounded to float as the tessellator places it.
glm::vec3 elevationGridPoint(double xSpacing, double zSpacing, std::size_t i, std::size_t j,
                             double height);
/// The first `count` points of a plain ElevationGrid (i fastest; a missing height is 0),
/// at most xDimension x zDimension of them; empty when a dimension is < 1.
std::vector<glm::vec3> elevationGridPoints(const Node& node, std::size_t count);
Mesh tessellateExtrusion(const Node& node, ProblemLog& log);

/// What an Extrusion is made of (clause 6.19's fields).
struct ExtrusionInput {
  std::span<const glm::vec3> spine;
  std::span<const glm::vec2> crossSection, scale;
  std::span<const Rotation> orientation;
  bool beginCap = true, endCap = true;
};
/// The Extrusion of `in` (clause 6.19), its grid points made a soup by `soupOf` (which
/// sets ccw, solid, convex and creaseAngle): Extrusion nodes and the NURBS swept and swung
/// surfaces (geometry_nurbs_swept.cpp).
Mesh extrude(const ExtrusionInput& in,
             const std::function<PolygonSoup(std::span<const glm::vec3>)>& soupOf, ProblemLog& log);
/// The points of the NURBS curve of `node`'s order, knot, weight, closed and tessellation
/// fields through control points `points` (X3D 4.0 27.2.3: tessellation segments; a closed
/// curve periodic, as X_ITE makes it), or none when there are fewer than 2 or too many
/// control points: geometry_nurbs.cpp.
std::vector<glm::dvec3> nurbsCurvePoints(const Node& node, const std::vector<glm::dvec3>& points,
                                         ProblemLog& log);
/// The points of a NurbsCurve2D (tessellated as a NurbsCurve is) or ContourPolyline2D (its
/// controlPoint), X3DNurbsControlCurveNode of X3D 4.0 27.3.1; none for other nodes.
std::vector<glm::dvec2> nurbsCurve2DPoints(const NodePtr& node, ProblemLog& log);
// X3D NURBS swept and swung surfaces (X3D 4.0 27.4.11, 27.4.12): geometry_nurbs_swept.cpp.
Mesh tessellateNurbsSweptSurface(const Node& node, ProblemLog& log);
Mesh tessellateNurbsSwungSurface(const Node& node, ProblemLog& log);

// X3D 4.0 Rendering (clause 11) and CADGeometry (clause 32): geometry_x3d.cpp.
Mesh tessellateIndexedTriangleSet(const Node& node, ProblemLog& log);
Mesh tessellateIndexedTriangleFanSet(const Node& node, ProblemLog& log);
Mesh tessellateIndexedTriangleStripSet(const Node& node, ProblemLog& log);
Mesh tessellateTriangleSet(const Node& node, ProblemLog& log);
Mesh tessellateTriangleFanSet(const Node& node, ProblemLog& log);
Mesh tessellateTriangleStripSet(const Node& node, ProblemLog& log);
Mesh tessellateIndexedQuadSet(const Node& node, ProblemLog& log);
Mesh tessellateQuadSet(const Node& node, ProblemLog& log);
Mesh tessellateLineSet(const Node& node, ProblemLog& log);

// X3D 4.0 Geometry2D (clause 14): geometry_2d.cpp.
/// X3D NURBS (geometry_nurbs.cpp): NurbsCurve as lines; NurbsPatchSurface and
/// NurbsTrimmedSurface (untrimmed) as triangles.
Mesh tessellateNurbsCurve(const Node& node, ProblemLog& log);
/// `scale`: the NurbsSet's tessellationScale (segments times it, rounded down, >= 1).
Mesh tessellateNurbsSurface(const Node& node, ProblemLog& log, float scale = 1.0f);
Mesh tessellateArc2D(const Node& node, ProblemLog& log);
Mesh tessellateArcClose2D(const Node& node, ProblemLog& log);
Mesh tessellateCircle2D(const Node& node, ProblemLog& log);
Mesh tessellateDisk2D(const Node& node, ProblemLog& log);
Mesh tessellatePolyline2D(const Node& node, ProblemLog& log);
Mesh tessellatePolypoint2D(const Node& node, ProblemLog& log);
Mesh tessellateRectangle2D(const Node& node, ProblemLog& log);
Mesh tessellateTriangleSet2D(const Node& node, ProblemLog& log);

/// An orthonormal basis (u, v) of the plane normal to the unit vector `n`, with
/// u x v = n: counter-clockwise in the (u, v) plane is counter-clockwise about n.
inline void planeBasis(const glm::dvec3& n, glm::dvec3& u, glm::dvec3& v) {
  u = std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0));
  u = glm::normalize(u);
  v = glm::cross(n, u);
}

}  // namespace gs::vrml::geometry_detail
