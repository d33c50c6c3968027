// The X3D composed geometry of the Rendering component (X3D 4.0 clause 11):
// IndexedTriangleSet, IndexedTriangleFanSet, IndexedTriangleStripSet, TriangleSet,
// TriangleFanSet, TriangleStripSet and LineSet; and of the CADGeometry component (clause
// 32): IndexedQuadSet and QuadSet. The triangle and quad sets become a polygon soup over
// their Coordinate (or CoordinateDouble) points and go through buildPolygonMesh, as
// IndexedFaceSet does, so ccw, degenerate faces and vertex splitting behave the same.
//
// In these nodes one number per vertex (the index value, or the vertex's position in
// `coord` for the non-indexed sets) selects its coordinate, and per vertex its colour,
// normal and texture coordinate too. Per face (colorPerVertex / normalPerVertex FALSE)
// a face is one triangle (one quad for the quad sets), numbered in the node's order; a
// face dropped for a bad index keeps its number, so the colours of the others stay put.
//
// Normals, when the node has none, are generated as clause 11 asks of these nodes: with
// normalPerVertex TRUE the normal at a vertex is the average of the normals of all the
// faces that share that vertex (that coordinate index: the vertices of the fans and
// strips are shared within a fan or strip, those of TriangleSet and QuadSet are not, so
// they come out flat), with normalPerVertex FALSE each face gets its own flat normal.
// Texture coordinates, when texCoord is NULL, default as for IndexedFaceSet (bounding
// box); a TextureCoordinateGenerator gives none here.
#include "geometry_internal.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

namespace gs::vrml::geometry_detail {

namespace {

constexpr glm::vec4 kWhite(1.0f);

/// The faces of a composed triangle or quad set, as vertex numbers, checked against
/// the node's points: a face with a vertex out of range or not finite is counted (for
/// per-face attributes) but not kept, and the first problem is reported.
class Faces {
 public:
  Faces(std::span<const glm::vec3> points, ProblemLog& log) : points_(points), log_(log) {}

  /// Offers the next face, of `n` vertex numbers `v`; `what` and `pos` name where the
  /// first of them was read (e.g. "index", 6) for the message of a bad one.
  void add(const std::int64_t* v, int n, const char* what, std::size_t pos) {
    const std::size_t number = count_++;
    for (int k = 0; k < n; ++k) {
      if (v[k] < 0 || static_cast<std::uint64_t>(v[k]) >= points_.size()) {
        log_.addLazy([&] {
          return std::string(what) + "[" + std::to_string(pos + static_cast<std::size_t>(k)) +
                 "] = " + std::to_string(v[k]) + " is out of range (" +
                 std::to_string(points_.size()) + " points)";
        });
        return;
      }
      if (!finite(points_[static_cast<std::size_t>(v[k])])) {
        log_.addLazy([&] { return "point " + std::to_string(v[k]) + " is not a finite number"; });
        return;
      }
    }
    for (int k = 0; k < n; ++k) corners.push_back(static_cast<std::uint32_t>(v[k]));
    faceStart.push_back(static_cast<std::uint32_t>(corners.size()));
    number_.push_back(number);
  }

  void triangle(std::int64_t a, std::int64_t b, std::int64_t c, const char* what, std::size_t pos) {
    const std::int64_t v[3] = {a, b, c};
    add(v, 3, what, pos);
  }

  std::vector<std::uint32_t> corners;
  std::vector<std::uint32_t> faceStart{0};
  /// The number of kept face k among all faces offered.
  std::size_t number(std::size_t k) const { return number_[k]; }
  std::size_t kept() const { return number_.size(); }

