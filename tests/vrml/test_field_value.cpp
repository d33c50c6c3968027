// FieldValue keeps its large alternatives (matrices, SFImage, SFString, SFVec4d, MFBool)
// boxed on the heap: copies must stay deep, a value moved from or never written must read
// as the type's default, and comparing compares values, not boxes.
#include "vrml/field.hpp"

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
