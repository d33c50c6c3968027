#include "vrml/field.hpp"

#include <array>

namespace gs::vrml {

namespace {
constexpr std::array<std::string_view, kFieldTypeCount> kFieldTypeNames = {
    "SFBool", "SFColor", "SFFloat", "SFImage", "SFInt32", "SFNode", "SFRotation", "SFString",
    "SFTime", "SFVec2f", "SFVec3f", "MFColor", "MFFloat", "MFInt32", "MFNode", "MFRotation",
    "MFString", "MFTime", "MFVec2f", "MFVec3f",
    // X3D
    "SFDouble", "SFVec2d", "SFVec3d", "SFVec4f", "SFVec4d", "SFColorRGBA", "SFMatrix3f",
    "SFMatrix3d", "SFMatrix4f", "SFMatrix4d", "MFBool", "MFDouble", "MFImage", "MFVec2d", "MFVec3d",
    "MFVec4f", "MFVec4d", "MFColorRGBA", "MFMatrix3f", "MFMatrix3d", "MFMatrix4f", "MFMatrix4d"};

// One constructor per alternative, picked by index (a jump, not 42 comparisons: make()
// and every node's default fields come through here).
template <std::size_t... I>
FieldValue::Storage makeDefault(std::size_t index, std::index_sequence<I...>) {
  using Make = FieldValue::Storage (*)();
  static constexpr Make kMake[] = {
      +[]() -> FieldValue::Storage { return FieldValue::Storage(std::in_place_index<I>); }...};
  return index < sizeof...(I) ? kMake[index]() : FieldValue::Storage();
}
}  // namespace

std::string_view fieldTypeName(FieldType t) {
  const auto i = static_cast<std::size_t>(t);
  return i < kFieldTypeNames.size() ? kFieldTypeNames[i] : std::string_view("?");
}

bool fieldTypeFromName(std::string_view name, FieldType& out) {
  for (std::size_t i = 0; i < kFieldTypeNames.size(); ++i) {
    if (kFieldTypeNames[i] == name) {
      out = static_cast<FieldType>(i);
      return true;
    }
  }
  return false;
}

std::string_view accessTypeName(AccessType a) {
  switch (a) {
    case AccessType::field:
      return "field";
    case AccessType::exposedField:
      return "exposedField";
    case AccessType::eventIn:
      return "eventIn";
    case AccessType::eventOut:
      return "eventOut";
  }
  return "?";
}

std::string_view x3dAccessTypeName(AccessType a) {
  switch (a) {
    case AccessType::field:
      return "initializeOnly";
    case AccessType::exposedField:
      return "inputOutput";
    case AccessType::eventIn:
      return "inputOnly";
    case AccessType::eventOut:
      return "outputOnly";
  }
  return "?";
}

bool accessTypeFromName(std::string_view name, AccessType& out, bool* x3d) {
  static constexpr AccessType kAll[] = {AccessType::field, AccessType::exposedField,
                                        AccessType::eventIn, AccessType::eventOut};
  for (AccessType a : kAll) {
    if (name == accessTypeName(a) || name == x3dAccessTypeName(a)) {
      out = a;
      if (x3d != nullptr) *x3d = name == x3dAccessTypeName(a);
      return true;
    }
  }
  return false;
}

FieldType elementType(FieldType t) {
  switch (t) {
    case FieldType::MFColor:
      return FieldType::SFColor;
    case FieldType::MFFloat:
      return FieldType::SFFloat;
    case FieldType::MFInt32:
      return FieldType::SFInt32;
    case FieldType::MFNode:
      return FieldType::SFNode;
    case FieldType::MFRotation:
      return FieldType::SFRotation;
    case FieldType::MFString:
      return FieldType::SFString;
    case FieldType::MFTime:
      return FieldType::SFTime;
    case FieldType::MFVec2f:
      return FieldType::SFVec2f;
    case FieldType::MFVec3f:
      return FieldType::SFVec3f;
    case FieldType::MFBool:
      return FieldType::SFBool;
    case FieldType::MFDouble:
      return FieldType::SFDouble;
    case FieldType::MFImage:
      return FieldType::SFImage;
    case FieldType::MFVec2d:
      return FieldType::SFVec2d;
    case FieldType::MFVec3d:
      return FieldType::SFVec3d;
    case FieldType::MFVec4f:
      return FieldType::SFVec4f;
    case FieldType::MFVec4d:
      return FieldType::SFVec4d;
    case FieldType::MFColorRGBA:
      return FieldType::SFColorRGBA;
    case FieldType::MFMatrix3f:
      return FieldType::SFMatrix3f;
    case FieldType::MFMatrix3d:
      return FieldType::SFMatrix3d;
    case FieldType::MFMatrix4f:
      return FieldType::SFMatrix4f;
    case FieldType::MFMatrix4d:
      return FieldType::SFMatrix4d;
    default:
      return t;
  }
}

FieldType nearestVrml97Type(FieldType t) {
  switch (t) {
    case FieldType::SFDouble:
      return FieldType::SFTime;
    case FieldType::SFVec2d:
      return FieldType::SFVec2f;
    case FieldType::SFVec3d:
      return FieldType::SFVec3f;
    case FieldType::SFVec4f:
    case FieldType::SFVec4d:
    case FieldType::SFColorRGBA:
      return FieldType::SFRotation;
    case FieldType::SFMatrix3f:
    case FieldType::SFMatrix3d:
    case FieldType::SFMatrix4f:
    case FieldType::SFMatrix4d:
    case FieldType::MFMatrix3f:
    case FieldType::MFMatrix3d:
    case FieldType::MFMatrix4f:
    case FieldType::MFMatrix4d:
      return FieldType::MFFloat;
    case FieldType::MFBool:
    case FieldType::MFImage:
      return FieldType::MFInt32;
    case FieldType::MFDouble:
      return FieldType::MFTime;
    case FieldType::MFVec2d:
      return FieldType::MFVec2f;
    case FieldType::MFVec3d:
      return FieldType::MFVec3f;
    case FieldType::MFVec4f:
    case FieldType::MFVec4d:
    case FieldType::MFColorRGBA:
      return FieldType::MFRotation;
    default:
      return t;
  }
}

namespace {

template <class M, int N>
void flatten(const M& m, std::vector<float>& out) {
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col) out.push_back(static_cast<float>(m[col][row]));
}

template <class M, int N>
M unflatten(const std::vector<float>& f, std::size_t at) {
  M m(1);
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col) {
      const std::size_t i = at + static_cast<std::size_t>(row * N + col);
      if (i < f.size()) m[col][row] = static_cast<typename M::value_type>(f[i]);
    }
  return m;
}