 private:
  std::span<const glm::vec3> points_;
  ProblemLog& log_;
  std::vector<std::size_t> number_;
  std::size_t count_ = 0;
};

/// Triangulates the faces with the node's colours, normals and texture coordinates.
Mesh buildComposed(const Node& node, ProblemLog& log, std::span<const glm::vec3> points,
                   Faces& faces) {
  if (faces.kept() == 0) return {};
  PolygonSoup soup = polygonSoupOf(node, points);
  const bool colorPerVertex = node.get<FieldType::SFBool>("colorPerVertex", true);
  const bool normalPerVertex = node.get<FieldType::SFBool>("normalPerVertex", true);
  soup.convex = true;  // quads are split along their first diagonal when convex
  soup.creaseAngle = normalPerVertex ? static_cast<float>(std::numbers::pi) : 0.0f;

  const ColorSource colors(node);
  const auto& normals = childArray<FieldType::MFVec3f>(node, "normal", "vector");
  TexSource texKind = TexSource::none;
  const StrqPoints strq = strqTexCoordPoints(node);  // X3D TextureCoordinate3D / 4D
  const auto& texPoints = strq.present ? strq.st : texCoordPoints(node, texKind);
  if (strq.present) texKind = TexSource::points;
  const bool haveColor = colors.present() && !colors.empty();
  const bool haveNormal = node.sfnode("normal") != nullptr && !normals.empty();
  const bool haveTex = texKind == TexSource::points && !texPoints.empty();
  const std::vector<glm::vec2>* tex1 = haveTex ? secondTexCoordPoints(node) : nullptr;
  const std::size_t n = faces.corners.size();
  if (tex1 != nullptr) soup.texCoords1.reserve(n);
  if (haveColor) soup.colors.reserve(n);
  if (haveNormal) soup.normals.reserve(n);
  if (haveTex) soup.texCoords.reserve(n);

  auto missing = [](const char* what, std::size_t i, std::size_t size) {
    return std::string(what) + " has no entry " + std::to_string(i) + " (" + std::to_string(size) +
           " values)";
  };
  for (std::size_t f = 0; f < faces.kept(); ++f) {
    const std::size_t face = faces.number(f);
    for (std::uint32_t c = faces.faceStart[f]; c < faces.faceStart[f + 1]; ++c) {
      const std::size_t v = faces.corners[c];
      if (haveColor) {
        const std::size_t k = colorPerVertex ? v : face;
        if (k >= colors.size()) log.addLazy([&] { return missing("color", k, colors.size()); });
        soup.colors.push_back(k < colors.size() ? colors[k] : kWhite);
      }
      if (haveNormal) {
        const std::size_t k = normalPerVertex ? v : face;
        if (k >= normals.size()) log.addLazy([&] { return missing("normal", k, normals.size()); });
        // A missing normal (NaN) is generated from the geometry instead.
        soup.normals.push_back(
            k < normals.size() ? normals[k] : glm::vec3(std::numeric_limits<float>::quiet_NaN()));
      }
      if (haveTex) {
        if (v >= texPoints.size())
          log.addLazy([&] { return missing("texCoord", v, texPoints.size()); });
        addTexCorner(soup, texPoints, strq, tex1, v);
      }
    }
  }
  soup.corners = std::move(faces.corners);
  soup.faceStart = std::move(faces.faceStart);
  if (texKind != TexSource::generated && !haveTex) defaultTexCoords(soup);
  return buildPolygonMesh(soup);
}

/// Calls `run(begin, length)` for each run of a count field (fanCount, stripCount,
/// vertexCount) over `total` consecutive vertices: counts below `minimum` are reported
/// and skip their vertices (a negative one skips none), counts past the end are cut short
/// and reported. Time is linear in the counts' array.
template <class F>
void forEachRun(const std::vector<std::int32_t>& counts, std::size_t total, int minimum,
                const char* what, ProblemLog& log, F&& run) {
  std::size_t next = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) {
    const std::int32_t c = counts[i];
    if (c < minimum) {
      log.addLazy([&] {
        return std::string(what) + "[" + std::to_string(i) + "] = " + std::to_string(c) +
               " is less than " + std::to_string(minimum) + "; ignored";
      });
      next += c > 0 ? static_cast<std::size_t>(c) : 0;
      continue;
    }
    const auto length = static_cast<std::size_t>(c);
    if (next > total || length > total - next) {
      log.add(std::string(what) + " asks for more vertices than coord has (" +
              std::to_string(total) + "); cut short");
      if (next < total && total - next >= static_cast<std::size_t>(minimum))
        run(next, total - next);
      return;
    }
    run(next, length);
    next += length;
  }
}

/// Calls `run(begin, length)` for each run of `index` between -1 separators (empty runs
/// are skipped; runs shorter than 3 are reported and ignored).
template <class F>
void forEachIndexRun(const std::vector<std::int32_t>& index, const char* what, ProblemLog& log,
                     F&& run) {
  std::size_t begin = 0;
  for (std::size_t i = 0; i <= index.size(); ++i) {
    if (i < index.size() && index[i] != -1) continue;
    const std::size_t length = i - begin;
    if (length >= 3)
      run(begin, length);
    else if (length > 0)
      log.addLazy([&] {
        return std::string(what) + " has a run of " + std::to_string(length) + " indices at " +
               std::to_string(begin) + "; at least 3 are needed";
      });
    begin = i + 1;
  }
}

/// Strip triangle k of the run starting at `s` in vertex numbers `at(i)`: every other
/// triangle is turned round so that all of them keep the strip's winding.
template <class At>
void stripTriangles(Faces& faces, std::size_t s, std::size_t length, At&& at, const char* what) {
  for (std::size_t k = 0; k + 2 < length; ++k) {
    if (k % 2 == 0)
      faces.triangle(at(s + k), at(s + k + 1), at(s + k + 2), what, s + k);
    else
      faces.triangle(at(s + k + 1), at(s + k), at(s + k + 2), what, s + k);
  }
}

template <class At>
void fanTriangles(Faces& faces, std::size_t s, std::size_t length, At&& at, const char* what) {
  for (std::size_t k = 1; k + 1 < length; ++k)
    faces.triangle(at(s), at(s + k), at(s + k + 1), what, s);
}

}  // namespace

Mesh tessellateIndexedTriangleSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& index = fieldOr<FieldType::MFInt32>(node, "index");
  if (points.empty() || index.empty()) return {};
  // X3D 4.0 clause 11.4 (IndexedTriangleSet): "If the index field does not contain a multiple of
  // three coordinate values, the remaining vertices shall be ignored": defined, not reported.
  Faces faces(points, log);
  for (std::size_t i = 0; i + 3 <= index.size(); i += 3)
    faces.triangle(index[i], index[i + 1], index[i + 2], "index", i);
  return buildComposed(node, log, points, faces);
}

Mesh tessellateIndexedTriangleFanSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& index = fieldOr<FieldType::MFInt32>(node, "index");
  if (points.empty() || index.empty()) return {};
  Faces faces(points, log);
  auto at = [&](std::size_t i) { return std::int64_t{index[i]}; };
  forEachIndexRun(index, "index", log, [&](std::size_t s, std::size_t len) {
    fanTriangles(faces, s, len, at, "index");
  });
  return buildComposed(node, log, points, faces);
}

Mesh tessellateIndexedTriangleStripSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& index = fieldOr<FieldType::MFInt32>(node, "index");
  if (points.empty() || index.empty()) return {};
  Faces faces(points, log);
  auto at = [&](std::size_t i) { return std::int64_t{index[i]}; };
  forEachIndexRun(index, "index", log, [&](std::size_t s, std::size_t len) {
    stripTriangles(faces, s, len, at, "index");
  });
  return buildComposed(node, log, points, faces);
}

Mesh tessellateTriangleSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  if (points.empty()) return {};
  // Clause 11.4 (TriangleSet): vertices after the last whole triangle "shall be ignored"
  // (silently).
  Faces faces(points, log);
  for (std::size_t i = 0; i + 3 <= points.size(); i += 3) {
    const auto v = static_cast<std::int64_t>(i);
    faces.triangle(v, v + 1, v + 2, "coord", i);
  }
  return buildComposed(node, log, points, faces);
}

