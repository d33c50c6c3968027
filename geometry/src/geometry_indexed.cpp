// IndexedFaceSet (6.23), IndexedLineSet (6.24) and PointSet (6.36). Indices are checked
// one by one: a polygon with a bad coordinate index is dropped, a bad colour, normal or
// texture coordinate index gives white, a generated normal or (0, 0), and the first
// problem is reported once per node.
#include "geometry_internal.hpp"

#include <algorithm>
#include <limits>

namespace gs::vrml::geometry_detail {

namespace {

constexpr glm::vec4 kWhite(1.0f);
constexpr std::int32_t kMissing = std::numeric_limits<std::int32_t>::min();

/// The entry `i` of `index`, or kMissing when the array is too short.
std::int32_t at(const std::vector<std::int32_t>& index, std::size_t i) {
  return i < index.size() ? index[i] : kMissing;
}

/// An index into an array of `size` entries, resolved the clause-6.23 way: per vertex it
/// is index[corner] (or coordIndex[corner] when `index` is empty), per face index[face]
/// (or the face number when `index` is empty).
std::int32_t resolve(bool perVertex, const std::vector<std::int32_t>& index,
                     const std::vector<std::int32_t>& coordIndex, std::size_t corner,
                     std::size_t face) {
  if (perVertex) return index.empty() ? coordIndex[corner] : at(index, corner);
  if (index.empty())
    return face <= static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())
               ? static_cast<std::int32_t>(face)
               : kMissing;
  return at(index, face);
}

bool inRange(std::int32_t i, std::size_t size) {
  return i >= 0 && static_cast<std::size_t>(i) < size;
}

std::string badIndex(const char* what, std::size_t pos, std::int32_t value, std::size_t size) {
  if (value == kMissing)
    return std::string(what) + " has no entry " + std::to_string(pos) + " (array too short)";
  return std::string(what) + "[" + std::to_string(pos) + "] = " + std::to_string(value) +
         " is out of range (" + std::to_string(size) + " values)";
}

}  // namespace

void defaultTexCoords(PolygonSoup& soup) {
  Bounds box;
  for (std::uint32_t p : soup.corners) box.extend(soup.points[p]);
  if (box.empty()) return;
  const glm::vec3 size = box.size();
  int axis[3] = {0, 1, 2};
  std::stable_sort(axis, axis + 3, [&](int a, int b) { return size[a] > size[b]; });
  const int sAxis = axis[0], tAxis = axis[1];
  const float len = size[sAxis] > 0.0f ? size[sAxis] : 1.0f;
  soup.texCoords.reserve(soup.corners.size());
  for (std::uint32_t p : soup.corners) {
    const glm::vec3 d = soup.points[p] - box.min;
    soup.texCoords.emplace_back(d[sAxis] / len, d[tAxis] / len);
  }
}

Mesh tessellateIndexedFaceSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);  // or CoordinateDouble
  const auto& coordIndex = fieldOr<FieldType::MFInt32>(node, "coordIndex");
  if (points.empty() || coordIndex.empty()) return {};

  const ColorSource colors(node);  // Color or X3D ColorRGBA
  const auto& colorIndex = fieldOr<FieldType::MFInt32>(node, "colorIndex");
  const bool colorPerVertex = node.get<FieldType::SFBool>("colorPerVertex", true);
  const auto& normals = childArray<FieldType::MFVec3f>(node, "normal", "vector");
  const auto& normalIndex = fieldOr<FieldType::MFInt32>(node, "normalIndex");
  const bool normalPerVertex = node.get<FieldType::SFBool>("normalPerVertex", true);
  TexSource texKind = TexSource::none;
  const StrqPoints strq = strqTexCoordPoints(node);  // X3D TextureCoordinate3D / 4D
  const auto& texPoints = strq.present ? strq.st : texCoordPoints(node, texKind);
  if (strq.present) texKind = TexSource::points;
  const auto& texIndex = fieldOr<FieldType::MFInt32>(node, "texCoordIndex");
  const bool haveColor = colors.present();
  const bool haveNormal = node.sfnode("normal") != nullptr;
  const bool haveTex = texKind == TexSource::points;
  const std::vector<glm::vec2>* tex1 = haveTex ? secondTexCoordPoints(node) : nullptr;

  PolygonSoup soup = polygonSoupOf(node, points);
  soup.corners.reserve(coordIndex.size());
  if (haveColor) soup.colors.reserve(coordIndex.size());
  if (haveNormal) soup.normals.reserve(coordIndex.size());
  if (haveTex) soup.texCoords.reserve(coordIndex.size());

  auto addCorner = [&](std::size_t i, std::size_t face) {
    soup.corners.push_back(static_cast<std::uint32_t>(coordIndex[i]));
    if (haveColor) {
      const std::int32_t c = resolve(colorPerVertex, colorIndex, coordIndex, i, face);
      const bool ok = inRange(c, colors.size());
      if (!ok)
        log.addLazy([&] {
          return badIndex(colorPerVertex ? "colorIndex" : "colorIndex (per face)",
                          colorPerVertex ? i : face, c, colors.size());
        });
      soup.colors.push_back(ok ? colors[static_cast<std::size_t>(c)] : kWhite);
    }
    if (haveNormal) {
      const std::int32_t n = resolve(normalPerVertex, normalIndex, coordIndex, i, face);
      const bool ok = inRange(n, normals.size());
      if (!ok)
        log.addLazy([&] {
          return badIndex(normalPerVertex ? "normalIndex" : "normalIndex (per face)",
                          normalPerVertex ? i : face, n, normals.size());
        });
      // A missing normal (NaN) is generated from the geometry instead.
      soup.normals.push_back(ok ? normals[static_cast<std::size_t>(n)]
                                : glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    }
    if (haveTex) {
      const std::int32_t t = texIndex.empty() ? coordIndex[i] : at(texIndex, i);
      const bool ok =
          inRange(t, texPoints.size()) && finite(texPoints[static_cast<std::size_t>(t)]);
      if (!ok) log.addLazy([&] { return badIndex("texCoordIndex", i, t, texPoints.size()); });
      // The second set shares texCoordIndex (X3D 4.0 clause 18.4.3).
      addTexCorner(soup, texPoints, strq, tex1,
                   t >= 0 ? static_cast<std::size_t>(t) : std::numeric_limits<std::size_t>::max());
    }
  };

  // Polygons end at -1 or at the end of coordIndex; empty ones ("-1 -1") are not counted.
  std::size_t face = 0, faceBegin = 0;
  bool bad = false, empty = true;
  for (std::size_t i = 0; i <= coordIndex.size(); ++i) {
    if (i < coordIndex.size() && coordIndex[i] != -1) {
      empty = false;
      const std::int32_t idx = coordIndex[i];
      if (!inRange(idx, points.size())) {
        bad = true;
        log.addLazy([&] { return badIndex("coordIndex", i, idx, points.size()); });
      } else if (!finite(points[static_cast<std::size_t>(idx)])) {
        bad = true;
        log.addLazy([&] { return "point " + std::to_string(idx) + " is not a finite number"; });
      }
      continue;
    }
    if (!empty) {
      if (!bad) {
        for (std::size_t k = faceBegin; k < i; ++k) addCorner(k, face);
        soup.endFace();
      }
      ++face;
    }
    faceBegin = i + 1;
    bad = false;
    empty = true;
  }
  if (haveColor && colors.empty()) soup.colors.clear();
  if (texKind == TexSource::generated) {
    soup.texCoords.clear();  // TextureCoordinateGenerator: computed elsewhere
  } else if (!haveTex || texPoints.empty()) {
    soup.texCoords.clear();
    soup.texCoordsStrq.clear();
    defaultTexCoords(soup);
  }
  return buildPolygonMesh(soup);
}

