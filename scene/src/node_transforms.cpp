// The matrices of the grouping and texture nodes: LOD level choice (6.26), Billboard
// (6.6) and TextureTransform (6.51); Transform matrices are in vrml/transform.hpp.
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gs::scene {

int selectLodLevel(const std::vector<float>& range, float distance, std::size_t levelCount) {
  if (levelCount == 0) return -1;
  std::size_t level = 0;
  while (level < range.size() && distance >= range[level]) ++level;
  return static_cast<int>(std::min(level, levelCount - 1));
}

glm::mat4 billboardRotation(const glm::vec3& axisOfRotation, const glm::vec3& viewer,
                            const glm::vec3& viewerUp) {
  const float axisLength = glm::length(axisOfRotation);
  if (axisLength < 1e-9f) {
    // Viewer-aligned: Z towards the viewer, Y along the viewer's up vector.
    if (glm::length(viewer) < 1e-9f) return glm::mat4(1.0f);
    const glm::vec3 z = glm::normalize(viewer);
    glm::vec3 x = glm::cross(viewerUp, z);
    if (glm::length(x) < 1e-9f) return glm::mat4(1.0f);
    x = glm::normalize(x);
    const glm::vec3 y = glm::cross(z, x);
    return glm::mat4(glm::mat3(x, y, z));
  }
  const glm::vec3 axis = axisOfRotation / axisLength;
  // The viewer direction and the local Z axis, both projected on the plane normal to axis.
  const glm::vec3 toViewer = viewer - glm::dot(viewer, axis) * axis;
  const glm::vec3 localZ = glm::vec3(0, 0, 1) - axis.z * axis;
  if (glm::length(toViewer) < 1e-9f || glm::length(localZ) < 1e-9f) return glm::mat4(1.0f);
  const glm::vec3 to = glm::normalize(toViewer), from = glm::normalize(localZ);
  const float angle = std::atan2(glm::dot(glm::cross(from, to), axis), glm::dot(from, to));
  return glm::rotate(glm::mat4(1.0f), angle, axis);
}

namespace {

/// The 2D part of a 3D texture matrix acting on (s, t, 0, 1).
glm::mat3 planar(const glm::mat4& m) {
  glm::mat3 out(1.0f);
  out[0] = glm::vec3(m[0].x, m[0].y, 0.0f);
  out[1] = glm::vec3(m[1].x, m[1].y, 0.0f);
  out[2] = glm::vec3(m[3].x, m[3].y, 1.0f);
  return out;
}

}  // namespace

glm::mat4 textureTransformMatrix3D(const vrml::Node& tt) {
  switch (tt.typeId()) {
    case vrml::NodeTypeId::MultiTextureTransform: {
      const std::vector<vrml::NodePtr>& list = tt.mfnode("textureTransform");
      return !list.empty() && list.front() && list.front().get() != &tt
                 ? textureTransformMatrix3D(*list.front())
                 : glm::mat4(1.0f);
    }
    case vrml::NodeTypeId::TextureTransformMatrix3D:
      // The file writes the matrix row by row for row vectors (translation in its last
      // row, as X_ITE and VRML97's VrmlMatrix read it); GLM multiplies column vectors.
      return glm::transpose(tt.get<vrml::FieldType::SFMatrix4f>("matrix", glm::mat4(1.0f)));
    case vrml::NodeTypeId::TextureTransform3D: {
      const glm::vec3 c = sfVec3(tt, "center", glm::vec3(0.0f));
      const glm::vec3 s = sfVec3(tt, "scale", glm::vec3(1.0f));
      const glm::vec3 t = sfVec3(tt, "translation", glm::vec3(0.0f));
      const vrml::Rotation r = sfRotation(tt, "rotation", vrml::Rotation(0, 0, 1, 0));
      const glm::vec3 axis(r.x, r.y, r.z);
      const glm::mat4 rot = glm::length(axis) > 1e-12f
                                ? glm::rotate(glm::mat4(1.0f), r.w, glm::normalize(axis))
                                : glm::mat4(1.0f);
      return glm::translate(glm::mat4(1.0f), -c) * glm::scale(glm::mat4(1.0f), s) * rot *
             glm::translate(glm::mat4(1.0f), c) * glm::translate(glm::mat4(1.0f), t);
    }
    default: {  // a 2D transform acting on (s, t) and leaving r alone
      const glm::mat3 m = textureTransformMatrix(tt);
      glm::mat4 out(1.0f);
      out[0] = glm::vec4(m[0].x, m[0].y, 0.0f, 0.0f);
      out[1] = glm::vec4(m[1].x, m[1].y, 0.0f, 0.0f);
      out[3] = glm::vec4(m[2].x, m[2].y, 0.0f, 1.0f);
      return out;
    }
  }
}

glm::mat3 textureTransformMatrix(const vrml::Node& tt) {
  switch (tt.typeId()) {
    case vrml::NodeTypeId::MultiTextureTransform: {
      const std::vector<vrml::NodePtr>& list = tt.mfnode("textureTransform");
      return !list.empty() && list.front() && list.front().get() != &tt
                 ? textureTransformMatrix(*list.front())
                 : glm::mat3(1.0f);
    }
    case vrml::NodeTypeId::TextureTransformMatrix3D:
    case vrml::NodeTypeId::TextureTransform3D:
      return planar(textureTransformMatrix3D(tt));
    default:
      break;
  }
  const glm::vec2 c = sfVec2(tt, "center", glm::vec2(0.0f));
  const glm::vec2 s = sfVec2(tt, "scale", glm::vec2(1.0f));
  const glm::vec2 t = sfVec2(tt, "translation", glm::vec2(0.0f));
  const float a = sfFloat(tt, "rotation", 0.0f);
  auto translate = [](glm::vec2 v) {
    glm::mat3 m(1.0f);
    m[2] = glm::vec3(v, 1.0f);
    return m;
  };
  glm::mat3 rot(1.0f);
  rot[0] = glm::vec3(std::cos(a), std::sin(a), 0.0f);
  rot[1] = glm::vec3(-std::sin(a), std::cos(a), 0.0f);
  glm::mat3 scale(1.0f);
  scale[0][0] = s.x;
  scale[1][1] = s.y;
  return translate(-c) * scale * rot * translate(c) * translate(t);
}

}  // namespace gs::scene
