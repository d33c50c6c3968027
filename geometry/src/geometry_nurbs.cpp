// X3D's NURBS component (ISO/IEC 19775-1 X3D 4.0 clause 27): NurbsCurve as a line strip,
// NurbsPatchSurface and NurbsTrimmedSurface as a grid of triangles, evaluated as rational
// B-splines (geometry/nurbs.hpp, shared with the runtime's NURBS interpolators: L. Piegl,
// W. Tiller, "The NURBS Book", 2nd ed., algorithms A2.1 FindSpan and A2.2 BasisFuns,
// equation 4.15 for surfaces).
//
// - Knots: the node's when there are dimension + order of them, non-decreasing; otherwise
//   (and when absent) the uniform clamped vector 0 (order times), 1, 2, ..., n - order + 1
//   (order times), with a warning when some were given.
// - Weights: the node's when there is one per control point and all are > 0; otherwise
//   1 (a warning when some were given).
// - Tessellation (27.2.3): t > 0 gives t segments, t < 0 gives -t times the control
//   points, 0 gives 2 x the control points (a browser's choice; castle-model-viewer's).
// - Surfaces: texture coordinates are the parameters scaled to [0, 1] (the clause's
//   default), a NurbsTextureCoordinate's 2D NURBS surface evaluated at the same fractions
//   of its own parameter range (27.4.10; a warning and the default when its fields do not
//   make a surface), or a TextureCoordinate's points interpolated bilinearly over the grid
//   (one per control point); normals come from the grid (central differences), pointing as
//   u x v.
// - NurbsTrimmedSurface (27.4.9): as X_ITE 15 trims it, each Contour2D's curves joined into
//   one closed polygon of the parameter space (u, v); the part of the patch kept is inside
//   an odd number of contours (the odd winding rule: an outer contour keeps its inside, a
//   contour inside it cuts a hole). Triangles of the grid are kept by their centre (the
//   trimmed edge follows the grid's cells).
#include "geometry/nurbs.hpp"
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace gs::vrml::geometry_detail {

namespace {

using nurbs::Axis;

/// The most segments one direction is cut into.
constexpr int kMaxNurbsSegments = 1024;
constexpr int kMaxNurbsControlPoints = nurbs::kMaxControlPoints;

/// The axis of `count` control points of order `order` with knots `given` (checked; the
/// uniform knots with a warning when they are not right).
Axis nurbsAxis(int count, int order, const std::vector<double>& given, const char* what,
               ProblemLog& log) {
  std::string problem;
  Axis a = nurbs::lenientAxis(count, order, given, what, problem);
  if (!problem.empty()) log.add(problem);
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
  std::vector<double> w = nurbs::doubles(node, "weight");
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

/// The points of the surface of `points` (ua.count x va.count, u fastest) with weights
/// `w` at su + 1 by sv + 1 evenly spaced parameters, u fastest.
std::vector<glm::dvec3> nurbsGrid(const Axis& ua, const Axis& va,
                                  const std::vector<glm::dvec3>& points,
                                  const std::vector<double>& w, int su, int sv) {
  const auto gu = static_cast<std::size_t>(su + 1), gv = static_cast<std::size_t>(sv + 1);
  std::vector<glm::dvec3> grid(gu * gv);
  std::vector<std::vector<double>> bu(gu), bv(gv);
  std::vector<int> ku(gu), kv(gv);
  for (std::size_t i = 0; i < gu; ++i) {
    const double u = ua.at(static_cast<double>(i) / su);
    ku[i] = ua.span(u);
    ua.basis(ku[i], u, bu[i]);
  }
  for (std::size_t j = 0; j < gv; ++j) {
    const double v = va.at(static_cast<double>(j) / sv);
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
          const std::size_t c = pi + pj * static_cast<std::size_t>(ua.count);
          const double f =
              bu[i][static_cast<std::size_t>(r)] * bv[j][static_cast<std::size_t>(s)] * w[c];
          sum += f * points[c];
          weight += f;
        }
      }
      grid[i + j * gu] = weight != 0.0 ? sum / weight : points.front();
    }
  return grid;
}

/// The unit normals of a surface grid (gu x gv points, u fastest): the cross product of
/// the central differences along u and v, wrapping around where a row or column closes on
/// itself (its last point its first), so that a closed surface has no seam. A row or column that
/// collapses to one point (a pole: the tip of a surface of revolution, the centre of a flat cap)
/// has no tangent along it; its points take the mean of the next row's (column's) normals, the
/// surface's normal there, as X_ITE's normals averaged over the faces around a point give it,
/// instead of one made of a zero tangent. A point whose normal is still undefined gets +z.
std::vector<glm::vec3> nurbsGridNormals(const std::vector<glm::dvec3>& grid, std::size_t gu,
                                        std::size_t gv) {
  double extent = 0.0;
  for (const glm::dvec3& p : grid) extent = std::max(extent, glm::length(p - grid.front()));
  // Files write control points to about 6 digits: a pole written as (0, 0.999999, 0) and,
  // times its weight, (0, 0.707106, 0) is one point 1e-6 apart.
  const double tiny = 1e-5 * extent;
  const auto at = [&](std::size_t i, std::size_t j) { return grid[i + j * gu]; };
  // Across a seam where a row (column) closes on itself, the differences wrap around.
  const auto neighbours = [](std::size_t k, std::size_t count, bool closed) {
    if (closed && count > 2 && (k == 0 || k + 1 == count))
      return std::pair{count - 2, std::size_t{1}};
    return std::pair{k > 0 ? k - 1 : 0, std::min(k + 1, count - 1)};
  };
  std::vector<glm::dvec3> n(grid.size());
  std::vector<bool> columnClosed(gu);
  for (std::size_t i = 0; i < gu; ++i)
    columnClosed[i] = glm::length(at(i, gv - 1) - at(i, 0)) <= tiny;
  for (std::size_t j = 0; j < gv; ++j) {
    const bool rowClosed = glm::length(at(gu - 1, j) - at(0, j)) <= tiny;
    for (std::size_t i = 0; i < gu; ++i) {
      const auto [ua, ub] = neighbours(i, gu, rowClosed);
      const auto [va, vb] = neighbours(j, gv, columnClosed[i]);
      n[i + j * gu] = glm::cross(at(ub, j) - at(ua, j), at(i, vb) - at(i, va));
    }
  }
  // Rows whose points coincide (no u tangent), then columns (no v tangent): each takes the
  // mean normal of the nearest row (column) that does not collapse.
  const auto meanOf = [&](std::size_t count, auto&& normal) {
    glm::dvec3 sum(0.0);
    for (std::size_t k = 0; k < count; ++k) {
      const double len = glm::length(normal(k));
      if (len > 0.0) sum += normal(k) / len;
    }
    return sum;
  };
  // A line is a row (`lines` = gv of them, each `length` = gu long) or a column; point k of
  // line l is grid[index(l, k)].
  const auto fillPoles = [&](std::size_t lines, std::size_t length, auto&& index) {
    if (lines < 2) return;
    std::vector<bool> pole(lines, true);
    for (std::size_t l = 0; l < lines; ++l)
      for (std::size_t k = 1; k < length && pole[l]; ++k)
        pole[l] = glm::length(grid[index(l, k)] - grid[index(l, 0)]) <= tiny;
    for (std::size_t l = 0; l < lines; ++l) {
      if (!pole[l]) continue;
      std::size_t next = lines;
      for (std::size_t d = 1; d < lines && next == lines; ++d) {
        if (l + d < lines && !pole[l + d])
          next = l + d;
        else if (l >= d && !pole[l - d])
          next = l - d;
      }
      if (next == lines) return;  // everything collapses: no normal to take
      // A closed ring's last point is its first again: counted once.
      const bool ring =
          length > 2 && glm::length(grid[index(next, length - 1)] - grid[index(next, 0)]) <= tiny;
      const glm::dvec3 mean =
          meanOf(ring ? length - 1 : length, [&](std::size_t k) { return n[index(next, k)]; });
      for (std::size_t k = 0; k < length; ++k) n[index(l, k)] = mean;
    }
  };
  fillPoles(gv, gu, [&](std::size_t j, std::size_t i) { return i + j * gu; });
  fillPoles(gu, gv, [&](std::size_t i, std::size_t j) { return i + j * gu; });
  std::vector<glm::vec3> unit(grid.size());
  for (std::size_t k = 0; k < n.size(); ++k) {
    const double len = glm::length(n[k]);
    unit[k] = len > 0.0 ? glm::vec3(n[k] / len) : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return unit;
}

/// A NurbsTextureCoordinate's (27.4.10) texture coordinates at su + 1 by sv + 1 evenly
/// spaced parameters of its own surface (X_ITE samples it so: the host's parameter range
/// mapped onto the texture surface's), as (s, t, 0), u fastest; empty (a warning) when its
/// fields do not make a surface.
std::vector<glm::dvec3> nurbsTextureGrid(const Node& tc, int su, int sv, ProblemLog& log) {
  const int nu = tc.get<FieldType::SFInt32>("uDimension", 0);
  const int nv = tc.get<FieldType::SFInt32>("vDimension", 0);
  const auto given = tc.get<FieldType::MFVec2f>("controlPoint", std::vector<glm::vec2>{});
  std::string problem;
  std::optional<Axis> ua, va;
  std::optional<std::vector<double>> w;
  if (nu < 1 || nv < 1 ||
      given.size() != static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv))
    problem = "controlPoint has " + std::to_string(given.size()) +
              " points, uDimension x vDimension asks for " + std::to_string(std::max(nu, 0)) +
              " x " + std::to_string(std::max(nv, 0));
  else if (!(ua = nurbs::strictAxis(nu, tc.get<FieldType::SFInt32>("uOrder", 3),
                                    nurbs::doubles(tc, "uKnot"), problem)))
    problem = "u: " + problem;
  else if (!(va = nurbs::strictAxis(nv, tc.get<FieldType::SFInt32>("vOrder", 3),
                                    nurbs::doubles(tc, "vKnot"), problem)))
    problem = "v: " + problem;
  else
    w = nurbs::strictWeights(nurbs::doubles(tc, "weight"), given.size(), problem);
  if (!w) {
    log.add("NurbsTextureCoordinate: " + problem + ": the (u, v) parameters used");
    return {};
  }
  std::vector<glm::dvec3> points;
  points.reserve(given.size());
  for (const glm::vec2& p : given) points.emplace_back(p.x, p.y, 0.0);
  return nurbsGrid(*ua, *va, points, *w, su, sv);
}

}  // namespace