template <class To, class From>
std::vector<To> convertAll(const std::vector<From>& v) {
  std::vector<To> out;
  out.reserve(v.size());
  for (const From& x : v) out.push_back(To(x));
  return out;
}

template <FieldType T, class M, int N>
void flattenList(const FieldValue& v, std::vector<float>& out) {
  for (const M& m : v.get<T>()) flatten<M, N>(m, out);
}

template <class M, int N>
std::vector<M> unflattenList(const std::vector<float>& f) {
  std::vector<M> out;
  for (std::size_t at = 0; at + N * N <= f.size(); at += N * N)
    out.push_back(unflatten<M, N>(f, at));
  return out;
}

}  // namespace

FieldValue toNearestVrml97(const FieldValue& v) {
  using T = FieldType;
  std::vector<float> flat;
  switch (v.type()) {
    case T::SFDouble:
      return FieldValue::make<T::SFTime>(v.get<T::SFDouble>());
    case T::SFVec2d:
      return FieldValue::make<T::SFVec2f>(glm::vec2(v.get<T::SFVec2d>()));
    case T::SFVec3d:
      return FieldValue::make<T::SFVec3f>(glm::vec3(v.get<T::SFVec3d>()));
    case T::SFVec4f:
      return FieldValue::make<T::SFRotation>(v.get<T::SFVec4f>());
    case T::SFVec4d:
      return FieldValue::make<T::SFRotation>(glm::vec4(v.get<T::SFVec4d>()));
    case T::SFColorRGBA:
      return FieldValue::make<T::SFRotation>(v.get<T::SFColorRGBA>());
    case T::SFMatrix3f:
      flatten<glm::mat3, 3>(v.get<T::SFMatrix3f>(), flat);
      break;
    case T::SFMatrix3d:
      flatten<glm::dmat3, 3>(v.get<T::SFMatrix3d>(), flat);
      break;
    case T::SFMatrix4f:
      flatten<glm::mat4, 4>(v.get<T::SFMatrix4f>(), flat);
      break;
    case T::SFMatrix4d:
      flatten<glm::dmat4, 4>(v.get<T::SFMatrix4d>(), flat);
      break;
    case T::MFMatrix3f:
      flattenList<T::MFMatrix3f, glm::mat3, 3>(v, flat);
      break;
    case T::MFMatrix3d:
      flattenList<T::MFMatrix3d, glm::dmat3, 3>(v, flat);
      break;
    case T::MFMatrix4f:
      flattenList<T::MFMatrix4f, glm::mat4, 4>(v, flat);
      break;
    case T::MFMatrix4d:
      flattenList<T::MFMatrix4d, glm::dmat4, 4>(v, flat);
      break;
    case T::MFBool: {
      std::vector<std::int32_t> out;
      for (bool b : v.get<T::MFBool>()) out.push_back(b ? 1 : 0);
      return FieldValue::make<T::MFInt32>(std::move(out));
    }
    case T::MFImage:
      return FieldValue(T::MFInt32);
    case T::MFDouble:
      return FieldValue::make<T::MFTime>(v.get<T::MFDouble>());
    case T::MFVec2d:
      return FieldValue::make<T::MFVec2f>(convertAll<glm::vec2>(v.get<T::MFVec2d>()));
    case T::MFVec3d:
      return FieldValue::make<T::MFVec3f>(convertAll<glm::vec3>(v.get<T::MFVec3d>()));
    case T::MFVec4f:
      return FieldValue::make<T::MFRotation>(v.get<T::MFVec4f>());
    case T::MFVec4d:
      return FieldValue::make<T::MFRotation>(convertAll<glm::vec4>(v.get<T::MFVec4d>()));
    case T::MFColorRGBA:
      return FieldValue::make<T::MFRotation>(v.get<T::MFColorRGBA>());
    default:
      return v;
  }
  return FieldValue::make<T::MFFloat>(std::move(flat));
}

