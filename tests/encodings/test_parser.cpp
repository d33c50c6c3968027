// The VRML97 reader: header, the 20 field types, DEF/USE, Script declarations,
// diagnostics with their exact place, gzip, and the node table built through the
// PROTO-interface parser.
#include "test_parser_support.hpp"

#include "encodings/node_types.hpp"
#include "encodings/parser.hpp"
#include "vrml/node_table.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using namespace gs::vrml;
using gs::test::firstError;
using gs::test::parse;

TEST_CASE("header: V2.0 utf8 and X3D accepted, V1.0 and others refused", "[parser]") {
  CHECK(parseVrml("#VRML V2.0 utf8\n", "a.wrl").diagnostics.items.empty());
  CHECK(parseVrml("#VRML V2.0 utf8 written by hand\nGroup {}", "a.wrl").rootNodes.size() == 1);
  CHECK(parseVrml("#VRML V2.0 utf8", "a.wrl").diagnostics.items.empty());

  Scene v1 = parseVrml("#VRML V1.0 ascii\nSeparator {}\n", "old.wrl");
  REQUIRE(v1.diagnostics.items.size() == 1);
  CHECK(v1.diagnostics.items[0].message == "VRML 1.0 is not supported");
  CHECK(v1.diagnostics.items[0].severity == Severity::error);
  CHECK(v1.rootNodes.empty());

  // X3D's Classic VRML encoding is read (test_x3d_classic.cpp).
  CHECK(parseVrml("#X3D V3.0 utf8\nGroup {}\n", "x.wrl").diagnostics.items.empty());

  Scene other = parseVrml("#VRML V3.0 utf8\nGroup {}\n", "x.wrl");
  REQUIRE(other.diagnostics.items.size() == 1);
  CHECK(other.diagnostics.items[0].message ==
        "expected '#VRML V2.0 utf8' or '#X3D V4.0 utf8' header, got '#VRML V3.0 utf8'");
  CHECK(other.diagnostics.items[0].location.line == 1);
  CHECK(other.diagnostics.items[0].location.column == 1);

  Scene empty = parseVrml("", "e.wrl");
  REQUIRE(empty.diagnostics.items.size() == 1);
  CHECK(empty.diagnostics.items[0].message ==
        "expected '#VRML V2.0 utf8' or '#X3D V4.0 utf8' header, got ''");
}

TEST_CASE("SF field types of built-in nodes", "[parser]") {
  Scene s = parse(R"(
    Transform { translation 1 -2.5 3e2 rotation 0 1 0 1.5708 scale 2,2,2 }
    Cone { side FALSE bottomRadius 3 }
    Switch { whichChoice 0x10 }
    WorldInfo { title "a \"quoted\" back\\slash" }
    TimeSensor { cycleInterval 2.5 startTime 1e9 }
    TextureTransform { scale .5 +4. }
    Material { diffuseColor 1 0.5 0 }
    Shape { geometry Box { size 1 2 3 } }
  )");
  REQUIRE(s.diagnostics.errorCount() == 0);
  REQUIRE(s.rootNodes.size() == 8);
  const Node& t = *s.rootNodes[0];
  CHECK(t.get<FieldType::SFVec3f>("translation", glm::vec3(0)) == glm::vec3(1, -2.5f, 300));
  CHECK(t.get<FieldType::SFRotation>("rotation", Rotation(0)) == Rotation(0, 1, 0, 1.5708f));
  CHECK(t.get<FieldType::SFVec3f>("scale", glm::vec3(0)) == glm::vec3(2));
  CHECK(s.rootNodes[1]->get<FieldType::SFBool>("side", true) == false);
  CHECK(s.rootNodes[1]->get<FieldType::SFFloat>("bottomRadius", 0.0f) == 3.0f);
  CHECK(s.rootNodes[2]->get<FieldType::SFInt32>("whichChoice", 0) == 16);
  CHECK(s.rootNodes[3]->get<FieldType::SFString>("title", std::string()) ==
        "a \"quoted\" back\\slash");
  CHECK(s.rootNodes[4]->get<FieldType::SFTime>("cycleInterval", 0.0) == 2.5);
  CHECK(s.rootNodes[4]->get<FieldType::SFTime>("startTime", 0.0) == 1e9);
  CHECK(s.rootNodes[5]->get<FieldType::SFVec2f>("scale", glm::vec2(0)) == glm::vec2(0.5f, 4));
  CHECK(s.rootNodes[6]->get<FieldType::SFColor>("diffuseColor", glm::vec3(0)) ==
        glm::vec3(1, 0.5f, 0));
  NodePtr box = s.rootNodes[7]->sfnode("geometry");
  REQUIRE(box);
  CHECK(box->typeName() == "Box");
  CHECK(box->get<FieldType::SFVec3f>("size", glm::vec3(0)) == glm::vec3(1, 2, 3));
  // Defaults of fields not written come from the node table.
  CHECK(t.get<FieldType::SFVec3f>("center", glm::vec3(9)) == glm::vec3(0));
  CHECK(s.rootNodes[6]->get<FieldType::SFFloat>("ambientIntensity", 0.0f) == Approx(0.2f));
}