/// A closed curve (27.4.2 `closed` TRUE, its first and last control points and weights
/// the same) made periodic as X_ITE makes it: the order - 2 control points after the first
/// repeated at the end, the knots (the node's when usable, else uniform over [0, 1])
/// continued by the same steps. False (nothing changed) when the curve cannot close.
bool closeCurve(const Node& node, int order, std::vector<glm::dvec3>& points,
                std::vector<double>& weights, std::vector<double>& knots) {
  const std::size_t n = points.size();
  if (!node.get<FieldType::SFBool>("closed", false) || order < 3 || n < 3 ||
      n < static_cast<std::size_t>(order) || points.front() != points.back() ||
      weights.front() != weights.back())
    return false;
  const std::size_t length = n + static_cast<std::size_t>(order);
  std::string problem;
  if (knots.size() != length || !nurbs::strictAxis(static_cast<int>(n), order, knots, problem)) {
    knots.resize(length);
    for (std::size_t i = 0; i < length; ++i)
      knots[i] = static_cast<double>(i) / static_cast<double>(length - 1);
  }
  for (int i = 1; i < order - 1; ++i) {
    const auto k = static_cast<std::size_t>(i);
    knots.push_back(knots.back() + (knots[k] - knots[k - 1]));
    points.push_back(points[k]);
    weights.push_back(weights[k]);
  }
  return true;
}

