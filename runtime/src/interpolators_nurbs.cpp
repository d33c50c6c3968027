// X3D 4.0 clause 27's interpolators: NurbsPositionInterpolator (27.4.6),
// NurbsOrientationInterpolator (27.4.5) and NurbsSurfaceInterpolator (27.4.9), as pure
// functions (runtime/interpolators_nurbs.hpp) and as the execution model's role
// nurbsInterpolator (set_fraction -> value_changed, or position_changed and normal_changed).
#include "runtime/interpolators_nurbs.hpp"

#include "execution_state.hpp"
#include "geometry/nurbs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gs::runtime {

namespace {
namespace nurbsinterp {  // a name of its own: runtime sources may be unity-built together

/// A curve of an interpolator node, checked.
struct Curve {
  vrml::nurbs::Axis axis;
  std::vector<glm::dvec3> points;
  std::vector<double> weights;
};

std::optional<Curve> curveOf(const vrml::Node& node, std::string& problem) {
  Curve c;
  c.points = vrml::nurbs::controlPoints(node);
  if (c.points.empty()) {
    problem = "no control points";
    return std::nullopt;
  }
  const std::vector<double> knots = vrml::nurbs::doubles(node, "knot");
  const bool defaultKnots = knots.empty();
  auto axis = vrml::nurbs::strictAxis(
      static_cast<int>(std::min<std::size_t>(c.points.size(), vrml::nurbs::kMaxControlPoints + 1)),
      node.get<vrml::FieldType::SFInt32>("order", 3), knots, problem);
  if (!axis) return std::nullopt;
  auto weights =
      vrml::nurbs::strictWeights(vrml::nurbs::doubles(node, "weight"), c.points.size(), problem);
  if (!weights) return std::nullopt;
  c.axis = std::move(*axis);
  c.weights = std::move(*weights);
  vrml::nurbs::fromHomogeneous(c.points, c.weights);
  // No knots: the uniform clamped ones scaled to [0, 1], so that fractions 0 to 1 run the
  // whole curve (castle-model-viewer's default; the curve is the same).
  if (defaultKnots)
    for (double& k : c.axis.knots) k /= static_cast<double>(c.axis.count - c.axis.order + 1);
  return c;
}

/// The curve parameter of `fraction`: the knot value itself (X_ITE, castle-model-viewer),
/// clamped to the curve's range; NaN is its start.
double parameterOf(const vrml::nurbs::Axis& axis, float fraction) {
  if (!std::isfinite(fraction)) return axis.start();
  return std::clamp(static_cast<double>(fraction), axis.start(), axis.end());
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The rotation turning +Z onto `direction` by the shortest arc.
vrml::Rotation rotationOnto(const glm::dvec3& direction) {
  const double len = glm::length(direction);
  if (!(len > 0.0) || !std::isfinite(len)) return {0.0f, 0.0f, 1.0f, 0.0f};
  const glm::dvec3 d = direction / len;
  const glm::dvec3 axis = glm::cross(glm::dvec3(0.0, 0.0, 1.0), d);
  const double s = glm::length(axis);
  if (s < 1e-12) {
    if (d.z > 0.0) return {0.0f, 0.0f, 1.0f, 0.0f};
    return {0.0f, 1.0f, 0.0f, std::numbers::pi_v<float>};
  }
  const glm::dvec3 a = axis / s;
  return {static_cast<float>(a.x), static_cast<float>(a.y), static_cast<float>(a.z),
          static_cast<float>(std::atan2(s, d.z))};
}

}  // namespace nurbsinterp
}  // namespace

std::optional<glm::vec3> nurbsPositionAt(const vrml::Node& node, float fraction,
                                         std::string& problem) {
  const auto c = nurbsinterp::curveOf(node, problem);
  if (!c) return std::nullopt;
  const auto s = vrml::nurbs::evaluateCurve(c->axis, c->points, c->weights,
                                            nurbsinterp::parameterOf(c->axis, fraction));
  if (!nurbsinterp::finite(s.position)) {
    problem = "the curve is not finite there";
    return std::nullopt;
  }
  return glm::vec3(s.position);
}

std::optional<vrml::Rotation> nurbsOrientationAt(const vrml::Node& node, float fraction,
                                                 std::string& problem) {
  const auto c = nurbsinterp::curveOf(node, problem);
  if (!c) return std::nullopt;
  const vrml::nurbs::Axis& axis = c->axis;
  const double u = nurbsinterp::parameterOf(axis, fraction);
  glm::dvec3 tangent = vrml::nurbs::evaluateCurve(axis, c->points, c->weights, u).tangent;
  if (!(glm::length(tangent) > 1e-12 * (1.0 + glm::length(c->points.front())))) {
    // No derivative here (a repeated control point): the chord across the nearest
    // stretch of the curve that moves, widened step by step to the whole range.
    const double range = axis.end() - axis.start();
    tangent = glm::dvec3(0.0);
    for (double h = 1e-4 * range; h <= 2.0 * range && !(glm::length(tangent) > 0.0); h *= 2.0) {
      const double a = std::max(axis.start(), u - h), b = std::min(axis.end(), u + h);
      tangent = vrml::nurbs::evaluateCurve(axis, c->points, c->weights, b).position -
                vrml::nurbs::evaluateCurve(axis, c->points, c->weights, a).position;
    }
  }
  if (!nurbsinterp::finite(tangent)) {
    problem = "the curve is not finite there";
    return std::nullopt;
  }
  return nurbsinterp::rotationOnto(tangent);
}

std::optional<NurbsSurfacePoint> nurbsSurfaceAt(const vrml::Node& node, glm::vec2 fraction,
                                                std::string& problem) {
  using vrml::FieldType;
  std::vector<glm::dvec3> points = vrml::nurbs::controlPoints(node);
  const int nu = node.get<FieldType::SFInt32>("uDimension", 0);
  const int nv = node.get<FieldType::SFInt32>("vDimension", 0);
  if (nu < 1 || nv < 1 || static_cast<double>(nu) * nv != static_cast<double>(points.size())) {
    problem = std::to_string(points.size()) + " control points, uDimension x vDimension is " +
              std::to_string(nu) + " x " + std::to_string(nv);
    return std::nullopt;
  }
  const auto ua = vrml::nurbs::strictAxis(nu, node.get<FieldType::SFInt32>("uOrder", 3),
                                          vrml::nurbs::doubles(node, "uKnot"), problem);
  if (!ua) {
    problem = "u: " + problem;
    return std::nullopt;
  }
  const auto va = vrml::nurbs::strictAxis(nv, node.get<FieldType::SFInt32>("vOrder", 3),
                                          vrml::nurbs::doubles(node, "vKnot"), problem);
  if (!va) {
    problem = "v: " + problem;
    return std::nullopt;
  }
  const auto w =
      vrml::nurbs::strictWeights(vrml::nurbs::doubles(node, "weight"), points.size(), problem);
  if (!w) return std::nullopt;
  vrml::nurbs::fromHomogeneous(points, *w);
  const double fu = ua->at(fraction.x), fv = va->at(fraction.y);
  const auto s = vrml::nurbs::evaluateSurface(*ua, *va, points, *w, fu, fv);
  glm::dvec3 n = glm::cross(s.du, s.dv);
  const double scale = glm::length(s.du) * glm::length(s.dv);
  if (!(glm::length(n) > 1e-9 * scale) || !(scale > 0.0)) {
    // A pole or a collapsed edge: the normal a little way towards the middle of the patch.
    const double mu = (ua->start() + ua->end()) * 0.5, mv = (va->start() + va->end()) * 0.5;
    const double step = 1e-4;
    const auto inner = vrml::nurbs::evaluateSurface(*ua, *va, points, *w, fu + (mu - fu) * step,
                                                    fv + (mv - fv) * step);
    n = glm::cross(inner.du, inner.dv);
  }
  if (!nurbsinterp::finite(s.position) || !nurbsinterp::finite(n)) {
    problem = "the surface is not finite there";
    return std::nullopt;
  }
  NurbsSurfacePoint out;
  out.position = glm::vec3(s.position);
  const double len = glm::length(n);
  if (len > 0.0) out.normal = glm::vec3(n / len);
  return out;
}

bool ExecutionModel::State::classifyNurbsInterpolator(NodeState& ns) {
  using vrml::NodeTypeId;
  const NodeTypeId id = ns.node->typeId();
  if (id != NodeTypeId::NurbsPositionInterpolator &&
      id != NodeTypeId::NurbsOrientationInterpolator && id != NodeTypeId::NurbsSurfaceInterpolator)
    return false;
  const vrml::NodeType& type = ns.node->type();
  ns.role = NodeRole::nurbsInterpolator;
  ns.setFraction = type.findExact("set_fraction");
  const bool surface = id == NodeTypeId::NurbsSurfaceInterpolator;
  ns.valueChanged = type.findExact(surface ? "position_changed" : "value_changed");
  ns.normalChanged = surface ? type.findExact("normal_changed") : -1;
  return true;
}

void ExecutionModel::State::deliverNurbsInterpolator(NodeState& ns, vrml::FieldValue value) {
  using vrml::FieldType;
  using vrml::FieldValue;
  const vrml::Node& node = *ns.node;
  std::string problem;
  const auto fail = [&] {
    if (!ns.problemReported) report(vrml::Severity::error, node, problem + "; no output");
    ns.problemReported = true;
  };
  switch (node.typeId()) {
    case vrml::NodeTypeId::NurbsPositionInterpolator:
      if (const auto p = nurbsPositionAt(node, value.get<FieldType::SFFloat>(), problem))
        emitOwn(ns, ns.valueChanged, FieldValue::make<FieldType::SFVec3f>(*p));
      else
        fail();
      return;
    case vrml::NodeTypeId::NurbsOrientationInterpolator:
      if (const auto r = nurbsOrientationAt(node, value.get<FieldType::SFFloat>(), problem))
        emitOwn(ns, ns.valueChanged, FieldValue::make<FieldType::SFRotation>(*r));
      else
        fail();
      return;
    default:
      if (const auto s = nurbsSurfaceAt(node, value.get<FieldType::SFVec2f>(), problem)) {
        // X_ITE's order: normal_changed, then position_changed.
        emitOwn(ns, ns.normalChanged, FieldValue::make<FieldType::SFVec3f>(s->normal));
        emitOwn(ns, ns.valueChanged, FieldValue::make<FieldType::SFVec3f>(s->position));
      } else {
        fail();
      }
      return;
  }
}

}  // namespace gs::runtime