TEST_CASE("all 20 field types through Script declarations", "[parser]") {
  Scene s = parse(R"(
    DEF S Script {
      field SFBool b TRUE
      field SFColor c 0 0.5 1
      field SFFloat f -1.25e-1
      field SFImage i 2 1 3 0xFF0000 0x00ff00
      field SFInt32 n -0x7
      field SFNode nd Group {}
      field SFRotation r 1 0 0 3.14
      field SFString s "x"
      field SFTime t 0.5
      field SFVec2f v2 1 2
      field SFVec3f v3 1 2 3
      field MFColor mc [ 1 0 0, 0 1 0 ]
      field MFFloat mf [ 1, 2.5, -3 ]
      field MFInt32 mi [ 1 -2 0x1F, 4 ]
      field MFNode mn [ Group {} Transform {} ]
      field MFRotation mr [ 0 1 0 0, 1 0 0 1 ]
      field MFString ms [ "a" "b\"c" ]
      field MFTime mt [ 1 2 ]
      field MFVec2f m2 [ 0 0 1 1 ]
      field MFVec3f m3 [ 0 0 0, 1 1 1, ]
      eventIn SFBool go
      eventOut MFVec3f out
    }
  )");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 1);
  const Node& n = *s.rootNodes[0];
  CHECK(n.type().script);
  CHECK(n.defName == "S");
  CHECK(n.get<FieldType::SFBool>("b", false));
  CHECK(n.get<FieldType::SFColor>("c", glm::vec3(9)) == glm::vec3(0, 0.5f, 1));
  CHECK(n.get<FieldType::SFFloat>("f", 0.0f) == -0.125f);
  const SFImage& img = n.field("i")->get<FieldType::SFImage>();
  CHECK(img.width == 2);
  CHECK(img.height == 1);
  CHECK(img.components == 3);
  CHECK(img.pixels == std::vector<std::uint32_t>{0xFF0000u, 0x00FF00u});
  CHECK(n.get<FieldType::SFInt32>("n", 0) == -7);
  REQUIRE(n.sfnode("nd"));
  CHECK(n.sfnode("nd")->typeName() == "Group");
  CHECK(n.get<FieldType::SFRotation>("r", Rotation(0)) == Rotation(1, 0, 0, 3.14f));
  CHECK(n.get<FieldType::SFString>("s", std::string()) == "x");
  CHECK(n.get<FieldType::SFTime>("t", 0.0) == 0.5);
  CHECK(n.get<FieldType::SFVec2f>("v2", glm::vec2(0)) == glm::vec2(1, 2));
  CHECK(n.get<FieldType::SFVec3f>("v3", glm::vec3(0)) == glm::vec3(1, 2, 3));
  CHECK(n.field("mc")->get<FieldType::MFColor>() == std::vector<glm::vec3>{{1, 0, 0}, {0, 1, 0}});
  CHECK(n.field("mf")->get<FieldType::MFFloat>() == std::vector<float>{1, 2.5f, -3});
  CHECK(n.field("mi")->get<FieldType::MFInt32>() == std::vector<std::int32_t>{1, -2, 31, 4});
  REQUIRE(n.mfnode("mn").size() == 2);
  CHECK(n.mfnode("mn")[1]->typeName() == "Transform");
  CHECK(n.field("mr")->get<FieldType::MFRotation>() ==
        std::vector<Rotation>{{0, 1, 0, 0}, {1, 0, 0, 1}});
  CHECK(n.field("ms")->get<FieldType::MFString>() == std::vector<std::string>{"a", "b\"c"});
  CHECK(n.field("mt")->get<FieldType::MFTime>() == std::vector<double>{1, 2});
  CHECK(n.field("m2")->get<FieldType::MFVec2f>() == std::vector<glm::vec2>{{0, 0}, {1, 1}});
  CHECK(n.field("m3")->get<FieldType::MFVec3f>() == std::vector<glm::vec3>{{0, 0, 0}, {1, 1, 1}});
  const int go = n.type().findExact("go");
  REQUIRE(go >= 0);
  CHECK(n.type().fields[static_cast<std::size_t>(go)].access == AccessType::eventIn);
  CHECK(n.type().findExact("out") >= 0);
  // The per-instance type is a copy: the built-in Script type is unchanged.
  CHECK(builtInNodeType("Script")->findExact("b") < 0);
}

