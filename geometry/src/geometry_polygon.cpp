// Polygon triangulation for IndexedFaceSet, ElevationGrid and Extrusion (clause 6.23:
// "convex FALSE" polygons must be split by the browser). Each polygon is projected onto
// its best-fit plane (Newell normal) and ear-clipped in double precision.
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::vrml::geometry_detail {

glm::dvec3 newellNormal(std::span<const glm::vec3> pts) {
  glm::dvec3 n(0.0);
  if (pts.size() < 3) return n;
  const glm::dvec3 o(pts[0]);  // subtracting a vertex keeps precision far from the origin
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec3 a = glm::dvec3(pts[i]) - o;
    const glm::dvec3 b = glm::dvec3(pts[(i + 1) % pts.size()]) - o;
    n.x += (a.y - b.y) * (a.z + b.z);
    n.y += (a.z - b.z) * (a.x + b.x);
    n.z += (a.x - b.x) * (a.y + b.y);
  }
  return n;
}

namespace {

/// Twice the signed area of triangle (a, b, c); positive when counterclockwise.
double area2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// A uniform grid over the polygon's points, to find the points inside a candidate ear
/// without scanning the whole ring (large polygons only).
class PointGrid {
 public:
  PointGrid(const std::vector<glm::dvec2>& p, glm::dvec2 lo, glm::dvec2 hi) : lo_(lo) {
    const double cells = std::sqrt(static_cast<double>(p.size()) / 2.0);
    side_ = std::clamp(static_cast<int>(cells), 1, 1024);
    const glm::dvec2 ext = glm::max(hi - lo, glm::dvec2(1e-300));
    scale_ = glm::dvec2(side_) / ext;
    start_.assign(static_cast<std::size_t>(side_) * static_cast<std::size_t>(side_) + 1, 0);
    for (const glm::dvec2& q : p) ++start_[cellOf(q) + 1];
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    items_.resize(p.size());
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t i = 0; i < p.size(); ++i) items_[fill[cellOf(p[i])]++] = i;
  }

  /// Calls f(index) for every point in the cells overlapping [lo, hi]; stops and returns
  /// true as soon as f returns true.
  template <class F>
  bool any(glm::dvec2 lo, glm::dvec2 hi, F&& f) const {
    const int x0 = coord(lo.x, 0), x1 = coord(hi.x, 0), y0 = coord(lo.y, 1), y1 = coord(hi.y, 1);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::size_t c = static_cast<std::size_t>(y) * static_cast<std::size_t>(side_) +
                              static_cast<std::size_t>(x);
        for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k)
          if (f(items_[k])) return true;
      }
    }
    return false;
  }

 private:
  int coord(double v, int axis) const {
    const double t = (v - lo_[axis]) * scale_[axis];
    if (!(t > 0.0)) return 0;
    return std::min(static_cast<int>(t), side_ - 1);
  }
  std::size_t cellOf(const glm::dvec2& q) const {
    return static_cast<std::size_t>(coord(q.y, 1)) * static_cast<std::size_t>(side_) +
           static_cast<std::size_t>(coord(q.x, 0));
  }

  glm::dvec2 lo_;
  glm::dvec2 scale_{1.0};
  int side_ = 1;
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> items_;
};

/// Ear clipping on a ring of distinct consecutive 2D points, counterclockwise overall.
class EarClipper {
 public:
  EarClipper(std::vector<glm::dvec2> p, double eps) : p_(std::move(p)), eps_(eps) {
    const auto m = static_cast<std::uint32_t>(p_.size());
    prev_.resize(m);
    next_.resize(m);
    for (std::uint32_t i = 0; i < m; ++i) {
      prev_[i] = (i + m - 1) % m;
      next_[i] = (i + 1) % m;
    }
    active_.assign(m, 1);
    remaining_ = m;
  }

  /// True when every turn is a left turn (or straight ahead) and the turns add up to one
  /// full revolution: a convex, simple polygon.
  bool convex() const {
    const std::size_t m = p_.size();
    double turn = 0.0;
    for (std::size_t k = 0; k < m; ++k) {
      const glm::dvec2 e1 = p_[k] - p_[(k + m - 1) % m];
      const glm::dvec2 e2 = p_[(k + 1) % m] - p_[k];
      const double cr = e1.x * e2.y - e1.y * e2.x;
      if (cr < -eps_) return false;
      turn += std::atan2(cr, glm::dot(e1, e2));
    }
    return std::abs(turn - 2.0 * std::numbers::pi) < 1e-3;
  }

  /// Convex polygon: clip strictly convex vertices in turn starting after `apex` (a fan
  /// around the apex that keeps collinear vertices), with no containment test.
  void clipConvex(std::vector<std::uint32_t>& out, std::uint32_t apex) {
    std::uint32_t cur = next_[apex], stall = 0;
    while (remaining_ >= 3) {
      const std::uint32_t a = prev_[cur], c = next_[cur];
      if (area2(p_[a], p_[cur], p_[c]) > eps_) {
        clip(a, cur, c, out);
        if (remaining_ < 3) break;
        cur = c;
        stall = 0;
      } else {
        cur = c;
        if (++stall >= remaining_) break;  // only collinear vertices remain: no area left
      }
    }
  }

