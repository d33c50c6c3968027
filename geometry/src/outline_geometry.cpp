// The filled polygon of an OutlineGroup outline (GhostSpace extension node, paper section
// 1.1; docs/vrml-extensions.md): holes are bridged into the outer loop, then the ring is
// ear-clipped by the IndexedFaceSet triangulator (geometry_polygon.cpp).
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <string>

namespace gs::vrml {

namespace {

using geometry_detail::newellNormal;
using geometry_detail::planeBasis;
using geometry_detail::triangulatePolygon;

double area2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// True when the open segments (p, q) and (a, b) cross at a single interior point.
bool crosses(const glm::dvec2& p, const glm::dvec2& q, const glm::dvec2& a, const glm::dvec2& b) {
  const double d1 = area2(p, q, a), d2 = area2(p, q, b), d3 = area2(a, b, p), d4 = area2(a, b, q);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

/// Joins holes to a counter-clockwise outer ring (indices into `p`); holes must be
/// clockwise. Each hole is linked from its vertex of largest x to the nearest ring vertex
/// that sees it (the segment crosses no edge and enters the ring's corner from inside).
class Bridger {
 public:
  Bridger(const std::vector<glm::dvec2>& p, std::vector<std::uint32_t> outer)
      : p_(p), ring_(std::move(outer)) {}

  void addHoles(std::vector<std::vector<std::uint32_t>> holes) {
    auto maxX = [&](const std::vector<std::uint32_t>& h) {
      double m = -1e300;
      for (std::uint32_t i : h) m = std::max(m, p_[i].x);
      return m;
    };
    std::stable_sort(holes.begin(), holes.end(),
                     [&](const auto& a, const auto& b) { return maxX(a) > maxX(b); });
    pending_ = holes;
    for (std::size_t k = 0; k < holes.size(); ++k) {
      pending_[k].clear();  // the hole being joined is no longer an obstacle list entry
      join(holes[k], k);
    }
  }

  const std::vector<std::uint32_t>& ring() const { return ring_; }

 private:
  void join(const std::vector<std::uint32_t>& hole, std::size_t k) {
    std::size_t mi = 0;
    for (std::size_t i = 1; i < hole.size(); ++i)
      if (p_[hole[i]].x > p_[hole[mi]].x) mi = i;
    const glm::dvec2 m = p_[hole[mi]];
    std::vector<std::size_t> order(ring_.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      const double da = glm::dot(p_[ring_[a]] - m, p_[ring_[a]] - m);
      const double db = glm::dot(p_[ring_[b]] - m, p_[ring_[b]] - m);
      return da != db ? da < db : a < b;
    });
    std::size_t chosen = order.empty() ? 0 : order.front();
    for (std::size_t at : order) {
      if (visible(at, m, hole, k)) {
        chosen = at;
        break;
      }
    }
    // ring[..chosen], hole from m around to m, back to ring[chosen], ring[chosen+1..].
    std::vector<std::uint32_t> next;
    next.reserve(ring_.size() + hole.size() + 2);
    next.insert(next.end(), ring_.begin(), ring_.begin() + static_cast<std::ptrdiff_t>(chosen) + 1);
    for (std::size_t i = 0; i <= hole.size(); ++i) next.push_back(hole[(mi + i) % hole.size()]);
    next.push_back(ring_[chosen]);
    next.insert(next.end(), ring_.begin() + static_cast<std::ptrdiff_t>(chosen) + 1, ring_.end());
    ring_ = std::move(next);
    (void)k;
  }

  bool visible(std::size_t at, const glm::dvec2& m, const std::vector<std::uint32_t>& hole,
               std::size_t k) const {
    const std::size_t n = ring_.size();
    const glm::dvec2 a = p_[ring_[at]];
    if (a == m) return true;
    const glm::dvec2 prev = p_[ring_[(at + n - 1) % n]], next = p_[ring_[(at + 1) % n]];
    const bool inside = area2(prev, a, next) > 0 ? area2(a, m, next) <= 0 && area2(a, prev, m) <= 0
                                                 : area2(a, m, prev) > 0 || area2(a, next, m) > 0;
    if (!inside) return false;
    auto blocked = [&](const std::vector<std::uint32_t>& loop) {
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const glm::dvec2 c = p_[loop[i]], d = p_[loop[(i + 1) % loop.size()]];
        if (c == a || d == a || c == m || d == m) continue;
        if (crosses(a, m, c, d)) return true;
      }
      return false;
    };
    if (blocked(ring_) || blocked(hole)) return false;
    for (std::size_t j = k + 1; j < pending_.size(); ++j)
      if (blocked(pending_[j])) return false;
    return true;
  }