std::vector<glm::dvec3> nurbsCurvePoints(const Node& node, const std::vector<glm::dvec3>& given,
                                         ProblemLog& log) {
  if (given.size() < 2 || given.size() > static_cast<std::size_t>(kMaxNurbsControlPoints))
    return {};
  std::vector<glm::dvec3> points = given;
  // The weights as nurbsWeights() reads them (it reports their problem after the knots').
  ProblemLog quiet(node, nullptr);
  std::vector<double> w = nurbsWeights(node, points.size(), quiet);
  nurbs::fromHomogeneous(points, w);
  std::vector<double> knots = nurbs::doubles(node, "knot");
  const int order = node.get<FieldType::SFInt32>("order", 3);
  closeCurve(node, order, points, w, knots);
  const int n = static_cast<int>(points.size());
  const Axis axis = nurbsAxis(n, order, knots, "knot", log);
  nurbsWeights(node, given.size(), log);
  const int segments = nurbsSegments(node.get<FieldType::SFInt32>("tessellation", 0), n);
  std::vector<glm::dvec3> out;
  out.reserve(static_cast<std::size_t>(segments) + 1);
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
    out.push_back(weight != 0.0 ? sum / weight : points.front());
  }
  return out;
}

Mesh tessellateNurbsCurve(const Node& node, ProblemLog& log) {
  const std::vector<glm::dvec3> curve = nurbsCurvePoints(node, nurbs::controlPoints(node), log);
  if (curve.empty()) return {};
  MeshBuilder b(Primitive::lines, false, false, false);
  b.reserve(curve.size(), 2 * curve.size());
  for (std::size_t s = 0; s < curve.size(); ++s) {
    Vertex v;
    v.position = glm::vec3(curve[s]);
    const std::uint32_t index = b.push(v);
    if (s > 0) {
      b.index(index - 1);
      b.index(index);
    }
  }
  return b.finish(false);
}

