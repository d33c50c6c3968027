// X3D's non-linear interpolators (ISO/IEC 19775-1 X3D 4.0 clause 19) as pure functions of
// their fields and a fraction: 19.4.4 EaseInEaseOut, 19.2.4 Hermite spline interpolation
// for 19.4.10 SplinePositionInterpolator, 19.4.11 SplinePositionInterpolator2D and 19.4.12
// SplineScalarInterpolator, and 19.4.13 SquadOrientationInterpolator. Keys are
// non-decreasing; a fraction at or below the first key gives the first value, at or above the
// last key the last value (19.2.2), as for the linear interpolators (interpolators.hpp).
// docs/x3d.md "Interpolation" says where the standard is read through X_ITE.
#pragma once

#include "runtime/interpolators.hpp"
#include "vrml/field.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gs::runtime {

/// The fields of a spline interpolator besides key and keyValue (19.4.10-19.4.12).
struct SplineOptions {
  /// keyVelocity (MFFloat, MFVec2f or MFVec3f, as keyValue), or null. key.size() velocities
  /// give every tangent; exactly two give the first and last (the others are computed);
  /// any other count is ignored (every tangent computed).
  const vrml::FieldValue* keyVelocity = nullptr;
  /// closed: the curve's end tangents wrap around (19.2.4). Ignored unless the first and
  /// last keyValue are equal, there are at least three keys, and keyVelocity does not give
  /// the end velocities.
  bool closed = false;
  /// normalizeVelocity: each given velocity T_i becomes T_i * Dtot / |T_i|, Dtot the length
  /// of the polyline through keyValue (a zero velocity stays zero).
  bool normalizeVelocity = false;
};

/// The modified fraction of EaseInEaseOut (19.4.4) for `fraction`. `easeInEaseOut[i]` is
/// (easeIn, easeOut) at key i: in the key interval [key[i], key[i+1]] with local fraction
/// u in [0, 1], easeOut = easeInEaseOut[i].y and easeIn = easeInEaseOut[i+1].x; when their
/// sum S is negative the result is u; when S > 1 both are divided by S; then with
/// t = 1 / (2 - easeOut - easeIn) the result is (t / easeOut) u^2 for u < easeOut,
/// t (2u - easeOut) for u <= 1 - easeIn, and 1 - t (1 - u)^2 / easeIn above. The result is
/// the local eased fraction in [0, 1] of the interval the fraction falls in (as the
/// standard's pseudo-code, X_ITE and FreeWRL give it): 0 at or below the first key, 1 at or
/// above the last. Fewer easeInEaseOut values than keys are padded with the last one ((0, 0),
/// linear, when there is none), as X_ITE does. Nothing, with `problem` set, when key is
/// empty.
std::optional<float> easeInEaseOutFraction(const std::vector<float>& key,
                                           const std::vector<glm::vec2>& easeInEaseOut,
                                           float fraction, std::string& problem);

/// The cubic Hermite blend of 19.2.4, v(s) = S^T H C with S = (s^3, s^2, s, 1) and
/// C = (v0, v1, t0, t1): h1 v0 + h2 v1 + h3 t0 + h4 t1, h1 = 2s^3 - 3s^2 + 1,
/// h2 = -2s^3 + 3s^2, h3 = s^3 - 2s^2 + s, h4 = s^3 - s^2; `s` in [0, 1], t0 the outgoing
/// tangent at v0 and t1 the incoming one at v1, both per unit of s.
float hermite(float v0, float v1, float t0, float t1, float s);

/// value_changed of a spline interpolator (19.2.4; keyValue MFFloat -> SFFloat, MFVec2f ->
/// SFVec2f, MFVec3f -> SFVec3f) for `fraction`. In the key interval i with
/// s = (fraction - t_i) / (t_{i+1} - t_i): hermite(v_i, v_{i+1}, F+_i T_i, F-_{i+1} T_{i+1}, s)
/// with F-_i = 2 (t_{i+1} - t_i) / (t_{i+1} - t_{i-1}) and
/// F+_i = 2 (t_i - t_{i-1}) / (t_{i+1} - t_{i-1}) (1 at the ends of an open curve; on a closed
/// one t_{-1} and t_n wrap through t_{n-2} and t_1). Tangents T_i not given by keyVelocity
/// are (v_{i+1} - v_{i-1}) / 2 inside, (v_1 - v_{n-2}) / 2 at both ends of a closed curve
/// and zero at the ends of an open one. Nothing, with `problem` set, when key is empty,
/// keyValue has not key.size() values, or keyValue has another type.
std::optional<vrml::FieldValue> interpolateSpline(const std::vector<float>& key,
                                                  const vrml::FieldValue& keyValue,
                                                  const SplineOptions& options, float fraction,
                                                  std::string& problem);

/// Shoemake's intermediate quaternion of squad at q (19.4.13), between its neighbours
/// `previous` and `next`: q exp(-(log(q^-1 next) + log(q^-1 previous)) / 4), unit length.
/// All three are unit quaternions; `previous` and `next` are taken in q's hemisphere.
glm::dquat squadIntermediate(const glm::dquat& previous, const glm::dquat& q,
                             const glm::dquat& next);

/// value_changed of SquadOrientationInterpolator (19.4.13) for `fraction`: in the key
/// interval i with local fraction h, squad(q_i, q_{i+1}, s_i, s_{i+1}, h) =
/// slerp(slerp(q_i, q_{i+1}, h), slerp(s_i, s_{i+1}, h), 2h(1 - h)), the rotations as unit
/// quaternions, each key taken in the hemisphere of the one before (the shorter arc),
/// s_i = squadIntermediate(q_{i-1}, q_i, q_{i+1}) inside and s_i = q_i at the first and
/// last key (the node has no closed field in X3D 4.0). normalizeVelocity has no velocities
/// to act on and is ignored (X_ITE's node has no such field). The result's axis is unit
/// length. Nothing, with `problem` set, when key is empty or keyValue has not key.size()
/// values.
std::optional<vrml::Rotation> interpolateSquad(const std::vector<float>& key,
                                               const std::vector<vrml::Rotation>& keyValue,
                                               float fraction, std::string& problem);

/// The output of a non-linear interpolator of `kind` (nonLinearInterpolator(kind)) for
/// `fraction`: EaseInEaseOut's modifiedFraction_changed (SFFloat; `keyValue` is its
/// easeInEaseOut field, MFVec2f), the spline interpolators' and
/// SquadOrientationInterpolator's value_changed. `options` serves the splines only.
/// Nothing, with `problem` set, where the functions above give nothing or a field has the
/// wrong type.
std::optional<vrml::FieldValue> interpolateX3d(InterpolatorKind kind, const std::vector<float>& key,
                                               const vrml::FieldValue& keyValue,
                                               const SplineOptions& options, float fraction,
                                               std::string& problem);

}  // namespace gs::runtime
