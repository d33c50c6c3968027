// Field types and values: VRML97's 20 (ISO/IEC 14772-1:1997, clause 5 "Field and event
// reference") and the 22 X3D adds (ISO/IEC 19775-1:2023 clause 5 "Field type reference":
// SFDouble, SFVec2d/3d, SFVec4f/4d, SFColorRGBA, SFMatrix3f/3d/4f/4d and their MF forms,
// MFBool, MFImage). Pure data: no parsing, no OpenGL.
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

/// The 20 VRML97 field types (clause 5), then the 22 of X3D. The enumerator order is also
/// the index of the matching alternative in FieldValue::Storage, so keep the two in step.
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
  // X3D (ISO/IEC 19775-1 clause 5): single values
  SFDouble,
  SFVec2d,
  SFVec3d,
  SFVec4f,
  SFVec4d,
  SFColorRGBA,
  SFMatrix3f,
  SFMatrix3d,
  SFMatrix4f,
  SFMatrix4d,
  // X3D: multiple values
  MFBool,
  MFDouble,
  MFImage,
  MFVec2d,
  MFVec3d,
  MFVec4f,
  MFVec4d,
  MFColorRGBA,
  MFMatrix3f,
  MFMatrix3d,
  MFMatrix4f,
  MFMatrix4d,
};
inline constexpr int kFieldTypeCount = 42;
/// VRML97's 20 types are the first 20 enumerators.
inline constexpr int kVrml97FieldTypeCount = 20;

/// Interface access types of clause 4.7 / 5: field, exposedField, eventIn, eventOut (X3D's
/// initializeOnly, inputOutput, inputOnly, outputOnly).
enum class AccessType : std::uint8_t { field, exposedField, eventIn, eventOut };

/// Spelling of a field type as VRML97 and X3D write it ("SFVec3f"); "?" for out-of-range
/// values.
std::string_view fieldTypeName(FieldType t);
/// Parses a field type name (VRML97's 20 and X3D's 22); false when `name` is none of them.
bool fieldTypeFromName(std::string_view name, FieldType& out);
/// Spelling of an access type as VRML97 writes it ("exposedField").
std::string_view accessTypeName(AccessType a);
/// Spelling of an access type as X3D writes it ("inputOutput").
std::string_view x3dAccessTypeName(AccessType a);
/// Parses an access type in either spelling (VRML97's "exposedField" or X3D's
/// "inputOutput"); false when `name` is neither. `x3d` tells which spelling it was.
bool accessTypeFromName(std::string_view name, AccessType& out, bool* x3d = nullptr);
/// True for the MF* types.
constexpr bool isMultiValued(FieldType t) {
  return (t >= FieldType::MFColor && t <= FieldType::MFVec3f) || t >= FieldType::MFBool;
}
/// The SF type of the elements of MF type `t` (SFColor for MFColor ...); `t` itself for
/// an SF type.
FieldType elementType(FieldType t);

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

/// A value kept on the heap so that a rarely used large alternative (a matrix, an image, a
/// string) does not make every FieldValue as large as itself: FieldValue stays 32 bytes,
/// which is what the event queue and every node's field array pay per value. Copies are
/// deep; a Boxed that holds nothing (default-constructed or moved from) reads as `T{}` and
/// allocates only when written through get().
template <class T>
class Boxed {
 public:
  Boxed() = default;
  Boxed(T value) : p_(std::make_unique<T>(std::move(value))) {}  // NOLINT: implicit on purpose
  Boxed(const Boxed& o) : p_(o.p_ ? std::make_unique<T>(*o.p_) : nullptr) {}
  Boxed(Boxed&&) noexcept = default;
  Boxed& operator=(const Boxed& o) {
    if (this != &o) p_ = o.p_ ? std::make_unique<T>(*o.p_) : nullptr;
    return *this;
  }
  Boxed& operator=(Boxed&&) noexcept = default;
  ~Boxed() = default;

  /// The value, `T{}` when none was stored.
  const T& get() const {
    static const T kEmpty{};
    return p_ ? *p_ : kEmpty;
  }
  /// The value for writing (allocated as `T{}` first when none was stored).
  T& get() {
    if (!p_) p_ = std::make_unique<T>();
    return *p_;
  }
  friend bool operator==(const Boxed& a, const Boxed& b) { return a.get() == b.get(); }

 private:
  std::unique_ptr<T> p_;
};

namespace detail {
template <class T>
T& unbox(T& v) {
  return v;
}
template <class T>
const T& unbox(const T& v) {
  return v;
}
template <class T>
T& unbox(Boxed<T>& b) {
  return b.get();
}
template <class T>
const T& unbox(const Boxed<T>& b) {
  return b.get();
}
}  // namespace detail