Mesh tessellateIndexedLineSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);  // or CoordinateDouble
  const auto& coordIndex = fieldOr<FieldType::MFInt32>(node, "coordIndex");
  if (points.empty() || coordIndex.empty()) return {};
  const ColorSource colors(node);  // Color or X3D ColorRGBA
  const auto& colorIndex = fieldOr<FieldType::MFInt32>(node, "colorIndex");
  const bool colorPerVertex = node.get<FieldType::SFBool>("colorPerVertex", true);
  const bool haveColor = colors.present() && !colors.empty();

  MeshBuilder b(Primitive::lines, false, haveColor, false);
  if (hasVertexAttributes(node)) b.carryPoints();
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::uint32_t prev = kNone;  // previous vertex of the current polyline
  std::size_t line = 0;
  bool empty = true;
  for (std::size_t i = 0; i <= coordIndex.size(); ++i) {
    if (i == coordIndex.size() || coordIndex[i] == -1) {  // end of a polyline
      if (!empty) ++line;
      empty = true;
      prev = kNone;
      continue;
    }
    empty = false;
    const std::int32_t idx = coordIndex[i];
    if (!inRange(idx, points.size()) || !finite(points[static_cast<std::size_t>(idx)])) {
      log.addLazy([&] {
        return inRange(idx, points.size()) ? "point " + std::to_string(idx) + " is not finite"
                                           : badIndex("coordIndex", i, idx, points.size());
      });
      prev = kNone;  // the polyline breaks at a bad vertex
      continue;
    }
    Vertex v;
    v.position = points[static_cast<std::size_t>(idx)];
    v.point = static_cast<std::uint32_t>(idx);
    if (haveColor) {
      const std::int32_t c = resolve(colorPerVertex, colorIndex, coordIndex, i, line);
      const bool ok = inRange(c, colors.size());
      if (!ok)
        log.addLazy(
            [&] { return badIndex("colorIndex", colorPerVertex ? i : line, c, colors.size()); });
      v.color = ok ? colors[static_cast<std::size_t>(c)] : kWhite;
    }
    const std::uint32_t cur = b.add(v);
    if (prev != kNone && prev != cur) {
      b.index(prev);
      b.index(cur);
    }
    prev = cur;
  }
  return b.finish(false);
}

Mesh tessellatePointSet(const Node& node, ProblemLog& log) {
  std::vector<glm::vec3> scratch;
  const std::span<const glm::vec3> points = coordPoints(node, scratch);  // or CoordinateDouble
  const ColorSource colors(node);                                        // Color or X3D ColorRGBA
  const bool haveColor = colors.present() && !colors.empty();
  if (haveColor && colors.size() < points.size())
    log.add("Color has " + std::to_string(colors.size()) + " colours for " +
            std::to_string(points.size()) + " points; the others are white");
  MeshBuilder b(Primitive::points, false, haveColor, false);
  if (hasVertexAttributes(node)) b.carryPoints();
  b.reserve(points.size(), points.size());
  bool warnedNaN = false;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!finite(points[i])) {
      if (!warnedNaN) log.add("point " + std::to_string(i) + " is not a finite number");
      warnedNaN = true;
      continue;
    }
    Vertex v;
    v.position = points[i];
    v.point = static_cast<std::uint32_t>(i);
    if (haveColor) v.color = i < colors.size() ? colors[i] : kWhite;
    b.index(b.push(v));
  }
  return b.finish(false);
}

}  // namespace gs::vrml::geometry_detail
