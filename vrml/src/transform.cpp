#include "vrml/transform.hpp"

#include "vrml/geo_nodes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gs::vrml {

glm::mat4 rotationMatrix(const Rotation& rotation) {
  const glm::vec3 axis(rotation);
  const float len = glm::length(axis);
  if (!(len > 0.0f) || rotation.w == 0.0f) return glm::mat4(1.0f);
  return glm::rotate(glm::mat4(1.0f), rotation.w, axis / len);
}

Rotation rotationFromQuaternion(glm::dquat q) {
  const double length = glm::length(q);
  if (!(length > 0.0) || !std::isfinite(length)) return {0.0f, 0.0f, 1.0f, 0.0f};
  q /= length;
  if (q.w < 0.0) q = -q;
  const double s = std::sqrt(std::max(0.0, 1.0 - q.w * q.w));
  if (s < 1e-9) return {0.0f, 0.0f, 1.0f, 0.0f};
  const double angle = 2.0 * std::acos(std::clamp(q.w, -1.0, 1.0));
  return {static_cast<float>(q.x / s), static_cast<float>(q.y / s), static_cast<float>(q.z / s),
          static_cast<float>(angle)};
}

glm::mat4 transformMatrix(const Node& t) {
  if (t.typeId() == NodeTypeId::GeoLocation)
    return glm::mat4(geoLocationMatrix(t, t.get<FieldType::SFVec3d>("geoCoords", glm::dvec3(0.0))));
  glm::dmat4 location(1.0);  // GeoTransform: the transform in the frame at geoCenter
  if (t.typeId() == NodeTypeId::GeoTransform)
    location = geoLocationMatrix(t, t.get<FieldType::SFVec3d>("geoCenter", glm::dvec3(0.0)));
  const glm::vec3 translation = t.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f));
  const glm::vec3 center = t.get<FieldType::SFVec3f>("center", glm::vec3(0.0f));
  const glm::vec3 scale = t.get<FieldType::SFVec3f>("scale", glm::vec3(1.0f));
  const glm::mat4 r =
      rotationMatrix(t.get<FieldType::SFRotation>("rotation", Rotation(0, 0, 1, 0)));
  const glm::mat4 sr =
      rotationMatrix(t.get<FieldType::SFRotation>("scaleOrientation", Rotation(0, 0, 1, 0)));
  glm::mat4 m = glm::translate(glm::mat4(1.0f), translation + center);
  m = m * r * sr;
  m = glm::scale(m, scale);
  m = m * glm::transpose(sr);  // -SR: the inverse of a rotation is its transpose
  m = glm::translate(m, -center);
  if (t.typeId() == NodeTypeId::GeoTransform)
    return glm::mat4(location * glm::dmat4(m) * glm::inverse(location));
  return m;
}

}  // namespace gs::vrml
