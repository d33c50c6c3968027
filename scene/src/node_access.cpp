// The field accessors of node_access.hpp that return references to shared empty values.
#include "scene/node_access.hpp"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>

namespace gs::scene {

const std::vector<float>& mfFloat(const vrml::Node& n, vrml::FieldName name) {
  static const std::vector<float> kEmpty;
  return fieldRef<vrml::FieldType::MFFloat>(n, name, kEmpty);
}
const std::vector<glm::vec3>& mfColor(const vrml::Node& n, vrml::FieldName name) {
  static const std::vector<glm::vec3> kEmpty;
  return fieldRef<vrml::FieldType::MFColor>(n, name, kEmpty);
}
const std::vector<std::string>& mfString(const vrml::Node& n, vrml::FieldName name) {
  static const std::vector<std::string> kEmpty;
  return fieldRef<vrml::FieldType::MFString>(n, name, kEmpty);
}
const std::string& sfString(const vrml::Node& n, vrml::FieldName name) {
  static const std::string kEmpty;
  return fieldRef<vrml::FieldType::SFString>(n, name, kEmpty);
}
glm::mat3 rotationPart(const glm::mat4& m) {
  glm::mat3 r(m);
  for (int c = 0; c < 3; ++c) {
    const float len = glm::length(r[c]);
    r[c] = len > 0.0f ? r[c] / len : glm::vec3(c == 0, c == 1, c == 2);
  }
  return r;
}
float meanScale(const glm::mat4& m) {
  return std::cbrt(std::abs(glm::determinant(glm::mat3(m))));
}

}  // namespace gs::scene
