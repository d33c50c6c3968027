// The polygon-soup pipeline shared by IndexedFaceSet, ElevationGrid and Extrusion:
// winding, degenerate-face removal, triangulation, default normals, vertex splitting.
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::vrml::geometry_detail {

namespace {

/// The polygon's interior angle at vertex k (pi for a collinear vertex), used as the
/// weight of the face's normal at that corner.
float cornerAngle(const std::vector<glm::vec3>& poly, std::size_t k) {
  const std::size_t m = poly.size();
  const glm::dvec3 p(poly[k]);
  const glm::dvec3 a = glm::dvec3(poly[(k + m - 1) % m]) - p;
  const glm::dvec3 b = glm::dvec3(poly[(k + 1) % m]) - p;
  const double la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.0) || !(lb > 0.0)) return 0.0f;
  const double c = std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0);
  return static_cast<float>(std::acos(c));
}

/// A given normal that can be normalized (finite, not zero).
bool usableNormal(const glm::vec3& n) {
  if (!finite(n)) return false;
  const double d = glm::dot(glm::dvec3(n), glm::dvec3(n));
  return d > 1e-30 && std::isfinite(d);
}

}  // namespace

void addTexCorner(PolygonSoup& soup, std::span<const glm::vec2> texPoints, const StrqPoints& strq,
                  const std::vector<glm::vec2>* second, std::size_t index) {
  const bool ok = index < texPoints.size() && finite(texPoints[index]);
  soup.texCoords.push_back(ok ? texPoints[index] : glm::vec2(0.0f));
  if (strq.present)
    soup.texCoordsStrq.push_back(
        ok && index < strq.strq.size() ? strq.strq[index] : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
  if (second != nullptr)
    soup.texCoords1.push_back(index < second->size() && finite((*second)[index]) ? (*second)[index]
                                                                                 : glm::vec2(0.0f));
}

PolygonSoup polygonSoupOf(const Node& node, std::span<const glm::vec3> points) {
  PolygonSoup soup;
  soup.points = points;
  soup.ccw = node.get<FieldType::SFBool>("ccw", true);
  soup.convex = node.get<FieldType::SFBool>("convex", true);
  soup.solid = node.get<FieldType::SFBool>("solid", true);
  // SFFloat, but SFDouble in GeoElevationGrid (X3D 4.0 clause 25.4.3).
  soup.creaseAngle = node.get<FieldType::SFFloat>(
      "creaseAngle", static_cast<float>(node.get<FieldType::SFDouble>("creaseAngle", 0.0)));
  soup.carryPoints = hasVertexAttributes(node);
  return soup;
}

Mesh buildPolygonMesh(const PolygonSoup& s) {
  const std::size_t faces = s.faceCount();
  const bool haveColors = !s.colors.empty();
  const bool haveTex = !s.texCoords.empty();

  std::vector<std::uint32_t> kept;       // corner ids of usable faces, in output winding
  std::vector<std::uint32_t> keptPoint;  // their point index
  std::vector<std::uint32_t> keptFace;   // their face
  std::vector<float> keptWeight;         // the face's angle at the corner
  std::vector<glm::vec3> faceNormal(faces, glm::vec3(0.0f));
  std::vector<std::uint32_t> tris;  // indices into kept, 3 per triangle
  kept.reserve(s.corners.size());
  keptPoint.reserve(s.corners.size());
  keptFace.reserve(s.corners.size());
  keptWeight.reserve(s.corners.size());

  std::vector<glm::vec3> poly;
  std::vector<std::uint32_t> polyCorners, local;
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t b = s.faceStart[f], e = s.faceStart[f + 1];
    poly.clear();
    polyCorners.clear();
    for (std::uint32_t t = 0; t < e - b; ++t) {
      const std::uint32_t c = s.ccw ? b + t : e - 1 - t;  // ccw FALSE: reverse the winding
      const glm::vec3& p = s.points[s.corners[c]];
      if (!poly.empty() && p == poly.back()) continue;  // repeated point
      poly.push_back(p);
      polyCorners.push_back(c);
    }
    while (poly.size() > 1 && poly.back() == poly.front()) {
      poly.pop_back();
      polyCorners.pop_back();
    }
    if (poly.size() < 3) continue;  // fewer than 3 distinct points

    glm::vec3 lo = poly[0], hi = poly[0];
    for (const glm::vec3& p : poly) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::dvec3 ext = glm::dvec3(hi) - glm::dvec3(lo);
    const double extent = std::max({ext.x, ext.y, ext.z});
    const glm::dvec3 nn = newellNormal(poly);
    const double len = glm::length(nn);
    if (!(len > extent * extent * 1e-10) || !std::isfinite(len)) continue;  // zero area
    const glm::dvec3 unit = nn / len;
    faceNormal[f] = glm::vec3(unit);

    local.clear();
    if (poly.size() == 3)
      local = {0, 1, 2};  // counterclockwise about its own Newell normal
    else                  // the fan starts at the face's first corner, reversed or not (ccw FALSE)
      triangulatePolygon(poly, unit, s.convex, local, s.ccw ? 0 : poly.size() - 1);
    if (local.empty()) continue;
    const auto base = static_cast<std::uint32_t>(kept.size());
    for (std::size_t k = 0; k < poly.size(); ++k) {
      kept.push_back(polyCorners[k]);
      keptPoint.push_back(s.corners[polyCorners[k]]);
      keptFace.push_back(static_cast<std::uint32_t>(f));
      keptWeight.push_back(cornerAngle(poly, k));
    }
    for (std::uint32_t i : local) tris.push_back(base + i);
  }

  // Normals: the node's own where usable, else generated with creaseAngle.
  bool needGenerated = s.normals.empty();
  if (!needGenerated) {
    for (std::uint32_t c : kept) {
      if (!usableNormal(s.normals[c])) {
        needGenerated = true;
        break;
      }
    }
  }
  std::vector<glm::vec3> generated;
  if (needGenerated) {
    CornerSet cs;
    cs.point = keptPoint;
    cs.face = keptFace;
    cs.weight = keptWeight;
    cs.faceNormal = faceNormal;
    cs.pointCount = s.points.size();
    generated = creaseNormals(cs, s.creaseAngle);
  }

  MeshBuilder builder(Primitive::triangles, true, haveColors, haveTex);
  const bool haveTex1 = haveTex && s.texCoords1.size() == s.texCoords.size();
  if (haveTex1) builder.carrySecondTexCoords();
  const bool haveStrq = haveTex && s.texCoordsStrq.size() == s.texCoords.size();
  if (haveStrq) builder.carryStrqTexCoords();
  if (s.carryPoints) builder.carryPoints();
  builder.reserve(0, tris.size());
  // Output vertices are found through a short chain per shared point (better locality
  // than one big hash table); past kMaxChain vertices at one point, new ones are simply
  // appended.
  constexpr std::uint32_t kNone = 0xffffffffu;
  constexpr int kMaxChain = 16;
  std::vector<std::uint32_t> vertexOf(kept.size(), kNone);
  std::vector<std::uint32_t> head(s.points.size(), kNone), chain;
  chain.reserve(kept.size());
  for (std::uint32_t k : tris) {
    if (vertexOf[k] == kNone) {
      const std::uint32_t c = kept[k], p = keptPoint[k];
      Vertex v;
      v.position = s.points[p];
      v.point = p;
      if (!s.normals.empty() && usableNormal(s.normals[c]))
        v.normal = glm::vec3(glm::normalize(glm::dvec3(s.normals[c])));
      else
        v.normal = generated[k];
      if (haveColors) v.color = s.colors[c];
      if (haveTex && finite(s.texCoords[c])) v.texCoord = s.texCoords[c];
      if (haveTex1 && finite(s.texCoords1[c])) v.texCoord1 = s.texCoords1[c];
      if (haveStrq) v.texCoordStrq = s.texCoordsStrq[c];
      std::uint32_t found = kNone;
      int steps = 0;
      for (std::uint32_t i = head[p]; i != kNone && steps < kMaxChain; i = chain[i], ++steps) {
        if (builder.sameAsStored(i, v)) {
          found = i;
          break;
        }
      }
      if (found == kNone) {
        found = builder.push(v);
        chain.push_back(head[p]);
        head[p] = found;
      }
      vertexOf[k] = found;
    }
    builder.index(vertexOf[k]);
  }
  return builder.finish(s.solid);
}

}  // namespace gs::vrml::geometry_detail