TEST_CASE("MF values with and without brackets, empty lists", "[parser]") {
  Scene s = parse(R"(
    Coordinate { point 1 2 3 }
    Coordinate { point [] }
    IndexedFaceSet { coordIndex 7 colorIndex [ ] }
    WorldInfo { info "single" }
    Group { children Shape {} }
    ElevationGrid { height 4.5 }
    Color { color [ 0 0 0 ] }
  )");
  REQUIRE(s.diagnostics.errorCount() == 0);
  CHECK(s.rootNodes[0]->field("point")->get<FieldType::MFVec3f>() ==
        std::vector<glm::vec3>{{1, 2, 3}});
  CHECK(s.rootNodes[1]->field("point")->get<FieldType::MFVec3f>().empty());
  CHECK(s.rootNodes[2]->field("coordIndex")->get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{7});
  CHECK(s.rootNodes[3]->field("info")->get<FieldType::MFString>() ==
        std::vector<std::string>{"single"});
  CHECK(s.rootNodes[4]->mfnode("children").size() == 1);
  CHECK(s.rootNodes[5]->field("height")->get<FieldType::MFFloat>() == std::vector<float>{4.5f});
  CHECK(s.rootNodes[6]->field("color")->get<FieldType::MFColor>().size() == 1);
}

TEST_CASE("numbers: exact float rounding on the fast and slow paths", "[parser][lexer]") {
  // Values chosen to cross the inline parser's limits (8 digits, 2^24, exponents).
  const std::vector<std::string> texts = {"0",
                                          "-0.5",
                                          "18.860",
                                          "0.1",
                                          "16777215",
                                          "16777217",
                                          "0.12345678",
                                          "123456789",
                                          "1.5e3",
                                          "-2E-2",
                                          "3.",
                                          ".25",
                                          "0.5500000119209289",
                                          "1e-45",
                                          "3.4028235e38",
                                          "00012.500",
                                          "-7.547"};
  for (const std::string& t : texts) {
    Scene s = parse("Coordinate { point [ " + t + " 0 0 ] } Sphere { radius " + t + " }");
    INFO(t);
    REQUIRE(s.diagnostics.errorCount() == 0);
    const float want = std::strtof(t.c_str(), nullptr);
    CHECK(s.rootNodes[0]->field("point")->get<FieldType::MFVec3f>()[0].x == want);
    CHECK(s.rootNodes[1]->get<FieldType::SFFloat>("radius", 99.0f) == want);
  }
}

TEST_CASE("integers: hex, range, and floats refused", "[parser][lexer]") {
  Scene s = parse("IndexedFaceSet { coordIndex [ 0xFFFFFFFF 2147483647 -2147483648 0X10 ] }");
  REQUIRE(s.diagnostics.errorCount() == 0);
  CHECK(s.rootNodes[0]->field("coordIndex")->get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{-1, 2147483647, -2147483647 - 1, 16});

  Scene f = parse("Switch { whichChoice 1.5 }");
  REQUIRE(f.diagnostics.errorCount() == 1);
  CHECK(f.diagnostics.items[0].message == "expected an integer, got '1.5'");
  CHECK(f.diagnostics.items[0].location.line == 2);
  CHECK(f.diagnostics.items[0].location.column == 22);

  Scene big = parse("Switch { whichChoice 99999999999 }");
  REQUIRE(big.diagnostics.errorCount() == 1);
  CHECK(big.diagnostics.items[0].message.find("out of range") != std::string::npos);
}

