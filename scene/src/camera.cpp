// Camera matrices and framing.
#include "scene/camera.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs::scene {

glm::mat4 viewMatrix(const Camera& camera) {
  const glm::mat4 rotation = glm::mat4_cast(glm::conjugate(glm::normalize(camera.orientation)));
  const glm::mat4 view = glm::translate(rotation, -camera.position);
  if (camera.deform == glm::mat3(1.0f)) return view;
  return glm::mat4(glm::inverse(camera.deform)) * view;
}

float verticalFieldOfView(float fieldOfView, float aspect) {
  const float fov = std::clamp(fieldOfView, 0.001f, 3.1f);
  if (!(aspect > 0.0f)) return fov;
  if (aspect >= 1.0f) return fov;
  // The field of view spans the width: convert to the vertical one.
  return 2.0f * std::atan(std::tan(fov * 0.5f) / aspect);
}

glm::mat4 projectionMatrix(const Camera& camera, float aspect) {
  if (!(aspect > 0.0f)) aspect = 1.0f;
  const float nearClip = std::max(camera.nearClip, 1e-6f);
  const float farClip = std::max(camera.farClip, nearClip * 1.001f);
  if (camera.orthographic) {
    const glm::vec4 r = camera.orthoRegion;
    float w = std::max(std::abs(r.z - r.x), 1e-6f), h = std::max(std::abs(r.w - r.y), 1e-6f);
    const float cx = (r.x + r.z) * 0.5f, cy = (r.y + r.w) * 0.5f;
    if (aspect > w / h)
      w = h * aspect;
    else
      h = w / aspect;
    return glm::ortho(cx - w * 0.5f, cx + w * 0.5f, cy - h * 0.5f, cy + h * 0.5f, nearClip,
                      farClip);
  }
  return glm::perspective(verticalFieldOfView(camera.fieldOfView, aspect), aspect, nearClip,
                          farClip);
}

void fitClipPlanes(Camera& camera, const vrml::Bounds& bounds, float maxNear) {
  if (bounds.empty()) return;
  const float radius = std::max(glm::length(bounds.size()) * 0.5f, 1e-4f);
  const float distance = glm::length(bounds.center() - camera.position);
  float farClip = (distance + radius) * 1.05f;
  float nearClip = std::max((distance - radius) * 0.95f, farClip / 10000.0f);
  if (camera.deform != glm::mat3(1.0f)) {
    // A deformed camera (a Viewpoint under a scaled Transform) measures depths in its own
    // units: the bounding sphere's centre seen through its view matrix, its radius
    // stretched by the most the view stretches a length (the largest singular value of
    // deform's inverse, by power iteration, 1% over).
    const glm::mat3 inverse = glm::inverse(camera.deform);
    const glm::mat3 gram = glm::transpose(inverse) * inverse;
    glm::vec3 v = glm::normalize(glm::vec3(1.0f, 0.7f, 0.4f));
    for (int k = 0; k < 24; ++k) {
      const glm::vec3 next = gram * v;
      const float len = glm::length(next);
      if (!(len > 0.0f)) break;
      v = next / len;
    }
    const float stretch = std::sqrt(std::max(glm::dot(v, gram * v), 0.0f)) * 1.01f;
    const float eyeDistance =
        glm::length(glm::vec3(viewMatrix(camera) * glm::vec4(bounds.center(), 1.0f)));
    const float eyeRadius = radius * stretch;
    if (std::isfinite(eyeDistance) && std::isfinite(eyeRadius) && eyeRadius > 0.0f) {
      farClip = (eyeDistance + eyeRadius) * 1.05f;
      nearClip = std::max((eyeDistance - eyeRadius) * 0.95f, farClip / 10000.0f);
    }
  }
  if (maxNear > 0.0f) nearClip = std::min(nearClip, maxNear);
  // A 24-bit depth buffer tells depths apart only while far / near stays well below 2^24:
  // a world of Earth's size (X3D Geospatial) seen from orbit would have every depth round
  // to the far plane's. At most 1e6, the near plane moved out.
  nearClip = std::max(nearClip, farClip / kMaxFarNearRatio);
  camera.nearClip = nearClip;
  camera.farClip = std::max(farClip, nearClip * 2.0f);
}

Camera wholeSceneCamera(const vrml::Bounds& bounds, const Camera& defaults) {
  Camera camera = defaults;
  if (bounds.empty()) return camera;
  const glm::vec3 size = bounds.size();
  const float offset = 2.0f * (size.x + size.y + size.z) / 3.0f;
  const glm::vec3 center = bounds.center();
  camera.orientation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  camera.position = glm::vec3(center.x, center.y, bounds.max.z + std::max(offset, 1e-4f));
  fitClipPlanes(camera, bounds);
  return camera;
}

Camera fitCamera(const vrml::Bounds& bounds, float aspect, const Camera& direction) {
  Camera camera = direction;
  if (bounds.empty()) return camera;
  if (!(aspect > 0.0f)) aspect = 1.0f;
  camera.orientation = glm::normalize(camera.orientation);
  const float tanV = std::tan(verticalFieldOfView(camera.fieldOfView, aspect) * 0.5f);
  const float tanH = tanV * aspect;
  const glm::vec3 center = bounds.center();
  const glm::vec3 right = camera.right(), up = camera.up(), forward = camera.forward();
  // The smallest distance back from the centre at which every corner of the box lies
  // inside the view frustum: for a corner at (x, y) across and z along the view from the
  // centre, |x| <= (d + z) tanH and |y| <= (d + z) tanV.
  float distance = 0.0f;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x,
                           (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec3 p = corner - center;
    const float x = std::abs(glm::dot(p, right)), y = std::abs(glm::dot(p, up));
    const float z = glm::dot(p, forward);
    distance = std::max({distance, x / tanH - z, y / tanV - z});
  }
  const float radius = std::max(glm::length(bounds.size()) * 0.5f, 1e-4f);
  distance = std::max(distance * 1.05f, radius * 1e-3f);  // a 5% margin
  camera.position = center - forward * distance;
  fitClipPlanes(camera, bounds);
  return camera;
}

UserOffset userOffset(const Camera& user, const Camera& defined) {
  const glm::quat inverse = glm::inverse(defined.orientation);
  return {inverse * (user.position - defined.position), glm::normalize(inverse * user.orientation)};
}

Camera withUserOffset(const Camera& defined, const UserOffset& offset) {
  Camera c = defined;
  c.position = defined.position + defined.orientation * offset.translation;
  c.orientation = glm::normalize(defined.orientation * offset.rotation);
  return c;
}

}  // namespace gs::scene
