// X3D Texture projection (X3D 4.0 clause 42): where a TextureProjector or
// TextureProjectorParallel stands and how it projects, as X_ITE 15 computes it
// (docs/x3d.md "Texture projection"); the renderer multiplies the shapes' colour by it.
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace gs::scene {

bool textureProjectorInstance(const vrml::Node& n, const glm::mat4& m,
                              TextureProjectorInstance& out) {
  if (!sfBool(n, "on", true)) return false;
  const float intensity = sfFloat(n, "intensity", 1.0f);
  if (!(intensity > 0.0f)) return false;
  const vrml::NodePtr& texture = n.sfnode("texture");
  if (!texture || texture->unresolved) return false;
  const vrml::NodeTypeId t = texture->typeId();
  if (t != vrml::NodeTypeId::ImageTexture && t != vrml::NodeTypeId::PixelTexture &&
      t != vrml::NodeTypeId::MovieTexture)
    return false;
  const glm::vec3 direction = sfVec3(n, "direction", glm::vec3(0, 0, 1));
  const float length = glm::length(direction);
  if (!(length > 1e-12f) || !std::isfinite(length)) return false;
  // The frame: z = -direction, x = up x z, y = z x x (a lookAt; no roll when up is
  // parallel to the direction).
  const glm::vec3 z = -direction / length;
  glm::vec3 up = sfVec3(n, "upVector", glm::vec3(0, 1, 0));
  glm::vec3 x = glm::cross(up, z);
  if (!(glm::length(x) > 1e-6f)) {
    up = std::abs(z.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    x = glm::cross(up, z);
  }
  x = glm::normalize(x);
  const glm::vec3 y = glm::cross(z, x);
  glm::mat4 frame(1.0f);
  frame[0] = glm::vec4(x, 0.0f);
  frame[1] = glm::vec4(y, 0.0f);
  frame[2] = glm::vec4(z, 0.0f);
  frame[3] = glm::vec4(sfVec3(n, "location", glm::vec3(0.0f)), 1.0f);
  out.node = &n;
  out.projectorToWorld = m * frame;
  out.parallel = n.typeId() == vrml::NodeTypeId::TextureProjectorParallel;
  if (out.parallel) {
    out.area = n.get<vrml::FieldType::SFVec4f>("fieldOfView", glm::vec4(-1, -1, 1, 1));
  } else {
    const float f = sfFloat(n, "fieldOfView", 0.785398f);
    out.fieldOfView = f > 0.0f && f < std::numbers::pi_v<float> ? f : 0.785398f;
  }
  out.nearDistance = sfFloat(n, "nearDistance", -1.0f);
  out.farDistance = sfFloat(n, "farDistance", -1.0f);
  out.color = glm::clamp(sfColor(n, "color", glm::vec3(1.0f)), 0.0f, 1.0f);
  out.intensity = intensity;
  return true;
}

glm::mat4 textureProjection(const TextureProjectorInstance& p, int width, int height) {
  const float nearPlane = p.nearDistance < 0.0f ? 0.125f : p.nearDistance;
  float farPlane = p.farDistance < 0.0f ? 100000.0f : p.farDistance;
  if (!(farPlane > nearPlane)) farPlane = nearPlane + 1.0f;
  const float w = width > 0 && height > 0 ? static_cast<float>(width) : 1.0f;
  const float h = width > 0 && height > 0 ? static_cast<float>(height) : 1.0f;
  if (!p.parallel) {
    const float r = std::tan(p.fieldOfView / 2.0f) * nearPlane;
    if (w > h) return glm::frustum(-r * w / h, r * w / h, -r, r, nearPlane, farPlane);
    return glm::frustum(-r, r, -r * h / w, r * h / w, nearPlane, farPlane);
  }
  const glm::vec4& a = p.area;
  const float aspect = w / h;
  const float sizeX = a.z - a.x, sizeY = a.w - a.y;
  if (!(sizeX > 0.0f) || !(sizeY > 0.0f))
    return glm::ortho(-1.0f, 1.0f, -1.0f, 1.0f, nearPlane, farPlane);
  if (aspect > sizeX / sizeY) {
    const float c = (a.x + a.z) / 2.0f, half = sizeY * aspect / 2.0f;
    return glm::ortho(c - half, c + half, a.y, a.w, nearPlane, farPlane);
  }
  const float c = (a.y + a.w) / 2.0f, half = sizeX / aspect / 2.0f;
  return glm::ortho(a.x, a.z, c - half, c + half, nearPlane, farPlane);
}

}  // namespace gs::scene
