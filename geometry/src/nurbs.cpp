// X3D NURBS evaluation (X3D 4.0 clause 27.2): geometry/nurbs.hpp. The NURBS Book's A2.1, A2.2,
// equation 2.9 (derivatives of the basis functions), 4.8 and 4.15 (rational curve and
// surface); the derivative of a quotient A / W is (A' - W' (A / W)) / W.
#include "geometry/nurbs.hpp"

#include <algorithm>
#include <cmath>

namespace gs::vrml::nurbs {

namespace {

/// The uniform clamped knots of `count` points of order `order`.
std::vector<double> uniformKnots(int count, int order) {
  std::vector<double> k;
  k.reserve(static_cast<std::size_t>(count + order));
  for (int i = 0; i < count + order; ++i)
    k.push_back(static_cast<double>(std::clamp(i - order + 1, 0, count - order + 1)));
  return k;
}

/// Why `given` is not a knot vector for `count` points of order `order` ("" when it is).
std::string knotProblem(int count, int order, const std::vector<double>& given) {
  const std::size_t need = static_cast<std::size_t>(count + order);
  if (given.size() != need)
    return std::to_string(given.size()) + " knots, not the " + std::to_string(need) +
           " the control points and order ask for";
  for (std::size_t i = 0; i < given.size(); ++i) {
    if (!std::isfinite(given[i])) return "a knot is not finite";
    if (i > 0 && given[i] < given[i - 1]) return "the knots decrease";
  }
  if (!(given[static_cast<std::size_t>(order - 1)] < given[static_cast<std::size_t>(count)]))
    return "the knots leave no parameter range";
  return {};
}

/// A2.2 for the basis of order `order` (which may be lower than the axis's).
void basisOfOrder(const std::vector<double>& knots, int order, int k, double u,
                  std::vector<double>& n) {
  const int p = order - 1;
  const auto at = [&](int i) { return knots[static_cast<std::size_t>(i)]; };
  n.assign(static_cast<std::size_t>(order), 0.0);
  std::vector<double> left(static_cast<std::size_t>(order)), right(static_cast<std::size_t>(order));
  n[0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    left[uj] = u - at(k + 1 - j);
    right[uj] = at(k + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      const auto ur = static_cast<std::size_t>(r);
      const double denominator = right[ur + 1] + left[uj - ur];
      const double t = denominator != 0.0 ? n[ur] / denominator : 0.0;
      n[ur] = saved + right[ur + 1] * t;
      saved = left[uj - ur] * t;
    }
    n[uj] = saved;
  }
}

}  // namespace

double Axis::at(double fraction) const {
  const double f = std::isfinite(fraction) ? std::clamp(fraction, 0.0, 1.0) : 0.0;
  return start() + (end() - start()) * f;
}

int Axis::span(double u) const {
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

void Axis::basis(int k, double u, std::vector<double>& n) const {
  basisOfOrder(knots, order, k, u, n);
}

void Axis::basisDerivatives(int k, double u, std::vector<double>& n, std::vector<double>& d) const {
  basis(k, u, n);
  const int p = order - 1;    // >= 1
  std::vector<double> lower;  // N[k - p + 1 .. k] of degree p - 1
  basisOfOrder(knots, order - 1, k, u, lower);
  d.assign(static_cast<std::size_t>(order), 0.0);
  const auto knot = [&](int i) { return knots[static_cast<std::size_t>(i)]; };
  for (int r = 0; r <= p; ++r) {
    const int i = k - p + r;  // N_{i,p}' = p (N_{i,p-1} / (u_{i+p} - u_i)
                              //            - N_{i+1,p-1} / (u_{i+p+1} - u_{i+1}))
    double value = 0.0;
    if (r >= 1) {
      const double span1 = knot(i + p) - knot(i);
      if (span1 > 0.0) value += lower[static_cast<std::size_t>(r - 1)] / span1;
    }
    if (r <= p - 1) {
      const double span2 = knot(i + p + 1) - knot(i + 1);
      if (span2 > 0.0) value -= lower[static_cast<std::size_t>(r)] / span2;
    }
    d[static_cast<std::size_t>(r)] = p * value;
  }
}

std::optional<Axis> strictAxis(int count, int order, const std::vector<double>& given,
                               std::string& problem) {
  if (order < 2) {
    problem = "order " + std::to_string(order) + " is below 2";
    return std::nullopt;
  }
  if (count < order) {
    problem =
        std::to_string(count) + " control points, fewer than the order " + std::to_string(order);
    return std::nullopt;
  }
  if (count > kMaxControlPoints) {
    problem =
        std::to_string(count) + " control points, more than " + std::to_string(kMaxControlPoints);
    return std::nullopt;
  }
  Axis a;
  a.count = count;
  a.order = order;
  if (given.empty()) {
    a.knots = uniformKnots(count, order);
    return a;
  }
  problem = knotProblem(count, order, given);
  if (!problem.empty()) return std::nullopt;
  a.knots = given;
  return a;
}

Axis lenientAxis(int count, int order, const std::vector<double>& given, const char* what,
                 std::string& problem) {
  Axis a;
  a.count = count;
  a.order = std::clamp(order, 2, std::max(2, count));
  if (knotProblem(count, a.order, given).empty()) {
    a.knots = given;
    return a;
  }
  if (!given.empty())
    problem = std::string(what) + " has " + std::to_string(given.size()) + " values, not the " +
              std::to_string(count + a.order) +
              " non-decreasing ones the control points and order ask for: uniform knots used";
  a.knots = uniformKnots(count, a.order);
  return a;
}

std::vector<glm::dvec3> controlPoints(const Node& node) {
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

std::vector<double> doubles(const Node& node, FieldName name) {
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

std::optional<std::vector<double>> strictWeights(const std::vector<double>& given,
                                                 std::size_t count, std::string& problem) {
  if (given.empty()) return std::vector<double>(count, 1.0);
  if (given.size() != count) {
    problem =
        std::to_string(given.size()) + " weights for " + std::to_string(count) + " control points";
    return std::nullopt;
  }
  for (const double w : given)
    if (!(std::isfinite(w) && w > 0.0)) {
      problem = "a weight is not > 0";
      return std::nullopt;
    }
  return given;
}

void fromHomogeneous(std::vector<glm::dvec3>& points, const std::vector<double>& weights) {
  const std::size_t n = std::min(points.size(), weights.size());
  for (std::size_t i = 0; i < n; ++i) points[i] /= weights[i];
}

CurveSample evaluateCurve(const Axis& axis, const std::vector<glm::dvec3>& points,
                          const std::vector<double>& weights, double u) {
  u = std::clamp(u, axis.start(), axis.end());
  const int k = axis.span(u);
  std::vector<double> n, d;
  axis.basisDerivatives(k, u, n, d);
  glm::dvec3 a(0.0), da(0.0);
  double w = 0.0, dw = 0.0;
  for (int r = 0; r < axis.order; ++r) {
    const auto i = static_cast<std::size_t>(k - axis.order + 1 + r);
    const auto ur = static_cast<std::size_t>(r);
    a += n[ur] * weights[i] * points[i];
    da += d[ur] * weights[i] * points[i];
    w += n[ur] * weights[i];
    dw += d[ur] * weights[i];
  }
  CurveSample s;
  if (!(w > 0.0)) {
    s.position = points[static_cast<std::size_t>(std::max(0, k - axis.order + 1))];
    return s;
  }
  s.position = a / w;
  s.tangent = (da - dw * s.position) / w;
  return s;
}

SurfaceSample evaluateSurface(const Axis& ua, const Axis& va, const std::vector<glm::dvec3>& points,
                              const std::vector<double>& weights, double u, double v) {
  u = std::clamp(u, ua.start(), ua.end());
  v = std::clamp(v, va.start(), va.end());
  const int ku = ua.span(u), kv = va.span(v);
  std::vector<double> nu, du, nv, dv;
  ua.basisDerivatives(ku, u, nu, du);
  va.basisDerivatives(kv, v, nv, dv);
  glm::dvec3 a(0.0), au(0.0), av(0.0);
  double w = 0.0, wu = 0.0, wv = 0.0;
  for (int s = 0; s < va.order; ++s) {
    const auto pj = static_cast<std::size_t>(kv - va.order + 1 + s);
    const auto us = static_cast<std::size_t>(s);
    for (int r = 0; r < ua.order; ++r) {
      const auto pi = static_cast<std::size_t>(ku - ua.order + 1 + r);
      const auto ur = static_cast<std::size_t>(r);
      const std::size_t c = pi + pj * static_cast<std::size_t>(ua.count);
      const double f = nu[ur] * nv[us] * weights[c];
      const double fu = du[ur] * nv[us] * weights[c];
      const double fv = nu[ur] * dv[us] * weights[c];
      a += f * points[c];
      au += fu * points[c];
      av += fv * points[c];
      w += f;
      wu += fu;
      wv += fv;
    }
  }
  SurfaceSample out;
  if (!(w > 0.0)) {
    out.position = points.front();
    return out;
  }
  out.position = a / w;
  out.du = (au - wu * out.position) / w;
  out.dv = (av - wv * out.position) / w;
  return out;
}

}  // namespace gs::vrml::nurbs