TEST_CASE("strings: escapes, newlines inside, UTF-8 kept as bytes", "[parser][lexer]") {
  Scene s = parse("WorldInfo { info [ \"line1\nline2\" \"\\\\\" \"caf\xC3\xA9\" \"\\x\" ] }");
  REQUIRE(s.diagnostics.items.empty());
  CHECK(s.rootNodes[0]->field("info")->get<FieldType::MFString>() ==
        std::vector<std::string>{"line1\nline2", "\\", "caf\xC3\xA9", "x"});
}

TEST_CASE("identifiers: VRML97 id characters, comments and commas", "[parser][lexer]") {
  Scene s = parse(R"(
    # comment { with [ brackets
    DEF my-node+1|x Group { children [ ,,, Shape {}, ] } # trailing
    DEF caf)"
                  "\xC3\xA9"
                  R"( Transform {}
    USE my-node+1|x
  )");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 3);
  CHECK(s.rootNodes[0]->defName == "my-node+1|x");
  CHECK(s.rootNodes[1]->defName == "caf\xC3\xA9");
  CHECK(s.rootNodes[2] == s.rootNodes[0]);
}

TEST_CASE("DEF/USE share one node; USE of an unknown name is an error with place", "[parser]") {
  Scene s = parse(R"(
DEF M Material { diffuseColor 1 0 0 }
Shape { appearance Appearance { material USE M } }
Shape { appearance Appearance { material USE M } }
Shape { appearance Appearance { material USE Nope } }
)");
  REQUIRE(s.diagnostics.items.size() == 2);  // the Material at the root is a warning
  CHECK(s.diagnostics.items[0].severity == Severity::warning);
  const Diagnostic& e = s.diagnostics.items[1];
  CHECK(e.severity == Severity::error);
  CHECK(e.message == "USE of unknown DEF name 'Nope'");
  CHECK(e.location.file == "test.wrl");
  CHECK(e.location.line == 6);
  CHECK(e.location.column == 46);
  REQUIRE(s.rootNodes.size() == 4);
  NodePtr m1 = s.rootNodes[1]->sfnode("appearance")->sfnode("material");
  NodePtr m2 = s.rootNodes[2]->sfnode("appearance")->sfnode("material");
  CHECK(m1 == s.rootNodes[0]);
  CHECK(m1 == m2);
  CHECK(s.rootNodes[3]->sfnode("appearance")->sfnode("material") == nullptr);
  // A later DEF of the same name replaces it for later USEs.
  Scene r = parse("DEF A Group {} DEF A Transform {} Group { children USE A }");
  CHECK(r.rootNodes[2]->mfnode("children")[0]->typeName() == "Transform");
}

TEST_CASE("unknown field: error with file:line:column, value skipped, parse goes on", "[parser]") {
  Scene s = parse(R"(
Shape {
  appearance Appearance {
    material Material { colr 1 0 0 diffuseColor 0 1 0 }
  }
  bogus [ 1 2 3 ] geometry Sphere { radius 2 }
  junk Box { size 1 1 1 }
}
Group { oops 1 2 3 children [ Shape {} ] }
)");
  REQUIRE(s.diagnostics.items.size() == 4);
  CHECK(s.diagnostics.items[0].message == "unknown field 'colr' in Material");
  CHECK(s.diagnostics.items[0].location.line == 5);
  CHECK(s.diagnostics.items[0].location.column == 25);
  CHECK(s.diagnostics.items[0].format() ==
        "test.wrl:5:25: error: unknown field 'colr' in Material");
  CHECK(s.diagnostics.items[1].message == "unknown field 'bogus' in Shape");
  CHECK(s.diagnostics.items[1].location.line == 7);
  CHECK(s.diagnostics.items[1].location.column == 3);
  CHECK(s.diagnostics.items[2].message == "unknown field 'junk' in Shape");
  CHECK(s.diagnostics.items[3].message == "unknown field 'oops' in Group");
  CHECK(s.diagnostics.items[3].location.line == 10);
  REQUIRE(s.rootNodes.size() == 2);
  NodePtr mat = s.rootNodes[0]->sfnode("appearance")->sfnode("material");
  CHECK(mat->get<FieldType::SFColor>("diffuseColor", glm::vec3(0)) == glm::vec3(0, 1, 0));
  CHECK(s.rootNodes[0]->sfnode("geometry")->get<FieldType::SFFloat>("radius", 0.0f) == 2.0f);
  CHECK(s.rootNodes[1]->mfnode("children").size() == 1);
}

