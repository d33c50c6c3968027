// Typed, allocation-free access to node fields with the VRML97
// defaults as fallbacks (a node whose type lacks a field reads as the default).
#pragma once

#include "vrml/node.hpp"

#include <string_view>

namespace gs::scene {

/// Reference to the value of field `name` of type T, or to `fallback` when the field is
/// missing or of another type. `fallback` must outlive the reference (use statics or
/// literals bound to long-lived objects).
template <vrml::FieldType T, class V>
const V& fieldRef(const vrml::Node& node, vrml::FieldName name, const V& fallback) {
  const vrml::FieldValue* f = node.field(name);
  if (f == nullptr || f->type() != T) return fallback;
  return f->get<T>();
}

inline bool sfBool(const vrml::Node& n, vrml::FieldName name, bool fallback) {
  return n.get<vrml::FieldType::SFBool>(name, fallback);
}
inline float sfFloat(const vrml::Node& n, vrml::FieldName name, float fallback) {
  return n.get<vrml::FieldType::SFFloat>(name, fallback);
}
inline int sfInt(const vrml::Node& n, vrml::FieldName name, int fallback) {
  return n.get<vrml::FieldType::SFInt32>(name, fallback);
}
inline glm::vec3 sfVec3(const vrml::Node& n, vrml::FieldName name, glm::vec3 fallback) {
  return n.get<vrml::FieldType::SFVec3f>(name, fallback);
}
inline glm::vec3 sfColor(const vrml::Node& n, vrml::FieldName name, glm::vec3 fallback) {
  return n.get<vrml::FieldType::SFColor>(name, fallback);
}
inline glm::vec2 sfVec2(const vrml::Node& n, vrml::FieldName name, glm::vec2 fallback) {
  return n.get<vrml::FieldType::SFVec2f>(name, fallback);
}
inline vrml::Rotation sfRotation(const vrml::Node& n, vrml::FieldName name,
                                 vrml::Rotation fallback) {
  return n.get<vrml::FieldType::SFRotation>(name, fallback);
}
const std::vector<float>& mfFloat(const vrml::Node& n, vrml::FieldName name);
const std::vector<glm::vec3>& mfColor(const vrml::Node& n, vrml::FieldName name);
const std::vector<std::string>& mfString(const vrml::Node& n, vrml::FieldName name);
const std::string& sfString(const vrml::Node& n, vrml::FieldName name);

/// Upper-left 3x3 of `m` with its columns normalized (the rotation of a transform without
/// shear).
glm::mat3 rotationPart(const glm::mat4& m);
/// Cube root of |det| of the upper-left 3x3: the mean scale factor of `m`.
float meanScale(const glm::mat4& m);

}  // namespace gs::scene