  /// General polygon: ear clipping. Pass 0 accepts ears with no other vertex inside or
  /// on their boundary; when a whole round finds none, pass 1 tolerates vertices on the
  /// boundary; when that fails too the largest convex corner is cut regardless
  /// (self-intersecting input), and the loop stops when no corner has positive area.
  void clipGeneral(std::vector<std::uint32_t>& out, std::uint32_t apex) {
    if (p_.size() > 64) buildGrid();
    std::uint32_t cur = next_[apex], stall = 0;
    int pass = 0;
    while (remaining_ > 3) {
      const std::uint32_t a = prev_[cur], c = next_[cur];
      if (area2(p_[a], p_[cur], p_[c]) > eps_ && !blocked(a, cur, c, pass == 0)) {
        clip(a, cur, c, out);
        cur = c;
        stall = 0;
        pass = 0;
        continue;
      }
      cur = c;
      if (++stall < remaining_) continue;
      stall = 0;
      if (pass == 0) {
        pass = 1;
        continue;
      }
      // Nothing clean left: cut the convex corner of largest area, if there is one.
      std::uint32_t best = cur;
      double bestArea = eps_;
      std::uint32_t k = cur;
      for (std::uint32_t i = 0; i < remaining_; ++i, k = next_[k]) {
        const double ar = area2(p_[prev_[k]], p_[k], p_[next_[k]]);
        if (ar > bestArea) bestArea = ar, best = k;
      }
      if (bestArea <= eps_) return;  // what remains has no area
      cur = next_[best];
      clip(prev_[best], best, next_[best], out);
      pass = 0;
    }
    if (remaining_ == 3) {
      const std::uint32_t a = prev_[cur], c = next_[cur];
      if (area2(p_[a], p_[cur], p_[c]) > eps_) clip(a, cur, c, out);
    }
  }

 private:
  void clip(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::vector<std::uint32_t>& out) {
    out.insert(out.end(), {a, b, c});
    next_[a] = c;
    prev_[c] = a;
    active_[b] = 0;
    --remaining_;
  }

  /// True when some other vertex that is not strictly convex lies inside triangle
  /// (a, b, c) (or on its boundary when `inclusive`). Vertices at the same position as a
  /// corner of the triangle never block (they come from repeated points).
  bool blocked(std::uint32_t a, std::uint32_t b, std::uint32_t c, bool inclusive) const {
    const glm::dvec2 &pa = p_[a], &pb = p_[b], &pc = p_[c];
    auto blocks = [&](std::uint32_t k) {
      if (!active_[k] || k == a || k == b || k == c) return false;
      const glm::dvec2& q = p_[k];
      if (q == pa || q == pb || q == pc) return false;
      if (area2(p_[prev_[k]], q, p_[next_[k]]) > eps_) return false;  // convex: cannot be first
      const double d1 = area2(pa, pb, q), d2 = area2(pb, pc, q), d3 = area2(pc, pa, q);
      return inclusive ? (d1 >= -eps_ && d2 >= -eps_ && d3 >= -eps_)
                       : (d1 > eps_ && d2 > eps_ && d3 > eps_);
    };
    if (grid_.empty()) {
      for (std::uint32_t k = next_[c]; k != a; k = next_[k])
        if (blocks(k)) return true;
      return false;
    }
    const glm::dvec2 lo = glm::min(pa, glm::min(pb, pc)), hi = glm::max(pa, glm::max(pb, pc));
    return grid_.front().any(lo, hi, blocks);
  }

  void buildGrid() {
    glm::dvec2 lo = p_[0], hi = p_[0];
    for (const glm::dvec2& q : p_) lo = glm::min(lo, q), hi = glm::max(hi, q);
    grid_.emplace_back(p_, lo, hi);
  }

  std::vector<glm::dvec2> p_;
  double eps_;
  std::vector<std::uint32_t> prev_, next_;
  std::vector<unsigned char> active_;
  std::uint32_t remaining_ = 0;
  std::vector<PointGrid> grid_;  // empty, or one grid
};

}  // namespace

void triangulatePolygon(std::span<const glm::vec3> pts, const glm::dvec3& normal, bool assumeConvex,
                        std::vector<std::uint32_t>& out, std::size_t fanApex) {
  if (pts.size() < 3 || pts.size() > 0x7fffffffu) return;
  const double len = glm::length(normal);
  if (!(len > 0.0) || !std::isfinite(len)) return;
  const glm::dvec3 n = normal / len;
  glm::dvec3 u, v;
  planeBasis(n, u, v);
  const glm::dvec3 o(pts[0]);

  // Project, dropping consecutive repeated points (and a closing repeat of the first).
  std::vector<glm::dvec2> p;
  std::vector<std::uint32_t> original;
  p.reserve(pts.size());
  original.reserve(pts.size());
  glm::dvec2 lo(1e300), hi(-1e300);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const glm::dvec3 d = glm::dvec3(pts[i]) - o;
    const glm::dvec2 q(glm::dot(d, u), glm::dot(d, v));
    if (!p.empty() && q == p.back()) continue;
    p.push_back(q);
    original.push_back(static_cast<std::uint32_t>(i));
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  while (p.size() > 1 && p.back() == p.front()) {
    p.pop_back();
    original.pop_back();
  }
  if (p.size() < 3) return;
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  if (!(extent > 0.0) || !std::isfinite(extent)) return;
  const double eps = extent * extent * 1e-12;

  // The apex among the kept points: the first kept one at or after pts[fanApex].
  const auto apex =
      static_cast<std::uint32_t>(std::lower_bound(original.begin(), original.end(), fanApex) -
                                 original.begin()) %
      static_cast<std::uint32_t>(original.size());
  std::vector<std::uint32_t> local;
  local.reserve(3 * (p.size() - 2));
  EarClipper clipper(std::move(p), eps);
  if (assumeConvex && clipper.convex())
    clipper.clipConvex(local, apex);
  else
    clipper.clipGeneral(local, apex);
  for (std::uint32_t k : local) out.push_back(original[k]);
}

}  // namespace gs::vrml::geometry_detail