/// NurbsTrimmedSurface's trimming contours (27.4.9): each Contour2D's children
/// (NurbsCurve2D, ContourPolyline2D) joined end to end, a polygon of (u, v) parameters.
std::vector<std::vector<glm::dvec2>> trimmingLoops(const Node& node, ProblemLog& log) {
  std::vector<std::vector<glm::dvec2>> loops;
  if (node.typeId() != NodeTypeId::NurbsTrimmedSurface) return loops;
  for (const NodePtr& contour : node.mfnode("trimmingContour")) {
    if (!contour || contour->unresolved || contour->typeId() != NodeTypeId::Contour2D) continue;
    std::vector<glm::dvec2> loop;
    for (const NodePtr& curve : contour->mfnode("children"))
      for (const glm::dvec2& p : nurbsCurve2DPoints(curve, log))
        if (loop.empty() || p != loop.back()) loop.push_back(p);
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  return loops;
}

/// Whether (u, v) is kept: inside an odd number of `loops` (even-odd crossings per loop),
/// as X_ITE 15 trims.
bool keptByTrimming(const std::vector<std::vector<glm::dvec2>>& loops, glm::dvec2 p) {
  bool kept = false;
  for (const std::vector<glm::dvec2>& loop : loops) {
    bool inside = false;
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const glm::dvec2 a = loop[i], b = loop[j];
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
        inside = !inside;
    }
    if (inside) kept = !kept;
  }
  return kept;
}

