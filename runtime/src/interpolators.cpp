// Clause 4.6.8 and the six interpolator nodes of part 6; X3D's linear 2D interpolators
// (X3D 4.0 19.4.3, 19.4.8).
#include "runtime/interpolators.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace gs::runtime {

KeySpan findKeySpan(const std::vector<float>& key, float fraction) {
  const std::size_t n = key.size();
  if (n <= 1 || !(fraction > key.front())) return {0, 0.0f};
  if (fraction >= key.back()) return {n - 1, 0.0f};
  // The last key <= fraction: with equal keys (a step) the later value wins at the key.
  const auto it = std::upper_bound(key.begin(), key.end(), fraction);
  const std::size_t i = static_cast<std::size_t>(it - key.begin()) - 1;
  const float span = key[i + 1] - key[i];
  const float t = span > 0.0f ? (fraction - key[i]) / span : 0.0f;
  return {i, std::clamp(t, 0.0f, 1.0f)};
}

namespace {

glm::quat toQuat(const vrml::Rotation& r) {
  const glm::vec3 axis(r.x, r.y, r.z);
  const float len = glm::length(axis);
  if (!(len > 0.0f) || !std::isfinite(r.w)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return glm::angleAxis(r.w, axis / len);
}

vrml::Rotation fromQuat(glm::quat q) {
  q = glm::normalize(q);
  if (q.w < 0.0f) q = -q;
  const float s = std::sqrt(std::max(0.0f, 1.0f - q.w * q.w));
  const float angle = 2.0f * std::acos(std::clamp(q.w, -1.0f, 1.0f));
  if (s < 1e-6f) return {0.0f, 0.0f, 1.0f, 0.0f};
  return {q.x / s, q.y / s, q.z / s, angle};
}

template <class T>
T mixValue(const T& a, const T& b, float t) {
  return a + (b - a) * t;
}

}  // namespace

vrml::Rotation slerpRotation(const vrml::Rotation& a, const vrml::Rotation& b, float t) {
  glm::quat qa = toQuat(a), qb = toQuat(b);
  if (glm::dot(qa, qb) < 0.0f) qb = -qb;  // the shorter arc
  return fromQuat(glm::slerp(qa, qb, t));
}

glm::vec3 slerpNormal(const glm::vec3& a, const glm::vec3& b, float t) {
  const float la = glm::length(a), lb = glm::length(b);
  if (!(la > 0.0f) || !(lb > 0.0f)) return mixValue(a, b, t);
  const glm::vec3 ua = a / la, ub = b / lb;
  const float cosine = std::clamp(glm::dot(ua, ub), -1.0f, 1.0f);
  const float omega = std::acos(cosine);
  if (omega < 1e-5f) return glm::normalize(mixValue(ua, ub, t));
  const float s = std::sin(omega);
  if (s < 1e-6f) return glm::normalize(mixValue(ua, ub, t));  // opposite: no unique arc
  return (std::sin((1.0f - t) * omega) / s) * ua + (std::sin(t * omega) / s) * ub;
}

namespace {

/// One value per key.
template <vrml::FieldType T, class V, class Mix>
std::optional<vrml::FieldValue> single(const std::vector<float>& key, const std::vector<V>& values,
                                       float fraction, std::string& problem, Mix mix) {
  if (values.size() != key.size()) {
    problem = "keyValue has " + std::to_string(values.size()) + " values for " +
              std::to_string(key.size()) + " keys";
    return std::nullopt;
  }
  const KeySpan s = findKeySpan(key, fraction);
  const V v = s.index + 1 < values.size() ? mix(values[s.index], values[s.index + 1], s.t)
                                          : values[s.index];
  return vrml::FieldValue::make<T>(v);
}

/// keyValue.size() / key.size() values per key (Coordinate, Coordinate2D, Normal); `T` is
/// the MF type of value_changed.
template <vrml::FieldType T, class V, class Mix>
std::optional<vrml::FieldValue> multiple(const std::vector<float>& key,
                                         const std::vector<V>& values, float fraction,
                                         std::string& problem, Mix mix) {
  if (values.size() % key.size() != 0) {
    problem = "keyValue has " + std::to_string(values.size()) + " values, not a multiple of the " +
              std::to_string(key.size()) + " keys";
    return std::nullopt;
  }
  const std::size_t n = values.size() / key.size();
  const KeySpan s = findKeySpan(key, fraction);
  std::vector<V> out(n);
  const V* a = values.data() + s.index * n;
  if (s.index + 1 < key.size()) {
    const V* b = a + n;
    for (std::size_t i = 0; i < n; ++i) out[i] = mix(a[i], b[i], s.t);
  } else {
    std::copy(a, a + n, out.begin());
  }
  return vrml::FieldValue::make<T>(std::move(out));
}

}  // namespace

std::optional<vrml::FieldValue> interpolate(InterpolatorKind kind, const std::vector<float>& key,
                                            const vrml::FieldValue& keyValue, float fraction,
                                            std::string& problem) {
  using vrml::FieldType;
  if (key.empty()) {
    problem = "key is empty";
    return std::nullopt;
  }
  if (!std::isfinite(fraction)) fraction = 0.0f;
  auto lerp = [](const auto& a, const auto& b, float t) { return mixValue(a, b, t); };
  switch (kind) {
    case InterpolatorKind::Color:
      if (keyValue.type() != FieldType::MFColor) break;
      return single<FieldType::SFColor>(key, keyValue.get<FieldType::MFColor>(), fraction, problem,
                                        lerp);
    case InterpolatorKind::Position:
      if (keyValue.type() != FieldType::MFVec3f) break;
      return single<FieldType::SFVec3f>(key, keyValue.get<FieldType::MFVec3f>(), fraction, problem,
                                        lerp);
    case InterpolatorKind::Scalar:
      if (keyValue.type() != FieldType::MFFloat) break;
      return single<FieldType::SFFloat>(key, keyValue.get<FieldType::MFFloat>(), fraction, problem,
                                        lerp);
    case InterpolatorKind::Orientation:
      if (keyValue.type() != FieldType::MFRotation) break;
      return single<FieldType::SFRotation>(key, keyValue.get<FieldType::MFRotation>(), fraction,
                                           problem, slerpRotation);
    case InterpolatorKind::Coordinate:
      if (keyValue.type() != FieldType::MFVec3f) break;
      return multiple<FieldType::MFVec3f>(key, keyValue.get<FieldType::MFVec3f>(), fraction,
                                          problem, lerp);
    case InterpolatorKind::Normal:
      if (keyValue.type() != FieldType::MFVec3f) break;
      return multiple<FieldType::MFVec3f>(key, keyValue.get<FieldType::MFVec3f>(), fraction,
                                          problem, slerpNormal);
    case InterpolatorKind::Position2D:  // X3D 4.0 19.4.8
      if (keyValue.type() != FieldType::MFVec2f) break;
      return single<FieldType::SFVec2f>(key, keyValue.get<FieldType::MFVec2f>(), fraction, problem,
                                        lerp);
    case InterpolatorKind::Coordinate2D:  // X3D 4.0 19.4.3
      if (keyValue.type() != FieldType::MFVec2f) break;
      return multiple<FieldType::MFVec2f>(key, keyValue.get<FieldType::MFVec2f>(), fraction,
                                          problem, lerp);
    case InterpolatorKind::EaseInEaseOut:
    case InterpolatorKind::SplinePosition:
    case InterpolatorKind::SplinePosition2D:
    case InterpolatorKind::SplineScalar:
    case InterpolatorKind::SquadOrientation:
      problem = "a non-linear interpolator (interpolateX3d)";
      return std::nullopt;
  }
  problem = "keyValue has the wrong type";
  return std::nullopt;
}

}  // namespace gs::runtime
