// X3D's NURBS component (ISO/IEC 19775-1 X3D 4.0 clause 27): NurbsCurve as a line strip,
// NurbsPatchSurface and NurbsTrimmedSurface as a grid of triangles, evaluated as rational
// B-splines (L. Piegl, W. Tiller, "The NURBS Book", 2nd ed., algorithms A2.1 FindSpan and
// A2.2 BasisFuns, equation 4.15 for surfaces).
//
// - Knots: the node's when there are dimension + order of them, non-decreasing; otherwise
//   (and when absent) the uniform clamped vector 0 (order times), 1, 2, ..., n - order + 1
//   (order times), with a warning when some were given.
// - Weights: the node's when there is one per control point and all are > 0; otherwise
//   1 (a warning when some were given).
// - Tessellation (27.2.3): t > 0 gives t segments, t < 0 gives -t times the control
//   points, 0 gives 2 x the control points (a browser's choice; castle-model-viewer's).
// - Surfaces: texture coordinates are the parameters scaled to [0, 1] (the clause's
//   default), or a TextureCoordinate's points interpolated bilinearly over the grid (one
//   per control point); normals come from the grid (central differences), pointing as
//   u x v. NurbsTrimmedSurface's trimming contours are not applied (a warning).
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace gs::vrml::geometry_detail {

namespace {

/// The most segments one direction is cut into, and the most control points a direction
/// may have (bounds for untrusted files).
constexpr int kMaxNurbsSegments = 1024;
constexpr int kMaxNurbsControlPoints = 1 << 16;

/// The control points of `node`'s controlPoint field: Coordinate or CoordinateDouble.
std::vector<glm::dvec3> nurbsControlPoints(const Node& node) {
  std::vector<glm::dvec3> out;
  const NodePtr& c = node.sfnode("controlPoint");
  if (!c || c->unresolved) return out;
  if (const FieldValue* f = c->field("point"); f != nullptr) {
    if (f->type() == FieldType::MFVec3f)
      for (const glm::vec3& p : f->get<FieldType::MFVec3f>()) out.emplace_back(p);
    else if (f->type() == FieldType::MFVec3d)
      for (const glm::dvec3& p : f->get<FieldType::MFVec3d>()) out.push_back(p);
  }
  return out;
}

/// An MFDouble field (or MFFloat, as some files write it) as doubles.
std::vector<double> nurbsDoubles(const Node& node, FieldName name) {
  std::vector<double> out;
  if (const FieldValue* f = node.field(name); f != nullptr) {
    if (f->type() == FieldType::MFDouble) {
      const auto& v = f->get<FieldType::MFDouble>();
      out.assign(v.begin(), v.end());
    } else if (f->type() == FieldType::MFFloat) {
      const auto& v = f->get<FieldType::MFFloat>();
      out.assign(v.begin(), v.end());
    }
  }
  return out;
}

/// One direction of a B-spline: its knots, order and control point count.
struct BSplineAxis {
  std::vector<double> knots;
  int order = 3;
  int count = 0;

  double start() const { return knots[static_cast<std::size_t>(order - 1)]; }
  double end() const { return knots[static_cast<std::size_t>(count)]; }

  /// A2.1: the span k with knots[k] <= u < knots[k + 1] (the last one at the end).
  int span(double u) const {
    const int p = order - 1;
    if (u >= end()) {
      int k = count - 1;
      while (k > p && knots[static_cast<std::size_t>(k)] >= end()) --k;
      return k;
    }
    int lo = p, hi = count;
    while (hi - lo > 1) {
      const int mid = (lo + hi) / 2;
      if (u < knots[static_cast<std::size_t>(mid)])
        hi = mid;
      else
        lo = mid;
    }
    return lo;
  }

  /// A2.2: the order non-zero basis functions at u, N[span - p .. span].
  void basis(int k, double u, std::vector<double>& n) const {
    const int p = order - 1;
    n.assign(static_cast<std::size_t>(order), 0.0);
    std::vector<double> left(static_cast<std::size_t>(order)),
        right(static_cast<std::size_t>(order));
    n[0] = 1.0;
    for (int j = 1; j <= p; ++j) {
      left[static_cast<std::size_t>(j)] = u - knots[static_cast<std::size_t>(k + 1 - j)];
      right[static_cast<std::size_t>(j)] = knots[static_cast<std::size_t>(k + j)] - u;
      double saved = 0.0;
      for (int r = 0; r < j; ++r) {
        const double denominator =
            right[static_cast<std::size_t>(r + 1)] + left[static_cast<std::size_t>(j - r)];
        const double t = denominator != 0.0 ? n[static_cast<std::size_t>(r)] / denominator : 0.0;
        n[static_cast<std::size_t>(r)] = saved + right[static_cast<std::size_t>(r + 1)] * t;
        saved = left[static_cast<std::size_t>(j - r)] * t;
      }
      n[static_cast<std::size_t>(j)] = saved;
    }
  }
};

/// The axis of `count` control points of order `order` with knots `given` (checked).
BSplineAxis nurbsAxis(int count, int order, const std::vector<double>& given, const char* what,
                      ProblemLog& log) {
  BSplineAxis a;
  a.count = count;
  a.order = std::clamp(order, 2, std::max(2, count));
  const std::size_t need = static_cast<std::size_t>(count + a.order);
  bool ok = given.size() == need;
  for (std::size_t i = 1; ok && i < given.size(); ++i)
    ok = std::isfinite(given[i]) && given[i] >= given[i - 1];
  ok = ok && given[static_cast<std::size_t>(a.order - 1)] < given[static_cast<std::size_t>(count)];
  if (ok) {
    a.knots = given;
    return a;
  }
  if (!given.empty())
    log.addLazy([&] {
      return std::string(what) + " has " + std::to_string(given.size()) + " values, not the " +
             std::to_string(need) +
             " non-decreasing ones the control points and order ask for: uniform knots used";
    });
  for (int i = 0; i < count + a.order; ++i)
    a.knots.push_back(static_cast<double>(std::clamp(i - a.order + 1, 0, count - a.order + 1)));
  return a;
}

int nurbsSegments(int tessellation, int count) {
  const int t = tessellation > 0   ? tessellation
                : tessellation < 0 ? -tessellation * count
                                   : 2 * count;
  return std::clamp(t, 1, kMaxNurbsSegments);
}

/// The weights of `count` control points (1 when not one per point, all > 0).
std::vector<double> nurbsWeights(const Node& node, std::size_t count, ProblemLog& log) {
  std::vector<double> w = nurbsDoubles(node, "weight");
  const bool ok = w.size() == count && std::all_of(w.begin(), w.end(), [](double x) {
                    return std::isfinite(x) && x > 0;
                  });
  if (ok) return w;
  if (!w.empty())
    log.addLazy([&] {
      return "weight has " + std::to_string(w.size()) + " values for " + std::to_string(count) +
             " control points (or one is not > 0): weights of 1 used";
    });
  return std::vector<double>(count, 1.0);
}

}  // namespace

Mesh tessellateNurbsCurve(const Node& node, ProblemLog& log) {
  const std::vector<glm::dvec3> points = nurbsControlPoints(node);
  const int n = static_cast<int>(points.size());
  if (n < 2 || n > kMaxNurbsControlPoints) return {};
  const BSplineAxis axis = nurbsAxis(n, node.get<FieldType::SFInt32>("order", 3),
                                     nurbsDoubles(node, "knot"), "knot", log);
  const std::vector<double> w = nurbsWeights(node, points.size(), log);
  const int segments = nurbsSegments(node.get<FieldType::SFInt32>("tessellation", 0), n);
  MeshBuilder b(Primitive::lines, false, false, false);
  b.reserve(static_cast<std::size_t>(segments) + 1, 2 * static_cast<std::size_t>(segments));
  std::vector<double> basis;
  for (int s = 0; s <= segments; ++s) {
    const double u = axis.start() + (axis.end() - axis.start()) * s / segments;
    const int k = axis.span(u);
    axis.basis(k, u, basis);
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (int r = 0; r < axis.order; ++r) {
      const auto i = static_cast<std::size_t>(k - axis.order + 1 + r);
      const double c = basis[static_cast<std::size_t>(r)] * w[i];
      sum += c * points[i];
      weight += c;
    }
    Vertex v;
    v.position = glm::vec3(weight != 0.0 ? sum / weight : points.front());
    const std::uint32_t index = b.push(v);
    if (s > 0) {
      b.index(index - 1);
      b.index(index);
    }
  }
  return b.finish(false);
}

Mesh tessellateNurbsSurface(const Node& node, ProblemLog& log) {
  const std::vector<glm::dvec3> points = nurbsControlPoints(node);
  const int nu = node.get<FieldType::SFInt32>("uDimension", 0);
  const int nv = node.get<FieldType::SFInt32>("vDimension", 0);
  if (nu < 2 || nv < 2 || nu > kMaxNurbsControlPoints || nv > kMaxNurbsControlPoints) return {};
  const auto count = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  if (points.size() < count) {
    log.add("controlPoint has " + std::to_string(points.size()) + " points, uDimension x " +
            "vDimension asks for " + std::to_string(count));
    return {};
  }
  if (node.typeId() == NodeTypeId::NurbsTrimmedSurface && !node.mfnode("trimmingContour").empty())
    log.add("NurbsTrimmedSurface: trimming contours are not applied (the whole patch is drawn)");
  const BSplineAxis ua = nurbsAxis(nu, node.get<FieldType::SFInt32>("uOrder", 3),
                                   nurbsDoubles(node, "uKnot"), "uKnot", log);
  const BSplineAxis va = nurbsAxis(nv, node.get<FieldType::SFInt32>("vOrder", 3),
                                   nurbsDoubles(node, "vKnot"), "vKnot", log);
  const std::vector<double> w = nurbsWeights(node, count, log);
  const int su = nurbsSegments(node.get<FieldType::SFInt32>("uTessellation", 0), nu);
  const int sv = nurbsSegments(node.get<FieldType::SFInt32>("vTessellation", 0), nv);
  const auto gu = static_cast<std::size_t>(su + 1), gv = static_cast<std::size_t>(sv + 1);

  // The grid of surface points, u fastest.
  std::vector<glm::dvec3> grid(gu * gv);
  std::vector<std::vector<double>> bu(gu), bv(gv);
  std::vector<int> ku(gu), kv(gv);
  for (std::size_t i = 0; i < gu; ++i) {
    const double u = ua.start() + (ua.end() - ua.start()) * static_cast<double>(i) / su;
    ku[i] = ua.span(u);
    ua.basis(ku[i], u, bu[i]);
  }
  for (std::size_t j = 0; j < gv; ++j) {
    const double v = va.start() + (va.end() - va.start()) * static_cast<double>(j) / sv;
    kv[j] = va.span(v);
    va.basis(kv[j], v, bv[j]);
  }
  for (std::size_t j = 0; j < gv; ++j)
    for (std::size_t i = 0; i < gu; ++i) {
      glm::dvec3 sum(0.0);
      double weight = 0.0;
      for (int s = 0; s < va.order; ++s) {
        const auto pj = static_cast<std::size_t>(kv[j] - va.order + 1 + s);
        for (int r = 0; r < ua.order; ++r) {
          const auto pi = static_cast<std::size_t>(ku[i] - ua.order + 1 + r);
          const std::size_t c = pi + pj * static_cast<std::size_t>(nu);
          const double f =
              bu[i][static_cast<std::size_t>(r)] * bv[j][static_cast<std::size_t>(s)] * w[c];
          sum += f * points[c];
          weight += f;
        }
      }
      grid[i + j * gu] = weight != 0.0 ? sum / weight : points.front();
    }

  // Texture coordinates: a TextureCoordinate per control point, bilinear over the
  // parameter grid; else the parameters.
  const NodePtr& tc = node.sfnode("texCoord");
  const std::vector<glm::vec2>* texPoints = nullptr;
  std::vector<glm::vec2> texHeld;
  if (tc && !tc->unresolved && tc->typeId() == NodeTypeId::TextureCoordinate) {
    texHeld = tc->get<FieldType::MFVec2f>("point", std::vector<glm::vec2>{});
    if (texHeld.size() >= count) texPoints = &texHeld;
  }
  const auto texAt = [&](double s, double t) {
    if (texPoints == nullptr) return glm::vec2(static_cast<float>(s), static_cast<float>(t));
    const double x = s * (nu - 1), y = t * (nv - 1);
    const auto x0 = static_cast<std::size_t>(std::min(std::floor(x), double(nu - 2)));
    const auto y0 = static_cast<std::size_t>(std::min(std::floor(y), double(nv - 2)));
    const auto fx = static_cast<float>(x - static_cast<double>(x0));
    const auto fy = static_cast<float>(y - static_cast<double>(y0));
    const auto at = [&](std::size_t a, std::size_t b) {
      return (*texPoints)[a + b * static_cast<std::size_t>(nu)];
    };
    return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                    glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
  };

  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve(gu * gv, 6 * static_cast<std::size_t>(su) * static_cast<std::size_t>(sv));
  for (std::size_t j = 0; j < gv; ++j)
    for (std::size_t i = 0; i < gu; ++i) {
      const glm::dvec3 du =
          grid[std::min(i + 1, gu - 1) + j * gu] - grid[(i > 0 ? i - 1 : 0) + j * gu];
      const glm::dvec3 dv =
          grid[i + std::min(j + 1, gv - 1) * gu] - grid[i + (j > 0 ? j - 1 : 0) * gu];
      glm::dvec3 n = glm::cross(du, dv);
      const double len = glm::length(n);
      Vertex v;
      v.position = glm::vec3(grid[i + j * gu]);
      v.normal = len > 0.0 ? glm::vec3(n / len) : glm::vec3(0.0f, 0.0f, 1.0f);
      v.texCoord = texAt(static_cast<double>(i) / su, static_cast<double>(j) / sv);
      b.push(v);
    }
  for (std::size_t j = 0; j + 1 < gv; ++j)
    for (std::size_t i = 0; i + 1 < gu; ++i) {
      const auto a = static_cast<std::uint32_t>(i + j * gu);
      const auto c = static_cast<std::uint32_t>(i + (j + 1) * gu);
      b.triangle(a, a + 1, c + 1);
      b.triangle(a, c + 1, c);
    }
  return b.finish(node.get<FieldType::SFBool>("solid", true));
}

}  // namespace gs::vrml::geometry_detail
