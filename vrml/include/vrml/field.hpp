// VRML97 field types and values (ISO/IEC 14772-1:1997, clause 5 "Field and event
// reference"). Pure data: no parsing, no OpenGL.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace gs::vrml {

class Node;
using NodePtr = std::shared_ptr<Node>;

/// The 20 VRML97 field types (clause 5). The enumerator order is also the index of the
/// matching alternative in FieldValue::Storage, so keep the two in step.
enum class FieldType : std::uint8_t {
  SFBool,
  SFColor,
  SFFloat,
  SFImage,
  SFInt32,
  SFNode,
  SFRotation,
  SFString,
  SFTime,
  SFVec2f,
  SFVec3f,
  MFColor,
  MFFloat,
  MFInt32,
  MFNode,
  MFRotation,
  MFString,
  MFTime,
  MFVec2f,
  MFVec3f,
};
inline constexpr int kFieldTypeCount = 20;

/// Interface access types of clause 4.7 / 5: field, exposedField, eventIn, eventOut.
enum class AccessType : std::uint8_t { field, exposedField, eventIn, eventOut };

/// Spelling of a field type as VRML97 writes it ("SFVec3f"); "?" for out-of-range values.
std::string_view fieldTypeName(FieldType t);
/// Parses a VRML97 field type name; returns false when `name` is not one of the 20.
bool fieldTypeFromName(std::string_view name, FieldType& out);
/// Spelling of an access type as VRML97 writes it ("exposedField").
std::string_view accessTypeName(AccessType a);
/// True for the MF* types.
constexpr bool isMultiValued(FieldType t) {
  return t >= FieldType::MFColor;
}

/// SFImage (clause 5.5): width, height, number of components (0..4) and one packed pixel
/// per entry, rows bottom to top, each pixel 0xRRGGBBAA-style packed as the file wrote it
/// (1 component: 0xII, 2: 0xIIAA, 3: 0xRRGGBB, 4: 0xRRGGBBAA).
struct SFImage {
  int width = 0;
  int height = 0;
  int components = 0;
  std::vector<std::uint32_t> pixels;  // width * height entries
  bool operator==(const SFImage&) const = default;
};

/// A rotation as axis (x, y, z, not necessarily unit length in the file) and angle in
/// radians, stored as (x, y, z, angle) (clause 5.8).
using Rotation = glm::vec4;

/// A field or event value of any of the 20 types. The active alternative's index equals
/// the FieldType enumerator; colours, vectors and rotations use glm (colour components
/// are in [0, 1]; times are seconds since 1970-01-01 UTC; angles are radians).
class FieldValue {
 public:
  using Storage = std::variant<bool,                       // SFBool
                               glm::vec3,                  // SFColor
                               float,                      // SFFloat
                               SFImage,                    // SFImage
                               std::int32_t,               // SFInt32
                               NodePtr,                    // SFNode (nullptr = NULL)
                               Rotation,                   // SFRotation
                               std::string,                // SFString
                               double,                     // SFTime
                               glm::vec2,                  // SFVec2f
                               glm::vec3,                  // SFVec3f
                               std::vector<glm::vec3>,     // MFColor
                               std::vector<float>,         // MFFloat
                               std::vector<std::int32_t>,  // MFInt32
                               std::vector<NodePtr>,       // MFNode
                               std::vector<Rotation>,      // MFRotation
                               std::vector<std::string>,   // MFString
                               std::vector<double>,        // MFTime
                               std::vector<glm::vec2>,     // MFVec2f
                               std::vector<glm::vec3>>;    // MFVec3f

  /// A default-constructed value of type `t` (FALSE, 0, empty, NULL).
  explicit FieldValue(FieldType t = FieldType::SFBool);

  FieldType type() const { return static_cast<FieldType>(storage_.index()); }

  /// Typed access: `v.get<FieldType::MFVec3f>()`. Throws std::bad_variant_access when
  /// the value holds another type.
  template <FieldType T>
  auto& get() {
    return std::get<static_cast<std::size_t>(T)>(storage_);
  }
  template <FieldType T>
  const auto& get() const {
    return std::get<static_cast<std::size_t>(T)>(storage_);
  }
  /// Typed construction: `FieldValue::make<FieldType::SFFloat>(1.0f)`.
  template <FieldType T, class V>
  static FieldValue make(V&& v) {
    FieldValue f;
    f.storage_.template emplace<static_cast<std::size_t>(T)>(std::forward<V>(v));
    return f;
  }

  Storage& storage() { return storage_; }
  const Storage& storage() const { return storage_; }

 private:
  Storage storage_;
};

}  // namespace gs::vrml