/// A field or event value of any of the 42 types. The active alternative's index equals
/// the FieldType enumerator; colours, vectors, rotations and matrices use glm (colour
/// components are in [0, 1]; times are seconds since 1970-01-01 UTC; angles are radians;
/// an SFColorRGBA is (r, g, b, a)). Matrices are glm's, column-major: the file's
/// row-major numbers are transposed when read (X3D clause 5.3.10).
class FieldValue {
 public:
  using Storage = std::variant<bool,                       // SFBool
                               glm::vec3,                  // SFColor
                               float,                      // SFFloat
                               Boxed<SFImage>,             // SFImage
                               std::int32_t,               // SFInt32
                               NodePtr,                    // SFNode (nullptr = NULL)
                               Rotation,                   // SFRotation
                               Boxed<std::string>,         // SFString
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
                               std::vector<glm::vec3>,     // MFVec3f
                               double,                     // SFDouble
                               glm::dvec2,                 // SFVec2d
                               glm::dvec3,                 // SFVec3d
                               glm::vec4,                  // SFVec4f
                               Boxed<glm::dvec4>,          // SFVec4d
                               glm::vec4,                  // SFColorRGBA
                               Boxed<glm::mat3>,           // SFMatrix3f
                               Boxed<glm::dmat3>,          // SFMatrix3d
                               Boxed<glm::mat4>,           // SFMatrix4f
                               Boxed<glm::dmat4>,          // SFMatrix4d
                               Boxed<std::vector<bool>>,   // MFBool
                               std::vector<double>,        // MFDouble
                               std::vector<SFImage>,       // MFImage
                               std::vector<glm::dvec2>,    // MFVec2d
                               std::vector<glm::dvec3>,    // MFVec3d
                               std::vector<glm::vec4>,     // MFVec4f
                               std::vector<glm::dvec4>,    // MFVec4d
                               std::vector<glm::vec4>,     // MFColorRGBA
                               std::vector<glm::mat3>,     // MFMatrix3f
                               std::vector<glm::dmat3>,    // MFMatrix3d
                               std::vector<glm::mat4>,     // MFMatrix4f
                               std::vector<glm::dmat4>>;   // MFMatrix4d

  /// A default-constructed value of type `t` (FALSE, 0, empty, NULL).
  explicit FieldValue(FieldType t = FieldType::SFBool);

  FieldType type() const { return static_cast<FieldType>(storage_.index()); }

  /// Typed access: `v.get<FieldType::MFVec3f>()`. Throws std::bad_variant_access when
  /// the value holds another type.
  template <FieldType T>
  auto& get() {
    return detail::unbox(std::get<static_cast<std::size_t>(T)>(storage_));
  }
  template <FieldType T>
  const auto& get() const {
    return detail::unbox(std::get<static_cast<std::size_t>(T)>(storage_));
  }
  /// Typed construction: `FieldValue::make<FieldType::SFFloat>(1.0f)`.
  template <FieldType T, class V>
  static FieldValue make(V&& v) {
    return FieldValue(std::in_place_index<static_cast<std::size_t>(T)>, std::forward<V>(v));
  }

  /// The variant itself: alternatives as listed above (the large ones as Boxed<T>). For
  /// comparing values (`a.storage() == b.storage()`) and for emplacing while parsing.
  Storage& storage() { return storage_; }
  const Storage& storage() const { return storage_; }

 private:
  template <std::size_t I, class V>
  FieldValue(std::in_place_index_t<I> i, V&& v) : storage_(i, std::forward<V>(v)) {}

  Storage storage_;
};

static_assert(sizeof(FieldValue) <= 32, "a FieldValue is what every field and event costs");

/// The VRML97 type nearest to `t` (itself for VRML97's 20): SFDouble -> SFTime, SFVec2d ->
/// SFVec2f, SFVec3d -> SFVec3f, SFVec4f/SFVec4d/SFColorRGBA -> SFRotation (4 floats),
/// SFMatrix* -> MFFloat (row by row), MFBool -> MFInt32 (0 or 1), MFDouble -> MFTime,
/// MFImage -> MFInt32 (empty), MFVec2d/3d -> MFVec2f/3f, MFVec4f/4d/MFColorRGBA ->
/// MFRotation, MFMatrix* -> MFFloat (all matrices' numbers). What a VRML97-only consumer
/// (the VRML97 ECMAScript classes, a .wrl writer) sees of an X3D value.
FieldType nearestVrml97Type(FieldType t);
/// `v` converted to nearestVrml97Type(v.type()) (doubles rounded to float).
FieldValue toNearestVrml97(const FieldValue& v);
/// The inverse of toNearestVrml97: `v` (of type nearestVrml97Type(t)) as a value of `t`;
/// FieldValue(t) when `v` has another type.
FieldValue fromNearestVrml97(FieldType t, const FieldValue& v);

}  // namespace gs::vrml