FieldValue fromNearestVrml97(FieldType t, const FieldValue& v) {
  using T = FieldType;
  if (v.type() != nearestVrml97Type(t)) return FieldValue(t);
  switch (t) {
    case T::SFDouble:
      return FieldValue::make<T::SFDouble>(v.get<T::SFTime>());
    case T::SFVec2d:
      return FieldValue::make<T::SFVec2d>(glm::dvec2(v.get<T::SFVec2f>()));
    case T::SFVec3d:
      return FieldValue::make<T::SFVec3d>(glm::dvec3(v.get<T::SFVec3f>()));
    case T::SFVec4f:
      return FieldValue::make<T::SFVec4f>(v.get<T::SFRotation>());
    case T::SFVec4d:
      return FieldValue::make<T::SFVec4d>(glm::dvec4(v.get<T::SFRotation>()));
    case T::SFColorRGBA:
      return FieldValue::make<T::SFColorRGBA>(v.get<T::SFRotation>());
    case T::SFMatrix3f:
      return FieldValue::make<T::SFMatrix3f>(unflatten<glm::mat3, 3>(v.get<T::MFFloat>(), 0));
    case T::SFMatrix3d:
      return FieldValue::make<T::SFMatrix3d>(unflatten<glm::dmat3, 3>(v.get<T::MFFloat>(), 0));
    case T::SFMatrix4f:
      return FieldValue::make<T::SFMatrix4f>(unflatten<glm::mat4, 4>(v.get<T::MFFloat>(), 0));
    case T::SFMatrix4d:
      return FieldValue::make<T::SFMatrix4d>(unflatten<glm::dmat4, 4>(v.get<T::MFFloat>(), 0));
    case T::MFMatrix3f:
      return FieldValue::make<T::MFMatrix3f>(unflattenList<glm::mat3, 3>(v.get<T::MFFloat>()));
    case T::MFMatrix3d:
      return FieldValue::make<T::MFMatrix3d>(unflattenList<glm::dmat3, 3>(v.get<T::MFFloat>()));
    case T::MFMatrix4f:
      return FieldValue::make<T::MFMatrix4f>(unflattenList<glm::mat4, 4>(v.get<T::MFFloat>()));
    case T::MFMatrix4d:
      return FieldValue::make<T::MFMatrix4d>(unflattenList<glm::dmat4, 4>(v.get<T::MFFloat>()));
    case T::MFBool: {
      std::vector<bool> out;
      for (std::int32_t i : v.get<T::MFInt32>()) out.push_back(i != 0);
      return FieldValue::make<T::MFBool>(std::move(out));
    }
    case T::MFImage:
      return FieldValue(T::MFImage);
    case T::MFDouble:
      return FieldValue::make<T::MFDouble>(v.get<T::MFTime>());
    case T::MFVec2d:
      return FieldValue::make<T::MFVec2d>(convertAll<glm::dvec2>(v.get<T::MFVec2f>()));
    case T::MFVec3d:
      return FieldValue::make<T::MFVec3d>(convertAll<glm::dvec3>(v.get<T::MFVec3f>()));
    case T::MFVec4f:
      return FieldValue::make<T::MFVec4f>(v.get<T::MFRotation>());
    case T::MFVec4d:
      return FieldValue::make<T::MFVec4d>(convertAll<glm::dvec4>(v.get<T::MFRotation>()));
    case T::MFColorRGBA:
      return FieldValue::make<T::MFColorRGBA>(v.get<T::MFRotation>());
    default:
      return v;
  }
}

FieldValue::FieldValue(FieldType t)
    : storage_(makeDefault(static_cast<std::size_t>(t),
                           std::make_index_sequence<std::variant_size_v<Storage>>{})) {
  static_assert(std::variant_size_v<Storage> == kFieldTypeCount);
}

}  // namespace gs::vrml