TEST_CASE("unknown node type: error, braces skipped, siblings kept", "[parser]") {
  Scene s = parse(R"(
Group { children [
  Foo { a [ 1 2 ] b Bar { } "str}" }
  Shape {}
] }
Baz {}
Transform {}
)");
  REQUIRE(s.diagnostics.items.size() == 2);
  CHECK(s.diagnostics.items[0].message == "unknown node type 'Foo'");
  CHECK(s.diagnostics.items[0].location.line == 4);
  CHECK(s.diagnostics.items[0].location.column == 3);
  CHECK(s.diagnostics.items[1].message == "unknown node type 'Baz'");
  CHECK(s.diagnostics.items[1].location.line == 7);
  REQUIRE(s.rootNodes.size() == 2);
  CHECK(s.rootNodes[0]->mfnode("children").size() == 1);
}

TEST_CASE("value errors are recovered at the next field", "[parser]") {
  Scene s = parse("Transform { translation 1 x 3 scale 2 2 2 }\nGroup {}");
  REQUIRE(s.diagnostics.errorCount() == 1);
  CHECK(s.diagnostics.items[0].message == "expected a number, got 'x'");
  CHECK(s.diagnostics.items[0].location.column == 27);
  REQUIRE(s.rootNodes.size() == 2);
  CHECK(s.rootNodes[0]->get<FieldType::SFVec3f>("scale", glm::vec3(0)) == glm::vec3(2));

  Scene b = parse("Cone { side yes bottom FALSE }");
  REQUIRE(b.diagnostics.errorCount() == 1);
  CHECK(b.diagnostics.items[0].message == "expected TRUE or FALSE, got 'yes'");
  CHECK(b.rootNodes[0]->get<FieldType::SFBool>("bottom", true) == false);

  Scene c = parse("Coordinate { point [ 1 2 3 4 ] }");
  REQUIRE(c.diagnostics.errorCount() == 1);
  CHECK(c.diagnostics.items[0].message == "expected a number, got ']'");
  CHECK(c.diagnostics.items[0].location.column == 30);
}

TEST_CASE("Script: exposedField refused, duplicate names, IS outside PROTO", "[parser]") {
  Scene s = parse("Script { exposedField SFBool v TRUE field SFInt32 n 3 }");
  REQUIRE(s.diagnostics.errorCount() == 1);
  CHECK(s.diagnostics.items[0].message ==
        "exposedField is not allowed in a Script node (clause 6.40)");
  CHECK(s.diagnostics.items[0].location.column == 10);
  CHECK(s.rootNodes[0]->get<FieldType::SFInt32>("n", 0) == 3);
  CHECK(s.rootNodes[0]->field("v") == nullptr);

  Scene d = parse("Script { field SFBool a TRUE field SFInt32 a 1 }");
  REQUIRE(d.diagnostics.errorCount() == 1);
  CHECK(d.diagnostics.items[0].message == "'a' is already declared in this Script node");

  // An identical second declaration (NIST, Sourcebook) is a warning; the first one holds.
  Scene twice = parse(
      "Script { eventIn SFBool value_in eventIn SFBool value_in\n"
      "field SFBool b TRUE field SFBool b FALSE }");
  CHECK(twice.diagnostics.errorCount() == 0);
  REQUIRE(twice.diagnostics.items.size() == 2);
  CHECK(twice.diagnostics.items[0].severity == Severity::warning);
  CHECK(twice.diagnostics.items[0].message ==
        "'value_in' is declared twice in this Script node; the second is ignored");
  CHECK(twice.rootNodes[0]->get<FieldType::SFBool>("b", false));
  CHECK(twice.rootNodes[0]->type().findExact("value_in") >= 0);

  Scene is = parse("Group {\n  children IS foo\n}");
  REQUIRE(is.diagnostics.errorCount() == 1);
  CHECK(is.diagnostics.items[0].location.line == 3);
  CHECK(is.diagnostics.items[0].location.column == 3);
}

