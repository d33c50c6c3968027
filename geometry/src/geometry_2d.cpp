// The Geometry2D component (X3D 4.0 clause 14): Arc2D, ArcClose2D, Circle2D, Disk2D,
// Polyline2D, Polypoint2D, Rectangle2D and TriangleSet2D, in the Z = 0 plane of the local
// coordinate system. Arc2D, Circle2D and Polyline2D give lines, Polypoint2D points (also
// Disk2D when innerRadius = outerRadius: a circle drawn with lines); the others triangles,
// counter-clockwise about +Z with normals +Z, not solid unless their `solid` field says
// so (default FALSE). Round shapes use kRoundSegments segments per full turn, angles
// counter-clockwise from +X. Texture coordinates of the filled shapes map the shape's
// bounding box onto the texture square (s from 0 to 1 along X, t along Y); for
// Rectangle2D that is exactly the front face of a Box.
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

namespace gs::vrml::geometry_detail {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

bool solid2D(const Node& node) {
  return node.get<FieldType::SFBool>("solid", false);
}

/// A radius or size that must be > 0: negative or non-finite values are reported and
/// give false; zero gives false silently (nothing to draw).
bool positive(float v, const char* name, ProblemLog& log) {
  if (std::isfinite(v) && v >= 0.0f) return v > 0.0f;
  log.add(std::string(name) + " must be > 0, got " + std::to_string(v) + "; not drawn");
  return false;
}

/// The angle swept counter-clockwise from startAngle to endAngle, in (0, 2 pi]: equal
/// angles (and sweeps of 2 pi or more) give a full circle (X3D clause 14, Arc2D). NaN when an
/// angle is not finite (reported).
double sweepOf(const Node& node, ProblemLog& log) {
  const double start = node.get<FieldType::SFFloat>("startAngle", 0.0f);
  const double end = node.get<FieldType::SFFloat>("endAngle", 1.570796f);
  if (!std::isfinite(start) || !std::isfinite(end)) {
    log.add("startAngle and endAngle must be finite numbers; not drawn");
    return std::nan("");
  }
  double sweep = end - start;
  if (std::abs(sweep) >= kTwoPi || sweep == 0.0) return kTwoPi;
  if (sweep < 0.0) sweep += kTwoPi;
  return sweep;
}

/// Number of segments of an arc sweeping `sweep` radians (at least 1).
int segmentsOf(double sweep) {
  // The tolerance absorbs float angles: a sweep of pi read as 3.14159274 is 16 segments.
  return std::max(1, static_cast<int>(std::ceil(kRoundSegments * sweep / kTwoPi - 1e-4)));
}

/// The n + 1 points of an arc of `radius` from `start` over `sweep` radians in n segments.
std::vector<glm::vec2> arcPoints(float radius, double start, double sweep, int n) {
  std::vector<glm::vec2> pts(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double a = start + sweep * k / n;
    pts[static_cast<std::size_t>(k)] = {static_cast<float>(radius * std::cos(a)),
                                        static_cast<float>(radius * std::sin(a))};
  }
  return pts;
}

/// Lines through `pts` in order (closed: back to the first one), deduplicated.
Mesh polyline(const std::vector<glm::vec2>& pts, bool closed) {
  MeshBuilder b(Primitive::lines, false, false, false);
  b.reserve(pts.size(), 2 * pts.size());
  std::uint32_t first = 0, prev = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    Vertex v;
    v.position = glm::vec3(pts[i], 0.0f);
    const std::uint32_t cur = b.add(v);
    if (i == 0)
      first = cur;
    else if (cur != prev) {
      b.index(prev);
      b.index(cur);
    }
    prev = cur;
  }
  if (closed && pts.size() > 2 && prev != first) {
    b.index(prev);
    b.index(first);
  }
  return b.finish(false);
}

