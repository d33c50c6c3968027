#include "vrml/field.hpp"

#include <array>

namespace gs::vrml {

namespace {
constexpr std::array<std::string_view, kFieldTypeCount> kFieldTypeNames = {
    "SFBool",   "SFColor",    "SFFloat",  "SFImage", "SFInt32", "SFNode",  "SFRotation",
    "SFString", "SFTime",     "SFVec2f",  "SFVec3f", "MFColor", "MFFloat", "MFInt32",
    "MFNode",   "MFRotation", "MFString", "MFTime",  "MFVec2f", "MFVec3f"};

template <std::size_t... I>
FieldValue::Storage makeDefault(std::size_t index, std::index_sequence<I...>) {
  FieldValue::Storage s;
  ((index == I ? (void)s.template emplace<I>() : (void)0), ...);
  return s;
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

FieldValue::FieldValue(FieldType t)
    : storage_(makeDefault(static_cast<std::size_t>(t),
                           std::make_index_sequence<std::variant_size_v<Storage>>{})) {
  static_assert(std::variant_size_v<Storage> == kFieldTypeCount);
}

}  // namespace gs::vrml