TEST_CASE("Script may USE itself; other cycles are refused", "[parser]") {
  Scene s = parse("DEF S Script { field SFNode self USE S field MFNode l [ Group {} USE S ] }");
  REQUIRE(s.diagnostics.items.empty());
  const Node* script = s.rootNodes[0].get();
  CHECK(s.rootNodes[0]->sfnode("self").get() == script);
  CHECK(s.rootNodes[0]->mfnode("l")[1].get() == script);

  Scene c = parse("DEF G Group { children [ USE G ] }");
  REQUIRE(c.diagnostics.errorCount() == 1);
  CHECK(c.diagnostics.items[0].message == "USE 'G' inside its own definition would make a cycle");
}

TEST_CASE("eventIn and eventOut cannot be given values", "[parser]") {
  Scene s = parse("Group { addChildren [ Group {} ] set_children [] children_changed [] }");
  REQUIRE(s.diagnostics.errorCount() == 3);
  CHECK(s.diagnostics.items[0].message == "cannot give a value to eventIn 'addChildren' of Group");
  CHECK(s.diagnostics.items[1].message == "cannot give a value to eventIn 'set_children' of Group");
  CHECK(s.diagnostics.items[2].message ==
        "cannot give a value to eventOut 'children_changed' of Group");
}

TEST_CASE("nodes where the spec does not allow them are read with a warning", "[parser]") {
  Scene s = parse("Material {}\nShape { geometry Material {} appearance Appearance {} }");
  REQUIRE(s.diagnostics.items.size() == 2);
  CHECK(s.diagnostics.errorCount() == 0);
  CHECK(s.diagnostics.items[0].message ==
        "Material node is not allowed at the root of a scene (expected X3DChildNode)");
  CHECK(s.diagnostics.items[1].message ==
        "Material node is not allowed in 'geometry' of Shape (expected X3DGeometryNode)");
  CHECK(s.rootNodes.size() == 2);
}

TEST_CASE("diagnostic columns with tabs, CR LF and CR line ends", "[parser]") {
  for (const std::string nl : {"\n", "\r\n", "\r"}) {
    Scene s =
        parseVrml("#VRML V2.0 utf8" + nl + "Group {" + nl + "\tfoo 1" + nl + "}" + nl, "t.wrl");
    INFO(nl.size());
    REQUIRE(s.diagnostics.items.size() == 1);
    CHECK(s.diagnostics.items[0].location.line == 3);
    CHECK(s.diagnostics.items[0].location.column == 2);
  }
}

TEST_CASE("node locations and onRootNode", "[parser]") {
  std::vector<std::string> seen;
  ParseOptions o;
  o.onRootNode = [&](const NodePtr& n) { seen.push_back(n->typeName()); };
  Scene s =
      parseVrml("#VRML V2.0 utf8\nGroup {}\n  Transform { children Shape {} }\n", "loc.wrl", o);
  CHECK(seen == std::vector<std::string>{"Group", "Transform"});
  CHECK(s.rootNodes[1]->location.file == "loc.wrl");
  CHECK(s.rootNodes[1]->location.line == 3);
  CHECK(s.rootNodes[1]->location.column == 3);
  NodePtr shape = s.rootNodes[1]->mfnode("children")[0];
  CHECK(shape->location.column == 24);
}

TEST_CASE("node locations share their file name in both X3D encodings", "[parser][x3d]") {
  // One name per file, referenced by every node (SourceFile): no copy of the string per
  // node. A long name (past the short-string buffer) would be a heap copy otherwise.
  const std::string url = "worlds/a-file-name-longer-than-sixteen-bytes.x3d";
  const Scene classic = parseVrml(
      "#X3D V4.0 utf8\nGroup {}\nTransform { children Shape { geometry Box {} } }\n", url);
  const Scene xml = parseVrml(
      "<X3D version='4.0'><Scene><Group/><Transform><Shape><Box/></Shape></Transform>"
      "</Scene></X3D>",
      url);
  for (const Scene* s : {&classic, &xml}) {
    INFO(s->x3d.encoding);
    REQUIRE(s->rootNodes.size() == 2);
    const Node& group = *s->rootNodes[0];
    const Node& box = *s->rootNodes[1]->mfnode("children").at(0)->sfnode("geometry");
    CHECK(group.location.file == url);
    CHECK(box.location.file == url);
    CHECK(&group.location.file.str() == &box.location.file.str());
  }
  // A copy shares; a name made anew compares equal by its characters.
  const SourceFile a(url);
  const SourceFile b = a;
  CHECK(&a.str() == &b.str());
  CHECK(SourceFile(url) == a);
  CHECK(SourceFile().empty());
  CHECK(SourceFile().str().empty());
  CHECK(a + ":1" == url + ":1");
}

