// EXTERNPROTO "urn:ghostspace:NAME" resolves to GhostSpace's own extension node
// (docs/vrml-extensions.md); other URNs stay unresolved.
#include <catch2/catch.hpp>

#include "encodings/parser.hpp"

TEST_CASE("urn:ghostspace names resolve to the built-in extension nodes", "[vrml][extension]") {
  const auto scene = gs::vrml::parseVrml(R"(#VRML V2.0 utf8
EXTERNPROTO OutlineGroup [ exposedField MFNode children field SFInt32 groupId field MFVec3f outline ]
  [ "urn:ghostspace:OutlineGroup" "ghostspace-extensions.wrl#OutlineGroup" ]
EXTERNPROTO QuantizedNormalVectors [ exposedField MFString url ]
  [ "urn:ghostspace:QuantizedNormalVectors" ]
EXTERNPROTO Other [ field SFInt32 x ] [ "urn:example:Other" ]
OutlineGroup { groupId 1 outline [0 0 0, 1 0 0, 1 1 0] }
QuantizedNormalVectors { url "a.qnv" fraction 0.5 }
Other { x 1 }
)",
                                         "urn.wrl");
  REQUIRE(scene.rootNodes.size() == 3);
  CHECK(scene.rootNodes[0]->typeName() == "OutlineGroup");
  CHECK(scene.rootNodes[0]->type().extension);
  CHECK(!scene.rootNodes[0]->unresolved);
  CHECK(scene.rootNodes[0]->get<gs::vrml::FieldType::SFInt32>("groupId", -1) == 1);
  // The built-in node has every field, also those the declaration left out.
  CHECK(scene.rootNodes[1]->get<gs::vrml::FieldType::SFFloat>("fraction", 1.0f) == 0.5f);
  CHECK(scene.rootNodes[2]->unresolved);
}