Mesh tessellateTriangleFanSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& fanCount = fieldOr<FieldType::MFInt32>(node, "fanCount");
  if (points.empty() || fanCount.empty()) return {};
  Faces faces(points, log);
  auto at = [](std::size_t i) { return static_cast<std::int64_t>(i); };
  forEachRun(fanCount, points.size(), 3, "fanCount", log,
             [&](std::size_t s, std::size_t len) { fanTriangles(faces, s, len, at, "coord"); });
  return buildComposed(node, log, points, faces);
}

Mesh tessellateTriangleStripSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& stripCount = fieldOr<FieldType::MFInt32>(node, "stripCount");
  if (points.empty() || stripCount.empty()) return {};
  Faces faces(points, log);
  auto at = [](std::size_t i) { return static_cast<std::int64_t>(i); };
  forEachRun(stripCount, points.size(), 3, "stripCount", log,
             [&](std::size_t s, std::size_t len) { stripTriangles(faces, s, len, at, "coord"); });
  return buildComposed(node, log, points, faces);
}

Mesh tessellateIndexedQuadSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& index = fieldOr<FieldType::MFInt32>(node, "index");
  if (points.empty() || index.empty()) return {};
  // Clause 32.4 (IndexedQuadSet): index values after the last whole quad "shall be ignored"
  // (silently).
  Faces faces(points, log);
  for (std::size_t i = 0; i + 4 <= index.size(); i += 4) {
    // Starting at the second vertex splits the quad along its 1-3 diagonal, as
    // castle-model-viewer does (colours interpolate as in its pictures).
    const std::int64_t v[4] = {index[i + 1], index[i + 2], index[i + 3], index[i]};
    faces.add(v, 4, "index", i);
  }
  return buildComposed(node, log, points, faces);
}

Mesh tessellateQuadSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  if (points.empty()) return {};
  // Clause 32.4 (QuadSet): vertices after the last whole quad "shall be ignored" (silently).
  Faces faces(points, log);
  for (std::size_t i = 0; i + 4 <= points.size(); i += 4) {
    const auto b = static_cast<std::int64_t>(i);
    const std::int64_t v[4] = {b + 1, b + 2, b + 3, b};  // the 1-3 diagonal, as above
    faces.add(v, 4, "coord", i);
  }
  return buildComposed(node, log, points, faces);
}

Mesh tessellateLineSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);
  const auto& vertexCount = fieldOr<FieldType::MFInt32>(node, "vertexCount");
  if (points.empty() || vertexCount.empty()) return {};
  const ColorSource colors(node);  // one colour per vertex (LineSet has no colorPerVertex)
  const bool haveColor = colors.present() && !colors.empty();
  if (haveColor && colors.size() < points.size())
    log.add("color has " + std::to_string(colors.size()) + " colours for " +
            std::to_string(points.size()) + " points; the others are white");

  MeshBuilder b(Primitive::lines, false, haveColor, false);
  if (hasVertexAttributes(node)) b.carryPoints();
  constexpr std::uint32_t kNone = 0xffffffffu;
  forEachRun(
      vertexCount, points.size(), 2, "vertexCount", log, [&](std::size_t s, std::size_t len) {
        std::uint32_t prev = kNone;  // the polyline breaks at a point that is not finite
        for (std::size_t i = s; i < s + len; ++i) {
          if (!finite(points[i])) {
            log.addLazy([&] { return "point " + std::to_string(i) + " is not a finite number"; });
            prev = kNone;
            continue;
          }
          Vertex v;
          v.position = points[i];
          v.point = static_cast<std::uint32_t>(i);
          if (haveColor) v.color = i < colors.size() ? colors[i] : kWhite;
          const std::uint32_t cur = b.add(v);
          if (prev != kNone && prev != cur) {
            b.index(prev);
            b.index(cur);
          }
          prev = cur;
        }
      });
  return b.finish(false);
}

}  // namespace gs::vrml::geometry_detail