namespace {

/// A surface closed in one direction (27.4.4 uClosed / vClosed TRUE, each row's first and
/// last control points and weights the same) made periodic there as X_ITE makes it: the
/// order - 2 points after each row's first repeated at its end, the knots (the node's when
/// usable, else uniform over [0, 1]) continued by the same steps. `points` and `weights`
/// are nu x nv, u fastest; `alongU` picks the direction. False (nothing changed) when the
/// surface cannot close that way.
bool closeSurface(bool alongU, int order, int& nu, int& nv, std::vector<glm::dvec3>& points,
                  std::vector<double>& weights, std::vector<double>& knots) {
  const int n = alongU ? nu : nv, rows = alongU ? nv : nu;
  const auto at = [&](int along, int row) {
    return static_cast<std::size_t>(alongU ? along + row * nu : row + along * nu);
  };
  if (order < 3 || n < order) return false;
  for (int r = 0; r < rows; ++r)
    if (points[at(0, r)] != points[at(n - 1, r)] || weights[at(0, r)] != weights[at(n - 1, r)])
      return false;
  const auto length = static_cast<std::size_t>(n + order);
  std::string problem;
  if (knots.size() != length || !nurbs::strictAxis(n, order, knots, problem)) {
    knots.resize(length);
    for (std::size_t i = 0; i < length; ++i)
      knots[i] = static_cast<double>(i) / static_cast<double>(length - 1);
  }
  const int extra = order - 2;
  for (int i = 1; i <= extra; ++i) {
    const auto k = static_cast<std::size_t>(i);
    knots.push_back(knots.back() + (knots[k] - knots[k - 1]));
  }
  const int n2 = n + extra;
  std::vector<glm::dvec3> p2;
  std::vector<double> w2;
  p2.reserve(static_cast<std::size_t>(n2 * rows));
  w2.reserve(p2.capacity());
  const int nu2 = alongU ? n2 : nu, nv2 = alongU ? nv : n2;
  for (int v = 0; v < nv2; ++v)
    for (int u = 0; u < nu2; ++u) {
      const int along = alongU ? u : v, row = alongU ? v : u;
      const std::size_t from = at(along < n ? along : along - n + 1, row);
      p2.push_back(points[from]);
      w2.push_back(weights[from]);
    }
  points = std::move(p2);
  weights = std::move(w2);
  nu = nu2;
  nv = nv2;
  return true;
}

}  // namespace

