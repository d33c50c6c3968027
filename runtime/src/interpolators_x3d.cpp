// X3D 4.0 clause 19: EaseInEaseOut (19.4.4), the spline interpolators (19.2.4, 19.4.10 -
// 19.4.12) and SquadOrientationInterpolator (19.4.13). Where the standard leaves a choice,
// X_ITE's reading is followed (src/x_ite/Components/Interpolation/*.js and
// src/x_ite/Browser/Interpolation/*.js); each place says so.
#include "runtime/interpolators_x3d.hpp"

#include "vrml/transform.hpp"

#include <algorithm>
#include <cmath>

namespace gs::runtime {

namespace {
namespace x3dinterp {  // a name of its own: runtime sources may be unity-built together

/// The key interval `fraction` falls in, i in [0, n - 2], and the local fraction s in
/// [0, 1]; at or past the last key the last interval at s = 1 (as X_ITE: the last value).
/// `key` has at least two keys.
struct Segment {
  std::size_t i = 0;
  float s = 0.0f;
};

Segment segmentOf(const std::vector<float>& key, float fraction) {
  const KeySpan span = findKeySpan(key, fraction);
  if (span.index + 1 >= key.size()) return {key.size() - 2, 1.0f};
  return {span.index, span.t};
}

float magnitude(float v) {
  return std::abs(v);
}
template <int N>
float magnitude(const glm::vec<N, float>& v) {
  return glm::length(v);
}

template <class V>
V hermiteBlend(const V& v0, const V& v1, const V& t0, const V& t1, float s) {
  const float s2 = s * s, s3 = s2 * s;
  return v0 * (2.0f * s3 - 3.0f * s2 + 1.0f) + v1 * (-2.0f * s3 + 3.0f * s2) +
         t0 * (s3 - 2.0f * s2 + s) + t1 * (s3 - s2);
}

/// 19.2.4 on `v` (one value per key, key.size() >= 1); `velocity` the keyVelocity values (may
/// be empty).
template <class V>
V splineValue(const std::vector<float>& key, const std::vector<V>& v,
              const std::vector<V>& velocity, const SplineOptions& options, float fraction) {
  const std::size_t n = key.size();
  if (n == 1) return v[0];
  const Segment seg = segmentOf(key, fraction);
  // keyVelocity: one per key, or exactly two (the first and the last: 19.4.10); any other
  // count is ignored (FreeWRL does the same; X_ITE pads a short list with zeros).
  const bool allGiven = velocity.size() == n;
  const bool endsGiven = allGiven || velocity.size() == 2;
  // "If velocity vectors at first and last keys are specified, the closed field is ignored.
  // If keyValues at first and last key are not identical, the closed field is ignored."
  const bool closed = options.closed && n >= 3 && !endsGiven && v.front() == v.back();
  float totalDistance = 0.0f;  // Dtot, for normalizeVelocity
  if (options.normalizeVelocity && endsGiven)
    for (std::size_t k = 0; k + 1 < n; ++k) totalDistance += magnitude(v[k + 1] - v[k]);
  // T_k: a given velocity (normalized on request), else the Catmull-Rom tangent.
  const auto tangent = [&](std::size_t k) -> V {
    const V* given = nullptr;
    if (allGiven)
      given = &velocity[k];
    else if (endsGiven && k == 0)
      given = &velocity.front();
    else if (endsGiven && k == n - 1)
      given = &velocity.back();
    if (given != nullptr) {
      const float m = magnitude(*given);
      // Every given velocity is normalized (X_ITE leaves the last one as it is).
      return options.normalizeVelocity && m > 0.0f ? *given * (totalDistance / m) : *given;
    }
    if (k > 0 && k + 1 < n) return (v[k + 1] - v[k - 1]) * 0.5f;
    if (closed) return (v[1] - v[n - 2]) * 0.5f;
    return V(0.0f);  // the ends of an open curve (X_ITE, FreeWRL)
  };
  // F-_k and F+_k (19.2.4); T0_k = F+_k T_k leaves key k, T1_k = F-_k T_k arrives at it,
  // as X_ITE and FreeWRL assign them.
  struct Factors {
    float minus = 1.0f, plus = 1.0f;
  };
  const auto factors = [&](std::size_t k) -> Factors {
    float before = 0.0f, after = 0.0f;  // t_k - t_{k-1}, t_{k+1} - t_k
    if (k > 0 && k + 1 < n) {
      before = key[k] - key[k - 1];
      after = key[k + 1] - key[k];
    } else if (closed) {  // t_{-1} and t_n wrap through t_{n-2} and t_1
      before = key[n - 1] - key[n - 2];
      after = key[1] - key[0];
    } else {
      return {};
    }
    const float d = before + after;
    if (!(d > 0.0f)) return {};  // equal keys: no spacing to correct for
    return {2.0f * after / d, 2.0f * before / d};
  };
  const std::size_t i = seg.i;
  const V t0 = tangent(i) * factors(i).plus;
  const V t1 = tangent(i + 1) * factors(i + 1).minus;
  return hermiteBlend(v[i], v[i + 1], t0, t1, seg.s);
}

template <vrml::FieldType MF, vrml::FieldType SF, class V>
std::optional<vrml::FieldValue> splineOf(const std::vector<float>& key,
                                         const vrml::FieldValue& keyValue,
                                         const SplineOptions& options, float fraction,
                                         std::string& problem) {
  const std::vector<V>& values = keyValue.get<MF>();
  if (values.size() != key.size()) {
    problem = "keyValue has " + std::to_string(values.size()) + " values for " +
              std::to_string(key.size()) + " keys";
    return std::nullopt;
  }
  static const std::vector<V> kNone;
  const std::vector<V>& velocity =
      options.keyVelocity != nullptr && options.keyVelocity->type() == MF
          ? options.keyVelocity->get<MF>()
          : kNone;
  return vrml::FieldValue::make<SF>(splineValue(key, values, velocity, options, fraction));
}

glm::dquat quatOf(const vrml::Rotation& r) {
  const glm::dvec3 axis(r.x, r.y, r.z);
  const double len = glm::length(axis);
  if (!(len > 0.0) || !std::isfinite(r.w)) return glm::dquat(1.0, 0.0, 0.0, 0.0);
  return glm::angleAxis(static_cast<double>(r.w), axis / len);
}

vrml::Rotation rotationOf(glm::dquat q) {
  return vrml::rotationFromQuaternion(q);
}

/// log of a unit quaternion (cos a, sin a n): the pure quaternion (0, a n).
glm::dquat logUnit(const glm::dquat& q) {
  const double a = std::acos(std::clamp(q.w, -1.0, 1.0));
  const double s = std::sin(a);
  const double k = std::abs(s) > 1e-12 ? a / s : 1.0;
  return glm::dquat(0.0, q.x * k, q.y * k, q.z * k);
}

/// exp of a pure quaternion (0, a n): (cos a, sin a n).
glm::dquat expPure(const glm::dquat& p) {
  const double a = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
  const double k = a > 1e-12 ? std::sin(a) / a : 1.0;
  return glm::dquat(std::cos(a), p.x * k, p.y * k, p.z * k);
}

/// Spherical linear interpolation without choosing the shorter arc (squad's slerp).
glm::dquat slerpPlain(const glm::dquat& a, const glm::dquat& b, double t) {
  const double cosine = std::clamp(glm::dot(a, b), -1.0, 1.0);
  const double omega = std::acos(cosine);
  const double s = std::sin(omega);
  if (s < 1e-9) return cosine > 0.0 ? glm::normalize(a * (1.0 - t) + b * t) : a;
  return a * (std::sin((1.0 - t) * omega) / s) + b * (std::sin(t * omega) / s);
}

/// q, or -q when that is nearer `reference` (the same rotation, the shorter arc).
glm::dquat towards(const glm::dquat& reference, const glm::dquat& q) {
  return glm::dot(reference, q) < 0.0 ? -q : q;
}

}  // namespace x3dinterp
}  // namespace

float hermite(float v0, float v1, float t0, float t1, float s) {
  return x3dinterp::hermiteBlend(v0, v1, t0, t1, s);
}

std::optional<float> easeInEaseOutFraction(const std::vector<float>& key,
                                           const std::vector<glm::vec2>& easeInEaseOut,
                                           float fraction, std::string& problem) {
  if (key.empty()) {
    problem = "key is empty";
    return std::nullopt;
  }
  if (key.size() == 1) return 0.0f;  // X_ITE: the one key's interval at weight 0
  if (!std::isfinite(fraction)) fraction = 0.0f;
  const auto at = [&](std::size_t k) {
    if (k < easeInEaseOut.size()) return easeInEaseOut[k];
    return easeInEaseOut.empty() ? glm::vec2(0.0f) : easeInEaseOut.back();
  };
  const x3dinterp::Segment seg = x3dinterp::segmentOf(key, fraction);
  const float u = seg.s;
  float easeOut = at(seg.i).y, easeIn = at(seg.i + 1).x;
  const float sum = easeOut + easeIn;
  if (sum < 0.0f) return u;
  if (sum > 1.0f) {
    easeIn /= sum;
    easeOut /= sum;
  }
  const float t = 1.0f / (2.0f - easeOut - easeIn);
  if (u < easeOut) return (t / easeOut) * u * u;
  // The standard says u < 1 - easeIn; X_ITE takes <= so that easeIn 0 does not divide by
  // zero at u = 1 (both give the same value where both are defined).
  if (u <= 1.0f - easeIn) return t * (2.0f * u - easeOut);
  const float w = 1.0f - u;
  return 1.0f - (t * w * w) / easeIn;
}

std::optional<vrml::FieldValue> interpolateSpline(const std::vector<float>& key,
                                                  const vrml::FieldValue& keyValue,
                                                  const SplineOptions& options, float fraction,
                                                  std::string& problem) {
  using vrml::FieldType;
  if (key.empty()) {
    problem = "key is empty";
    return std::nullopt;
  }
  if (!std::isfinite(fraction)) fraction = 0.0f;
  switch (keyValue.type()) {
    case FieldType::MFFloat:
      return x3dinterp::splineOf<FieldType::MFFloat, FieldType::SFFloat, float>(
          key, keyValue, options, fraction, problem);
    case FieldType::MFVec2f:
      return x3dinterp::splineOf<FieldType::MFVec2f, FieldType::SFVec2f, glm::vec2>(
          key, keyValue, options, fraction, problem);
    case FieldType::MFVec3f:
      return x3dinterp::splineOf<FieldType::MFVec3f, FieldType::SFVec3f, glm::vec3>(
          key, keyValue, options, fraction, problem);
    default:
      problem = "keyValue has the wrong type";
      return std::nullopt;
  }
}

glm::dquat squadIntermediate(const glm::dquat& previous, const glm::dquat& q,
                             const glm::dquat& next) {
  const glm::dquat inverse = glm::conjugate(q);
  const glm::dquat sum = x3dinterp::logUnit(inverse * x3dinterp::towards(q, next)) +
                         x3dinterp::logUnit(inverse * x3dinterp::towards(q, previous));
  return glm::normalize(q * x3dinterp::expPure(sum * -0.25));
}

std::optional<vrml::Rotation> interpolateSquad(const std::vector<float>& key,
                                               const std::vector<vrml::Rotation>& keyValue,
                                               float fraction, std::string& problem) {
  if (key.empty()) {
    problem = "key is empty";
    return std::nullopt;
  }
  if (keyValue.size() != key.size()) {
    problem = "keyValue has " + std::to_string(keyValue.size()) + " values for " +
              std::to_string(key.size()) + " keys";
    return std::nullopt;
  }
  const std::size_t n = key.size();
  if (n == 1) return x3dinterp::rotationOf(x3dinterp::quatOf(keyValue[0]));
  if (!std::isfinite(fraction)) fraction = 0.0f;
  const x3dinterp::Segment seg = x3dinterp::segmentOf(key, fraction);
  const std::size_t i = seg.i;
  // q_{i-1} .. q_{i+2}, each in the hemisphere of the one before.
  const glm::dquat qi = x3dinterp::quatOf(keyValue[i]);
  const glm::dquat qi1 = x3dinterp::towards(qi, x3dinterp::quatOf(keyValue[i + 1]));
  const glm::dquat si = i > 0 ? squadIntermediate(x3dinterp::quatOf(keyValue[i - 1]), qi, qi1) : qi;
  const glm::dquat si1 = i + 2 < n ? squadIntermediate(qi, qi1, x3dinterp::quatOf(keyValue[i + 2]))
                                   : qi1;  // the last key
  const double h = seg.s;
  return x3dinterp::rotationOf(x3dinterp::slerpPlain(
      x3dinterp::slerpPlain(qi, qi1, h), x3dinterp::slerpPlain(si, si1, h), 2.0 * h * (1.0 - h)));
}

std::optional<vrml::FieldValue> interpolateX3d(InterpolatorKind kind, const std::vector<float>& key,
                                               const vrml::FieldValue& keyValue,
                                               const SplineOptions& options, float fraction,
                                               std::string& problem) {
  using vrml::FieldType;
  using vrml::FieldValue;
  const auto wrongType = [&]() -> std::optional<FieldValue> {
    problem = "keyValue has the wrong type";
    return std::nullopt;
  };
  switch (kind) {
    case InterpolatorKind::EaseInEaseOut: {
      if (keyValue.type() != FieldType::MFVec2f) return wrongType();
      const auto f =
          easeInEaseOutFraction(key, keyValue.get<FieldType::MFVec2f>(), fraction, problem);
      if (!f) return std::nullopt;
      return FieldValue::make<FieldType::SFFloat>(*f);
    }
    case InterpolatorKind::SplinePosition:
      if (keyValue.type() != FieldType::MFVec3f) return wrongType();
      return interpolateSpline(key, keyValue, options, fraction, problem);
    case InterpolatorKind::SplinePosition2D:
      if (keyValue.type() != FieldType::MFVec2f) return wrongType();
      return interpolateSpline(key, keyValue, options, fraction, problem);
    case InterpolatorKind::SplineScalar:
      if (keyValue.type() != FieldType::MFFloat) return wrongType();
      return interpolateSpline(key, keyValue, options, fraction, problem);
    case InterpolatorKind::SquadOrientation: {
      if (keyValue.type() != FieldType::MFRotation) return wrongType();
      const auto r =
          interpolateSquad(key, keyValue.get<FieldType::MFRotation>(), fraction, problem);
      if (!r) return std::nullopt;
      return FieldValue::make<FieldType::SFRotation>(*r);
    }
    default:
      problem = "a linear interpolator (interpolate)";
      return std::nullopt;
  }
}

}  // namespace gs::runtime