/// Triangles `tris` (index triples into `pts`, counter-clockwise about +Z) with normals
/// +Z and texture coordinates from the bounding box of `pts`.
Mesh filled(const std::vector<glm::vec2>& pts, const std::vector<std::uint32_t>& tris, bool solid) {
  if (tris.empty()) return {};
  glm::vec2 lo = pts[0], hi = pts[0];
  for (const glm::vec2& p : pts) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::vec2 size = hi - lo;
  const glm::vec2 scale(size.x > 0.0f ? 1.0f / size.x : 0.0f, size.y > 0.0f ? 1.0f / size.y : 0.0f);
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve(pts.size(), tris.size());
  std::vector<std::uint32_t> id(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    id[i] = b.add({glm::vec3(pts[i], 0.0f), {0.0f, 0.0f, 1.0f}, {}, (pts[i] - lo) * scale});
  for (std::size_t t = 0; t + 3 <= tris.size(); t += 3)
    b.triangle(id[tris[t]], id[tris[t + 1]], id[tris[t + 2]]);
  return b.finish(solid);
}

/// A triangle fan from pts[0] over pts[1..].
std::vector<std::uint32_t> fan(std::size_t count) {
  std::vector<std::uint32_t> tris;
  for (std::uint32_t k = 1; k + 1 < count; ++k) tris.insert(tris.end(), {0u, k, k + 1});
  return tris;
}

/// The finite points of MFVec2f field `name` (the others are skipped and reported).
std::vector<glm::vec2> finitePoints(const Node& node, const char* name, ProblemLog& log) {
  const auto& in = fieldOr<FieldType::MFVec2f>(node, name);
  std::vector<glm::vec2> out;
  out.reserve(in.size());
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (!finite(in[i])) {
      log.addLazy([&] { return std::string(name) + "[" + std::to_string(i) + "] is not finite"; });
      continue;
    }
    out.push_back(in[i]);
  }
  return out;
}

}  // namespace

Mesh tessellateArc2D(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("radius", 1.0f);
  if (!positive(r, "radius", log)) return {};
  const double sweep = sweepOf(node, log);
  if (std::isnan(sweep)) return {};
  const double start = node.get<FieldType::SFFloat>("startAngle", 0.0f);
  const int n = segmentsOf(sweep);
  std::vector<glm::vec2> pts = arcPoints(r, start, sweep, n);
  if (sweep >= kTwoPi) pts.pop_back();  // a full circle: closed instead
  return polyline(pts, sweep >= kTwoPi);
}

Mesh tessellateCircle2D(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("radius", 1.0f);
  if (!positive(r, "radius", log)) return {};
  std::vector<glm::vec2> pts = arcPoints(r, 0.0, kTwoPi, kRoundSegments);
  pts.pop_back();
  return polyline(pts, true);
}

Mesh tessellateArcClose2D(const Node& node, ProblemLog& log) {
  const float r = node.get<FieldType::SFFloat>("radius", 1.0f);
  if (!positive(r, "radius", log)) return {};
  const double sweep = sweepOf(node, log);
  if (std::isnan(sweep)) return {};
  const double start = node.get<FieldType::SFFloat>("startAngle", 0.0f);
  const std::string closure = node.get<FieldType::SFString>("closureType", std::string("PIE"));
  const bool chord = closure == "CHORD";
  if (!chord && closure != "PIE")
    log.add("closureType \"" + closure + "\" is neither \"PIE\" nor \"CHORD\"; PIE used");
  const int n = segmentsOf(sweep);
  std::vector<glm::vec2> arc = arcPoints(r, start, sweep, n);
  if (sweep >= kTwoPi) arc.pop_back();  // full circle: the last point is the first
  std::vector<glm::vec2> pts;
  if (!chord) pts.emplace_back(0.0f, 0.0f);  // PIE: a fan from the centre
  pts.insert(pts.end(), arc.begin(), arc.end());
  std::vector<std::uint32_t> tris = fan(pts.size());
  if (!chord && sweep >= kTwoPi)  // close the full disk
    tris.insert(tris.end(), {0u, static_cast<std::uint32_t>(pts.size() - 1), 1u});
  return filled(pts, tris, solid2D(node));
}