TEST_CASE("gzip input is read transparently, concatenated members too", "[parser]") {
  const auto gz = gs::test::gzip;
  const std::string a = gz("#VRML V2.0 utf8\nGroup {}\n");
  Scene s = parseVrml(a, "g.wrl.gz");
  CHECK(s.diagnostics.items.empty());
  CHECK(s.rootNodes.size() == 1);
  Scene two = parseVrml(a + gz("Transform {}\n"), "g2.wrl.gz");
  CHECK(two.diagnostics.items.empty());
  CHECK(two.rootNodes.size() == 2);

  CHECK(gunzipIfCompressed("plain", "p", 100) == "plain");
  CHECK_THROWS_AS(gunzipIfCompressed(a, "small", 10), ParseError);
  Scene cut = parseVrml(a.substr(0, a.size() / 2), "cut.wrl.gz");
  REQUIRE(cut.diagnostics.errorCount() == 1);
  CHECK(cut.diagnostics.items[0].message.find("corrupt gzip data") != std::string::npos);
  Scene trailing = parseVrml(a + "junk", "t.wrl.gz");
  CHECK(trailing.diagnostics.errorCount() == 1);
}

TEST_CASE("loadVrmlFile names the file and reports what cannot be read", "[parser]") {
  Scene missing = loadVrmlFile("/nonexistent/dir/x.wrl");
  REQUIRE(missing.diagnostics.items.size() == 1);
  CHECK(missing.diagnostics.items[0].message.find("/nonexistent/dir/x.wrl") != std::string::npos);
  const std::string path = (gs::test::sourceDir() / "tests/data/vrml/extern_lib.wrl").string();
  Scene lib = loadVrmlFile(path);
  CHECK(lib.url == path);
  CHECK(lib.diagnostics.items.empty());
  CHECK(lib.protos.size() >= 2);
}

TEST_CASE("node table: every entry builds through the interface parser", "[parser]") {
  std::size_t vrml97 = 0;
  for (const NodeTableEntry& e : nodeTableEntries()) {
    INFO(e.name);
    auto t = builtInNodeType(e.name);
    REQUIRE(t);
    CHECK(t->name == e.name);
    CHECK(t->builtIn);
    CHECK(t->extension == e.extension);
    CHECK(t->script == (e.name == "Script"));
    for (const FieldSpec& f : t->fields) CHECK(f.defaultValue.type() == f.type);
    if (!e.extension) ++vrml97;
  }
  CHECK(vrml97 == 54);
  CHECK(builtInNodeType("Transform") == builtInNodeType("Transform"));
  CHECK(builtInNodeType("NoSuchNode") == nullptr);
  auto bg = builtInNodeType("Background");
  CHECK(bg->fields[static_cast<std::size_t>(bg->findExact("skyColor"))]
            .defaultValue.get<FieldType::MFColor>() == std::vector<glm::vec3>{{0, 0, 0}});
  auto fs = builtInNodeType("FontStyle");
  CHECK(fs->fields[static_cast<std::size_t>(fs->findExact("family"))]
            .defaultValue.get<FieldType::MFString>() == std::vector<std::string>{"SERIF"});
}

TEST_CASE("a missing header quotes the first bytes with the unprintable ones escaped",
          "[vrml][parser]") {
  const auto scene = gs::vrml::parseVrml(std::string("solid \x1b[31m\xff\x01", 13), "x.stl");
  REQUIRE(!scene.diagnostics.items.empty());
  CHECK(scene.diagnostics.items.front().message ==
        "expected '#VRML V2.0 utf8' or '#X3D V4.0 utf8' header, got 'solid \\x1b[31m\\xff\\x01'");
}
