// The six VRML97 interpolators (clause 4.6.8 "Interpolator nodes"; 6.10
// ColorInterpolator, 6.15 CoordinateInterpolator, 6.31 NormalInterpolator, 6.32
// OrientationInterpolator, 6.37 PositionInterpolator, 6.39 ScalarInterpolator) as pure
// functions of key, keyValue and fraction. Keys are non-decreasing; a fraction below the
// first key gives the first value, above the last the last value; two equal keys make a
// step (the value jumps at that key, the later value winning at the key itself).
#pragma once

#include "vrml/field.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace gs::runtime {

/// Where `fraction` falls among `key`: value = mix(keyValue[index], keyValue[index + 1], t)
/// with t in [0, 1]; index + 1 == key.size() (t = 0) past the last key. `key` must not be
/// empty.
struct KeySpan {
  std::size_t index = 0;
  float t = 0.0f;
};
KeySpan findKeySpan(const std::vector<float>& key, float fraction);

/// Spherical linear interpolation of two rotations (axis, angle in radians) along the
/// shorter arc (6.32); the result's axis is unit length. A zero axis is the identity.
vrml::Rotation slerpRotation(const vrml::Rotation& a, const vrml::Rotation& b, float t);

/// Interpolation on the unit sphere of two normals (6.31): the result is unit length.
glm::vec3 slerpNormal(const glm::vec3& a, const glm::vec3& b, float t);

/// The kinds of interpolator: VRML97's six, X3D's linear 2D ones (X3D 4.0 19.4.3
/// CoordinateInterpolator2D, 19.4.8 PositionInterpolator2D) and X3D's non-linear ones
/// (19.4.4 EaseInEaseOut, 19.4.10-19.4.12 the spline interpolators, 19.4.13
/// SquadOrientationInterpolator: runtime/interpolators_x3d.hpp).
enum class InterpolatorKind {
  Color,
  Coordinate,
  Normal,
  Orientation,
  Position,
  Scalar,
  Coordinate2D,
  Position2D,
  EaseInEaseOut,
  SplinePosition,
  SplinePosition2D,
  SplineScalar,
  SquadOrientation,
};

/// Whether `kind` is one of X3D's non-linear interpolators (interpolateX3d, not interpolate).
constexpr bool nonLinearInterpolator(InterpolatorKind kind) {
  return kind >= InterpolatorKind::EaseInEaseOut;
}

/// value_changed of a linear interpolator of `kind` for `fraction`, given its key and keyValue
/// fields (keyValue of the type 6.x declares: MFColor, MFVec3f, MFRotation or MFFloat; MFVec2f
/// for the X3D 2D ones).
/// Colours are interpolated linearly in RGB (castle-model-viewer and X_ITE do too; the
/// standard's HSV is a browser choice). Returns nothing, with `problem` set, when the
/// counts disagree (key empty, keyValue not key.size() values, or for Coordinate,
/// Coordinate2D and Normal not a whole multiple of key.size()), and for the non-linear kinds
/// (use interpolateX3d).
std::optional<vrml::FieldValue> interpolate(InterpolatorKind kind, const std::vector<float>& key,
                                            const vrml::FieldValue& keyValue, float fraction,
                                            std::string& problem);

}  // namespace gs::runtime