Mesh tessellateDisk2D(const Node& node, ProblemLog& log) {
  const float inner = node.get<FieldType::SFFloat>("innerRadius", 0.0f);
  const float outer = node.get<FieldType::SFFloat>("outerRadius", 1.0f);
  if (!positive(outer, "outerRadius", log)) return {};
  if (!std::isfinite(inner) || inner < 0.0f || inner > outer) {
    log.add("innerRadius must be in [0, outerRadius], got " + std::to_string(inner) +
            "; not drawn");
    return {};
  }
  constexpr int n = kRoundSegments;
  std::vector<glm::vec2> rim = arcPoints(outer, 0.0, kTwoPi, n);
  rim.pop_back();
  if (inner == outer) return polyline(rim, true);  // X3D: a circle drawn with lines
  std::vector<glm::vec2> pts;
  std::vector<std::uint32_t> tris;
  if (inner == 0.0f) {
    pts.emplace_back(0.0f, 0.0f);
    pts.insert(pts.end(), rim.begin(), rim.end());
    tris = fan(pts.size());
    tris.insert(tris.end(), {0u, static_cast<std::uint32_t>(n), 1u});
  } else {  // an annulus: rim points 0..n-1, inner ring n..2n-1
    pts = rim;
    for (const glm::vec2& p : rim) pts.push_back(p * (inner / outer));
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t k1 = (k + 1) % n;
      tris.insert(tris.end(), {k, k1, n + k1, k, n + k1, n + k});
    }
  }
  return filled(pts, tris, solid2D(node));
}

Mesh tessellatePolyline2D(const Node& node, ProblemLog& log) {
  const auto& in = fieldOr<FieldType::MFVec2f>(node, "lineSegments");
  // The polyline breaks at a point that is not finite.
  MeshBuilder b(Primitive::lines, false, false, false);
  b.reserve(in.size(), 2 * in.size());
  constexpr std::uint32_t kNone = 0xffffffffu;
  std::uint32_t prev = kNone;
  for (std::size_t i = 0; i < in.size(); ++i) {
    if (!finite(in[i])) {
      log.addLazy([&] { return "lineSegments[" + std::to_string(i) + "] is not finite"; });
      prev = kNone;
      continue;
    }
    Vertex v;
    v.position = glm::vec3(in[i], 0.0f);
    const std::uint32_t cur = b.add(v);
    if (prev != kNone && prev != cur) {
      b.index(prev);
      b.index(cur);
    }
    prev = cur;
  }
  return b.finish(false);
}

Mesh tessellatePolypoint2D(const Node& node, ProblemLog& log) {
  const std::vector<glm::vec2> pts = finitePoints(node, "point", log);
  MeshBuilder b(Primitive::points, false, false, false);
  b.reserve(pts.size(), pts.size());
  for (const glm::vec2& p : pts) {
    Vertex v;
    v.position = glm::vec3(p, 0.0f);
    b.index(b.push(v));
  }
  return b.finish(false);
}

Mesh tessellateRectangle2D(const Node& node, ProblemLog& log) {
  const glm::vec2 size = node.get<FieldType::SFVec2f>("size", glm::vec2(2.0f));
  if (!positive(size.x, "size.x", log) || !positive(size.y, "size.y", log)) return {};
  const glm::vec2 h = size * 0.5f;
  const std::vector<glm::vec2> pts = {{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}};
  return filled(pts, {0, 1, 2, 0, 2, 3}, solid2D(node));
}

Mesh tessellateTriangleSet2D(const Node& node, ProblemLog& log) {
  const auto& v = fieldOr<FieldType::MFVec2f>(node, "vertices");
  // X3D 4.0 clause 14.4 (TriangleSet2D): "If the number of vertices is not a multiple of three, the
  // last vertex or last two vertices shall be ignored": defined behaviour, not reported.
  std::vector<glm::vec2> pts;
  std::vector<std::uint32_t> tris;
  pts.reserve(v.size() - v.size() % 3);
  tris.reserve(v.size() - v.size() % 3);
  for (std::size_t i = 0; i + 3 <= v.size(); i += 3) {
    if (!finite(v[i]) || !finite(v[i + 1]) || !finite(v[i + 2])) {
      log.addLazy([&] { return "triangle " + std::to_string(i / 3) + " is not finite"; });
      continue;
    }
    const glm::dvec2 a(v[i]), b(v[i + 1]), c(v[i + 2]);
    const double area2 = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(area2 != 0.0) || !std::isfinite(area2)) continue;  // degenerate: dropped silently
    const auto base = static_cast<std::uint32_t>(pts.size());
    pts.insert(pts.end(), {v[i], v[i + 1], v[i + 2]});
    if (area2 > 0.0)  // counter-clockwise about +Z already
      tris.insert(tris.end(), {base, base + 1, base + 2});
    else
      tris.insert(tris.end(), {base, base + 2, base + 1});
  }
  return filled(pts, tris, solid2D(node));
}

}  // namespace gs::vrml::geometry_detail