  const std::vector<glm::dvec2>& p_;
  std::vector<std::uint32_t> ring_;
  std::vector<std::vector<std::uint32_t>> pending_;  // holes not joined yet
};

}  // namespace

Mesh triangulateOutline(const std::vector<glm::vec3>& points,
                        const std::vector<std::int32_t>& loopLengths, Diagnostics* diag,
                        const SourceLocation& where) {
  // Loops as index ranges into points.
  std::vector<std::vector<std::uint32_t>> loops;
  if (points.size() >= 0x7fffffffu) return {};
  const auto total = static_cast<std::uint32_t>(points.size());
  if (loopLengths.empty()) {
    loops.emplace_back(total);
    std::iota(loops.back().begin(), loops.back().end(), 0u);
  } else {
    std::uint32_t at = 0;
    bool cut = false;
    for (std::int32_t len : loopLengths) {
      const std::uint32_t want = len > 0 ? static_cast<std::uint32_t>(len) : 0u;
      const std::uint32_t take = std::min(want, total - at);
      cut = cut || take < want;
      loops.emplace_back(take);
      std::iota(loops.back().begin(), loops.back().end(), at);
      at += take;
    }
    if (cut && diag)
      diag->warning(where, "OutlineGroup: outlineLengths count more points than the " +
                               std::to_string(points.size()) + " in outline; loops cut short");
  }
  for (const glm::vec3& q : points)
    if (!geometry_detail::finite(q)) {
      if (diag) diag->warning(where, "OutlineGroup: non-finite outline point; outline not drawn");
      return {};
    }
  if (loops.empty() || loops.front().size() < 3) return {};

  const std::span<const glm::vec3> outerPts(points.data() + loops.front().front(),
                                            loops.front().size());
  const glm::dvec3 normal = newellNormal(outerPts);
  const double len = glm::length(normal);
  if (!(len > 0.0) || !std::isfinite(len)) return {};
  const glm::dvec3 n = normal / len;

  // Project into the plane.
  glm::dvec3 u, v;
  planeBasis(n, u, v);
  const glm::dvec3 o(outerPts[0]);
  std::vector<glm::dvec2> p(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(points[i]) - o;
    p[i] = {glm::dot(d, u), glm::dot(d, v)};
  }

  std::vector<std::vector<std::uint32_t>> holes;
  for (std::size_t l = 1; l < loops.size(); ++l) {
    std::vector<std::uint32_t>& h = loops[l];
    if (h.size() < 3) continue;
    double a = 0.0;
    for (std::size_t i = 0; i < h.size(); ++i) {
      const glm::dvec2 &s = p[h[i]], &t = p[h[(i + 1) % h.size()]];
      a += s.x * t.y - t.x * s.y;
    }
    if (a == 0.0 || !std::isfinite(a)) continue;
    if (a > 0.0) std::reverse(h.begin(), h.end());  // holes turn clockwise
    holes.push_back(std::move(h));
  }

  std::vector<std::uint32_t> ring = std::move(loops.front());
  if (!holes.empty()) {
    Bridger bridger(p, std::move(ring));
    bridger.addHoles(std::move(holes));
    ring = bridger.ring();
  }
  std::vector<glm::vec3> ringPts(ring.size());
  for (std::size_t i = 0; i < ring.size(); ++i) ringPts[i] = points[ring[i]];
  std::vector<std::uint32_t> local;
  triangulatePolygon(ringPts, normal, loops.size() == 1, local);

  Mesh m;
  m.primitive = Primitive::triangles;
  m.solid = false;
  m.positions = points;
  m.normals.assign(points.size(), glm::vec3(n));
  m.indices.reserve(local.size());
  for (std::uint32_t k : local) m.indices.push_back(ring[k]);
  for (const glm::vec3& q : m.positions) m.bounds.extend(q);
  return m;
}

}  // namespace gs::vrml
