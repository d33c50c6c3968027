// X3D's NURBS interpolators (ISO/IEC 19775-1 X3D 4.0 clause 27) as pure functions of their
// node's fields and a fraction: 27.4.6 NurbsPositionInterpolator, 27.4.5
// NurbsOrientationInterpolator and 27.4.9 NurbsSurfaceInterpolator. The curve and surface
// are evaluated as NurbsCurve and NurbsPatchSurface are (geometry/nurbs.hpp), exactly (not
// through a tessellation). Where the standard leaves a choice X_ITE's reading is followed
// (docs/x3d.md "NURBS" says where):
// - The curves' set_fraction is the curve parameter itself, a knot value (X_ITE and
//   castle-model-viewer read it so), clamped to [knot[order - 1], knot[dimension]] (NaN: the
//   start); with no knots given, the uniform clamped knots scaled to [0, 1] (castle's
//   default), so that 0 to 1 runs the whole curve.
// - The surface's set_fraction (u, v), each in [0, 1] (clamped; NaN: 0), is mapped linearly
//   onto the parameter ranges (X_ITE reads it through the default texture coordinates so;
//   castle-model-viewer takes knot values, the same for knots in [0, 1]).
// - The orientation turns +Z onto the curve's tangent by the shortest arc (X_ITE's
//   Rotation4 (zAxis, direction)).
// - The surface's normal is dS/du x dS/dv, normalized (as NurbsPatchSurface's normals).
// Fields: an empty knot gives the uniform clamped knots and an empty weight weights of 1
// (27.2); order < 2, fewer control points than the order, a wrong count of knots, weights
// or control points, decreasing knots, or a weight not > 0 give no value and `problem` says
// why (the runtime reports it once).
#pragma once

#include "vrml/field.hpp"
#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string>

namespace gs::runtime {

/// 27.4.6: the point of `node`'s curve (controlPoint, weight, knot, order) at parameter
/// `fraction` (see above).
std::optional<glm::vec3> nurbsPositionAt(const vrml::Node& node, float fraction,
                                         std::string& problem);

/// 27.4.5: the rotation turning +Z onto the tangent of `node`'s curve at `fraction` (the
/// identity where the curve has no direction, e.g. all its control points equal; a half turn
/// about +Y where the tangent is -Z).
std::optional<vrml::Rotation> nurbsOrientationAt(const vrml::Node& node, float fraction,
                                                 std::string& problem);

/// A point of a NurbsSurfaceInterpolator's surface and its unit normal.
struct NurbsSurfacePoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
};

/// 27.4.9: the point and normal of `node`'s surface (controlPoint, weight, uKnot, vKnot,
/// uOrder, vOrder, uDimension, vDimension; u fastest in controlPoint) at `fraction` = (u, v),
/// each in [0, 1] over its parameter range. Where dS/du x dS/dv vanishes (a pole) the normal
/// is taken a little way towards the middle of the patch; +Z where the surface is flat to a
/// point.
std::optional<NurbsSurfacePoint> nurbsSurfaceAt(const vrml::Node& node, glm::vec2 fraction,
                                                std::string& problem);

}  // namespace gs::runtime
