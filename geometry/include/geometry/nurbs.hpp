// X3D NURBS evaluation (ISO/IEC 19775-1 X3D 4.0 clause 27.2), shared by the NURBS geometry
// (geometry/src/geometry_nurbs.cpp) and the NURBS interpolators of the runtime
// (runtime/src/interpolators_nurbs.cpp): rational B-spline curves and surfaces and their
// first derivatives (L. Piegl, W. Tiller, "The NURBS Book", 2nd ed., algorithms A2.1
// FindSpan, A2.2 BasisFuns, equation 2.9 for the derivatives of the basis functions,
// equations 4.8 and 4.15 for the rational curve and surface).
//
// Internal to the project (not a stable interface): the parameter u of an Axis is in knot
// space, from start() to end().
#pragma once

#include "vrml/field_name.hpp"
#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gs::vrml::nurbs {

/// The most control points one direction may have (a bound for untrusted files).
constexpr int kMaxControlPoints = 1 << 16;

/// One direction of a B-spline: `count` control points of order `order` (degree order - 1)
/// over `knots` (count + order non-decreasing values with knots[order - 1] < knots[count]).
/// Made by strictAxis or lenientAxis, which check those conditions.
struct Axis {
  std::vector<double> knots;
  int order = 3;
  int count = 0;

  /// The first and last parameter of the curve: knots[order - 1], knots[count].
  double start() const { return knots[static_cast<std::size_t>(order - 1)]; }
  double end() const { return knots[static_cast<std::size_t>(count)]; }
  /// The parameter at `fraction` of the way from start() to end(); `fraction` is clamped to
  /// [0, 1] (NaN counts as 0).
  double at(double fraction) const;
  /// A2.1: the span k in [order - 1, count - 1] with knots[k] <= u < knots[k + 1] (the last
  /// non-empty one at or past end(); the first one before start()).
  int span(double u) const;
  /// A2.2: the `order` basis functions that may be non-zero at u in span k, N[k - order + 1
  /// .. k], into `n` (resized to order).
  void basis(int k, double u, std::vector<double>& n) const;
  /// As basis, and their first derivatives d/du into `d` (equation 2.9; 0 across a zero-length
  /// knot interval).
  void basisDerivatives(int k, double u, std::vector<double>& n, std::vector<double>& d) const;
};

/// The axis of `count` control points of order `order` over `given` knots, as the NURBS
/// interpolators need it: an empty `given` gives the uniform clamped vector (0 order times,
/// 1, 2, ..., count - order + 1 order times: 27.2.2's default); order < 2, count < order,
/// count > kMaxControlPoints, a count of knots other than count + order, a decreasing or
/// non-finite knot, or knots[order - 1] == knots[count] give nothing and `problem` says why.
std::optional<Axis> strictAxis(int count, int order, const std::vector<double>& given,
                               std::string& problem);

/// The axis of the NURBS geometry (lenient): the order clamped to [2, max(2, count)], and
/// the uniform clamped knots whenever `given` is not right (then `problem`, naming the field
/// `what`, says so when `given` was not empty). `count` >= 2.
Axis lenientAxis(int count, int order, const std::vector<double>& given, const char* what,
                 std::string& problem);

/// The points of `node`'s controlPoint field (a Coordinate's MFVec3f or a CoordinateDouble's
/// MFVec3d, 27.2.1); empty when there is none.
std::vector<glm::dvec3> controlPoints(const Node& node);

/// The MFDouble field `name` of `node` (MFFloat accepted, as some files write it); empty
/// when absent.
std::vector<double> doubles(const Node& node, FieldName name);

/// The weights of `count` control points as the interpolators need them: `given` when there
/// is one per control point, each finite and > 0; all 1 when `given` is empty (27.2.1);
/// otherwise nothing, and `problem` says why.
std::optional<std::vector<double>> strictWeights(const std::vector<double>& given,
                                                 std::size_t count, std::string& problem);

/// X3D's control points are homogeneous coordinates: a point with weight w is written
/// (w x, w y, w z), its weight in the weight field, as castle-model-viewer documents it
/// ("NURBS control points are expressed in homogeneous coordinates"; its
/// nurbs_weights.x3dv divides a point by its weight of 1/4 "to make weight 1/4 behave
/// intuitive") and X_ITE evaluates it (the B-spline of (x, y, z, w), then x / w). Divides
/// each of `points` by its weight (`weights` has one per point, all > 0), which makes them
/// the Euclidean points that evaluateCurve and evaluateSurface weight (The NURBS Book,
/// equation 4.2). The same curve: sum N w (P / w) / sum N w = sum N P / sum N w.
void fromHomogeneous(std::vector<glm::dvec3>& points, const std::vector<double>& weights);

/// A point of a curve and its first derivative d/du (in the control points' units per unit
/// of u).
struct CurveSample {
  glm::dvec3 position{0.0};
  glm::dvec3 tangent{0.0};
};

/// The rational B-spline curve of `points` (axis.count of them) with `weights` (as many, all
/// > 0) at parameter u (clamped to the axis's range).
CurveSample evaluateCurve(const Axis& axis, const std::vector<glm::dvec3>& points,
                          const std::vector<double>& weights, double u);

/// A point of a surface and its partial derivatives d/du and d/dv.
struct SurfaceSample {
  glm::dvec3 position{0.0};
  glm::dvec3 du{0.0};
  glm::dvec3 dv{0.0};
};

/// The rational B-spline surface of `points` (ua.count x va.count of them, u fastest: point
/// (i, j) is points[i + j * ua.count]) with `weights` (as many, all > 0) at (u, v) (each
/// clamped to its axis's range).
SurfaceSample evaluateSurface(const Axis& ua, const Axis& va, const std::vector<glm::dvec3>& points,
                              const std::vector<double>& weights, double u, double v);

}  // namespace gs::vrml::nurbs
