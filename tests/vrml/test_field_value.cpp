// FieldValue keeps its large alternatives (matrices, SFImage, SFString, SFVec4d, MFBool)
// boxed on the heap: copies must stay deep, a value moved from or never written must read
// as the type's default, and comparing compares values, not boxes.
#include "encodings/node_types.hpp"
#include "vrml/field.hpp"
#include "vrml/field_name.hpp"
#include "vrml/node.hpp"
#include "vrml/node_table.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <utility>

using namespace gs::vrml;

TEST_CASE("FieldValue: boxed alternatives copy deeply and compare by value", "[vrml][field]") {
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(1.0, 2.0, 3.0, 1.0);
  FieldValue a = FieldValue::make<FieldType::SFMatrix4d>(m);
  FieldValue b = a;
  b.get<FieldType::SFMatrix4d>()[3][0] = 9.0;  // writing the copy leaves the original
  CHECK(a.get<FieldType::SFMatrix4d>()[3][0] == 1.0);
  CHECK(b.get<FieldType::SFMatrix4d>()[3][0] == 9.0);
  CHECK_FALSE(a.storage() == b.storage());
  b.get<FieldType::SFMatrix4d>()[3][0] = 1.0;
  CHECK(a.storage() == b.storage());  // equal values in different boxes

  FieldValue s = FieldValue::make<FieldType::SFString>(std::string("a description"));
  const FieldValue t = s;
  CHECK(t.get<FieldType::SFString>() == "a description");
  FieldValue moved = std::move(s);
  CHECK(moved.get<FieldType::SFString>() == "a description");
}

TEST_CASE("FieldValue: a boxed value never written reads as the default", "[vrml][field]") {
  const FieldValue image(FieldType::SFImage);
  CHECK(image.type() == FieldType::SFImage);
  CHECK(image.get<FieldType::SFImage>().width == 0);
  CHECK(image.get<FieldType::SFImage>().pixels.empty());
  FieldValue text(FieldType::SFString);
  CHECK(text.get<FieldType::SFString>().empty());
  text.get<FieldType::SFString>() = "written";  // allocates on the first write
  CHECK(text.get<FieldType::SFString>() == "written");
  CHECK_FALSE(text.storage() == FieldValue(FieldType::SFString).storage());
  FieldValue bools(FieldType::MFBool);
  bools.get<FieldType::MFBool>().push_back(true);
  CHECK(bools.get<FieldType::MFBool>().size() == 1);
}

TEST_CASE("FieldValue: every type's default has that type, and a value is small", "[vrml][field]") {
  for (std::size_t i = 0; i < kFieldTypeCount; ++i) {
    const auto t = static_cast<FieldType>(i);
    CHECK(FieldValue(t).type() == t);
  }
  // The event queue and every node's field array hold FieldValues by value.
  CHECK(sizeof(FieldValue) <= 32);
}

TEST_CASE("FieldName: listed literals are keys, and indexOf answers as findExact",
          "[vrml][field]") {
  constexpr FieldName children("children");
  static_assert(children.key() == FieldKey::children);
  constexpr FieldName unlisted("notAFieldAnyNodeHas");
  static_assert(unlisted.key() == FieldKey::none);
  CHECK(FieldName(std::string("children")).key() == FieldKey::none);  // runtime: by name

  // Every listed name on every built-in type, asked twice (the second answer is the
  // table's), equals the scan of the interface.
  std::size_t found = 0;
  for (const NodeTableEntry& e : nodeTableEntries()) {
    const auto type = builtInNodeType(e.name);
    REQUIRE(type);
    for (std::size_t k = 0; k < kFieldKeyCount; ++k) {
      const std::string_view name = kFieldKeyNames[k];
      const int expected = type->findExact(name);
      const FieldName keyed(name, fieldKeyOf(name));  // as a literal would make it
      CHECK(type->indexOf(keyed) == expected);
      CHECK(type->indexOf(keyed) == expected);
      if (expected >= 0) ++found;
    }
  }
  CHECK(found > 300);
}

TEST_CASE("FieldName: a copied type that grows finds its new field", "[vrml][field]") {
  const auto script = builtInNodeType("Script");
  REQUIRE(script);
  CHECK(script->indexOf("value_changed") == -1);  // fills the table's slot with "none"
  NodeType grown(*script);
  grown.fields.push_back(FieldSpec{"value_changed", FieldType::SFFloat, AccessType::eventOut,
                                   FieldValue(FieldType::SFFloat)});
  CHECK(grown.indexOf("value_changed") == static_cast<int>(grown.fields.size()) - 1);
  Node node(std::make_shared<const NodeType>(grown));
  REQUIRE(node.field("value_changed") != nullptr);
  CHECK(node.field("value_changed")->type() == FieldType::SFFloat);
  CHECK(node.field("url") != nullptr);
  CHECK(node.field("noSuchField") == nullptr);
}