Mesh tessellateNurbsSurface(const Node& node, ProblemLog& log, float scale) {
  std::vector<glm::dvec3> points = nurbs::controlPoints(node);
  const int nu = node.get<FieldType::SFInt32>("uDimension", 0);
  const int nv = node.get<FieldType::SFInt32>("vDimension", 0);
  if (nu < 2 || nv < 2 || nu > kMaxNurbsControlPoints || nv > kMaxNurbsControlPoints) return {};
  const auto count = static_cast<std::size_t>(nu) * static_cast<std::size_t>(nv);
  if (points.size() < count) {
    log.add("controlPoint has " + std::to_string(points.size()) + " points, uDimension x " +
            "vDimension asks for " + std::to_string(count));
    return {};
  }
  points.resize(count);
  std::vector<double> w = nurbsWeights(node, count, log);
  nurbs::fromHomogeneous(points, w);
  // uClosed / vClosed (a NurbsPatchSurface's): periodic in that direction, as X_ITE.
  int eu = nu, ev = nv;
  const int uOrder = node.get<FieldType::SFInt32>("uOrder", 3);
  const int vOrder = node.get<FieldType::SFInt32>("vOrder", 3);
  std::vector<double> uKnots = nurbs::doubles(node, "uKnot");
  std::vector<double> vKnots = nurbs::doubles(node, "vKnot");
  if (node.get<FieldType::SFBool>("uClosed", false))
    closeSurface(true, uOrder, eu, ev, points, w, uKnots);
  if (node.get<FieldType::SFBool>("vClosed", false))
    closeSurface(false, vOrder, eu, ev, points, w, vKnots);
  const Axis ua = nurbsAxis(eu, uOrder, uKnots, "uKnot", log);
  const Axis va = nurbsAxis(ev, vOrder, vKnots, "vKnot", log);
  // A NurbsSet's tessellationScale: floor(segments x scale), as X_ITE 15.
  const auto scaled = [&](int segments) {
    const double s = std::floor(segments * std::clamp(static_cast<double>(scale), 0.0, 64.0));
    return std::clamp(static_cast<int>(s), 1, kMaxNurbsSegments);
  };
  const int su = scaled(nurbsSegments(node.get<FieldType::SFInt32>("uTessellation", 0), nu));
  const int sv = scaled(nurbsSegments(node.get<FieldType::SFInt32>("vTessellation", 0), nv));
  const auto gu = static_cast<std::size_t>(su + 1), gv = static_cast<std::size_t>(sv + 1);

  const std::vector<glm::dvec3> grid = nurbsGrid(ua, va, points, w, su, sv);

  // Texture coordinates: a NurbsTextureCoordinate's surface over the same grid of
  // parameters (27.4.10), or a TextureCoordinate per control point, bilinear over the
  // parameter grid; else the parameters scaled to [0, 1].
  const NodePtr& tc = node.sfnode("texCoord");
  const std::vector<glm::vec2>* texPoints = nullptr;
  std::vector<glm::vec2> texHeld;
  std::vector<glm::dvec3> texGrid;
  if (tc && !tc->unresolved && tc->typeId() == NodeTypeId::TextureCoordinate) {
    texHeld = tc->get<FieldType::MFVec2f>("point", std::vector<glm::vec2>{});
    if (texHeld.size() >= count) texPoints = &texHeld;
  } else if (tc && !tc->unresolved && tc->typeId() == NodeTypeId::NurbsTextureCoordinate) {
    texGrid = nurbsTextureGrid(*tc, su, sv, log);
  }
  const auto texAt = [&](double s, double t) {
    if (!texGrid.empty()) {
      const auto i = static_cast<std::size_t>(std::lround(s * su));
      const auto j = static_cast<std::size_t>(std::lround(t * sv));
      return glm::vec2(texGrid[i + j * static_cast<std::size_t>(su + 1)]);
    }
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

  const std::vector<glm::vec3> normals = nurbsGridNormals(grid, gu, gv);
  MeshBuilder b(Primitive::triangles, true, false, true);
  b.reserve(gu * gv, 6 * static_cast<std::size_t>(su) * static_cast<std::size_t>(sv));
  for (std::size_t j = 0; j < gv; ++j)
    for (std::size_t i = 0; i < gu; ++i) {
      Vertex v;
      v.position = glm::vec3(grid[i + j * gu]);
      v.normal = normals[i + j * gu];
      v.texCoord = texAt(static_cast<double>(i) / su, static_cast<double>(j) / sv);
      b.push(v);
    }
  const std::vector<std::vector<glm::dvec2>> loops = trimmingLoops(node, log);
  // The parameters of grid point (i, j) plus a fraction of a cell.
  const auto param = [&](double i, double j) {
    return glm::dvec2(ua.start() + (ua.end() - ua.start()) * i / su,
                      va.start() + (va.end() - va.start()) * j / sv);
  };
  for (std::size_t j = 0; j + 1 < gv; ++j)
    for (std::size_t i = 0; i + 1 < gu; ++i) {
      const auto a = static_cast<std::uint32_t>(i + j * gu);
      const auto c = static_cast<std::uint32_t>(i + (j + 1) * gu);
      const auto di = static_cast<double>(i), dj = static_cast<double>(j);
      if (loops.empty() || keptByTrimming(loops, param(di + 2.0 / 3.0, dj + 1.0 / 3.0)))
        b.triangle(a, a + 1, c + 1);
      if (loops.empty() || keptByTrimming(loops, param(di + 1.0 / 3.0, dj + 2.0 / 3.0)))
        b.triangle(a, c + 1, c);
    }
  return b.finish(node.get<FieldType::SFBool>("solid", true));
}

}  // namespace gs::vrml::geometry_detail
