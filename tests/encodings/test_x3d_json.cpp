// The X3D JSON encoding (ISO/IEC 19776-5), read by translating it into the XML encoding's
// elements and from there into Classic VRML text (encodings/src/x3d_json.cpp): a JSON world
// gives the scene of its Classic twin; field values; head statements; PROTOs; Scripts;
// syntax errors at file:line:column; structural errors naming the JSON path; the nesting
// bound; streaming; and assets/worlds/x3d_features.x3dj.
#include "scene_compare.hpp"
#include "scene_walk.hpp"
#include "test_support.hpp"

#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"

#include <catch2/catch.hpp>

#include <set>
#include <unordered_set>

using namespace gs::vrml;

namespace {

std::string describe(const Scene& s) {
  std::string out;
  for (const Diagnostic& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

const FieldValue& fieldOf(const Node& n, std::string_view name) {
  const FieldValue* v = n.field(name);
  REQUIRE(v != nullptr);
  return *v;
}

NodePtr sfnode(const Node& n, const char* name) {
  return fieldOf(n, name).get<FieldType::SFNode>();
}

using gs::test::Same;

std::multiset<std::string> diagnosticSet(const Scene& s) {
  std::multiset<std::string> out;
  for (const Diagnostic& d : s.diagnostics.items) out.insert(d.format());
  return out;
}

const char* const kTwinJson = R"({ "X3D": {
  "encoding": "UTF-8", "@profile": "Immersive", "@version": "3.3",
  "@xsd:noNamespaceSchemaLocation": "https://www.web3d.org/specifications/x3d-3.3.xsd",
  "JSON schema": "https://www.web3d.org/specifications/x3d-3.3-JSONSchema.json",
  "head": {
    "component": [ { "@name": "Geometry2D", "@level": 1 } ],
    "meta": [ { "@name": "title", "@content": "twin & more <\"quoted\">" } ]
  },
  "Scene": { "-children": [
    { "#comment": "a comment" },
    { "WorldInfo": { "@title": "A \"world\"", "@info": ["one", "two \"2\"", "back\\slash"] } },
    { "Transform": { "@DEF": "T", "@translation": [0, 1, 0], "@rotation": [0, 1, 0, 1.5],
        "-children": [
          { "Shape": { "-geometry": { "Box": { "@size": [1, 2, 3] } },
                       "-appearance": { "Appearance": { "-material": { "Material": {
                         "@diffuseColor": [1, 0, 0], "@transparency": 0.5 } } } } } },
          { "Shape": { "-geometry": { "Sphere": { "@radius": 2, "@solid": false } } } }
        ] } },
    { "TimeSensor": { "@DEF": "Clock", "@cycleInterval": 4, "@loop": true } },
    { "PositionInterpolator": { "@DEF": "PI", "@key": [0, 1], "@keyValue": [0, 0, 0, 1, 1, 1] } },
    { "ROUTE": { "@fromNode": "Clock", "@fromField": "fraction_changed", "@toNode": "PI", "@toField": "set_fraction" } },
    { "ROUTE": { "@fromNode": "PI", "@fromField": "value_changed", "@toNode": "T", "@toField": "set_translation" } },
    { "Transform": { "@USE": "T" } },
    { "Shape": { "-geometry": { "IndexedFaceSet": { "@coordIndex": [0, 1, 2, -1], "@colorPerVertex": false,
        "-coord": { "Coordinate": { "@point": [0, 0, 0, 1, 0, 0, 0, 1, 0] } } } } } },
    { "ProtoDeclare": { "@name": "Ball",
        "ProtoInterface": { "field": [
          { "@name": "color", "@type": "SFColor", "@accessType": "inputOutput", "@value": [0, 0, 1] },
          { "@name": "labels", "@type": "MFString", "@accessType": "initializeOnly", "@value": ["a", "b"] },
          { "@name": "on", "@type": "SFBool", "@accessType": "initializeOnly", "@value": true } ] },
        "ProtoBody": { "-children": [
          { "Shape": { "-appearance": { "Appearance": { "-material": { "Material": {
              "IS": { "connect": [ { "@nodeField": "diffuseColor", "@protoField": "color" } ] } } } } },
            "-geometry": { "Sphere": {} } } } ] } } },
    { "ProtoInstance": { "@name": "Ball", "@DEF": "B1",
        "fieldValue": [ { "@name": "color", "@value": [1, 0.5, 0] },
                        { "@name": "labels", "@value": ["x", "y", "z"] } ] } },
    { "Script": { "@DEF": "S", "@directOutput": true,
        "field": [ { "@name": "n", "@type": "SFInt32", "@accessType": "initializeOnly", "@value": 7 },
                   { "@name": "names", "@type": "MFString", "@accessType": "initializeOnly", "@value": ["p", "q"] } ],
        "#sourceCode": [ "ecmascript:", "function initialize() {", "  n = n + 1;", "}" ] } }
  ] }
} }
)";

const char* const kTwinClassic = R"(#X3D V3.3 utf8
PROFILE Immersive
COMPONENT Geometry2D:1
META "title" "twin & more <\"quoted\">"
WorldInfo { title "A \"world\"" info [ "one" "two \"2\"" "back\\slash" ] }
DEF T Transform {
  translation 0 1 0 rotation 0 1 0 1.5
  children [
    Shape { geometry Box { size 1 2 3 } appearance Appearance { material Material {
      diffuseColor 1 0 0 transparency 0.5 } } }
    Shape { geometry Sphere { radius 2 solid FALSE } }
  ]
}
DEF Clock TimeSensor { cycleInterval 4 loop TRUE }
DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 1 1 1 ] }
ROUTE Clock.fraction_changed TO PI.set_fraction
ROUTE PI.value_changed TO T.set_translation
USE T
Shape { geometry IndexedFaceSet { coordIndex [ 0 1 2 -1 ] colorPerVertex FALSE
  coord Coordinate { point [ 0 0 0 1 0 0 0 1 0 ] } } }
PROTO Ball [ inputOutput SFColor color 0 0 1 initializeOnly MFString labels [ "a" "b" ]
             initializeOnly SFBool on TRUE ] {
  Shape { appearance Appearance { material Material { diffuseColor IS color } } geometry Sphere {} }
}
DEF B1 Ball { color 1 0.5 0 labels [ "x" "y" "z" ] }
DEF S Script { directOutput TRUE initializeOnly SFInt32 n 7 initializeOnly MFString names [ "p" "q" ]
  url [ "ecmascript:
function initialize() {
  n = n + 1;
}" ] }
)";

Scene json(const std::string& scene) {
  return parseVrml(
      R"({"X3D": {"@profile": "Immersive", "@version": "4.0", "Scene": {"-children": [)" + scene +
          "]}}}\n",
      "test.x3dj");
}

}  // namespace

TEST_CASE("X3D JSON: a world gives the scene of its Classic VRML twin", "[x3d][json]") {
  const Scene a = parseVrml(kTwinJson, "twin.x3dj");
  const Scene b = parseVrml(kTwinClassic, "twin.x3dv");
  INFO(describe(a) << "--\n" << describe(b));
  CHECK(a.diagnostics.items.empty());
  CHECK(b.diagnostics.errorCount() == 0);
  CHECK(a.x3d.encoding == "JSON");
  CHECK(a.x3d.version == "3.3");
  CHECK(a.x3d.profile == "Immersive");
  REQUIRE(a.x3d.meta.size() == 1);
  CHECK(a.x3d.meta[0].second == "twin & more <\"quoted\">");
  REQUIRE(a.x3d.components.size() == 1);
  Same same;
  CHECK(same.scenes(a, b));
  INFO(same.diff);
  CHECK(same.diff.empty());
  REQUIRE(a.rootNodes.size() == 8);
  CHECK(a.rootNodes[1]->defName == "T");
  CHECK(a.rootNodes[4] == a.rootNodes[1]);  // USE
  CHECK(a.routes.size() == 2);
  CHECK(a.protos.size() == 1);
  CHECK(a.rootNodes[6]->defName == "B1");
  // Node locations are the JSON's: the object naming Transform DEF T is on line 12.
  CHECK(a.rootNodes[1]->location.file == "twin.x3dj");
  CHECK(a.rootNodes[1]->location.line == 12);
  CHECK(a.rootNodes[1]->location.column == 5);
}

TEST_CASE("X3D JSON: head statements in order", "[x3d][json]") {
  const Scene s = parseVrml(R"({"X3D": {"@profile": "Interchange", "@version": "4.0", "head": {
    "component": [{"@name": "Geometry2D", "@level": 1}, {"@name": "Text", "@level": 1}],
    "unit": [{"@category": "angle", "@name": "degree", "@conversionFactor": 0.017453292519943295}],
    "meta": [{"@name": "creator", "@content": "me"}, {"@name": "title", "@content": "t"}]},
    "Scene": {"-children": [{"Transform": {"@rotation": [0, 1, 0, 90]}}]}}})",
                            "head.x3dj");
  INFO(describe(s));
  CHECK(s.diagnostics.items.empty());
  CHECK(s.x3d.version == "4.0");
  CHECK(s.x3d.profile == "Interchange");
  CHECK(s.x3d.components.size() == 2);
  REQUIRE(s.x3d.units.size() == 1);
  REQUIRE(s.x3d.meta.size() == 2);
  CHECK(s.x3d.meta[0].first == "creator");
  CHECK(s.x3d.meta[1].second == "t");
  REQUIRE(s.rootNodes.size() == 1);
}

TEST_CASE("X3D JSON: MFString, SFBool and MF number values", "[x3d][json]") {
  const Scene s = json(R"(
    {"Shape": {"-geometry": {"Text": {"@string": ["a b", "c\"d", ""], "@solid": true}}}},
    {"Shape": {"-geometry": {"IndexedLineSet": {"@coordIndex": [0, 1, -1],
      "-coord": {"Coordinate": {"@point": [0, 0, 0, 1.5, -2e3, 0.25]}}}}}},
    {"Switch": {"@whichChoice": -1}},
    {"WorldInfo": {"@title": "line\nbreak\ttab"}})");
  INFO(describe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 4);
  const NodePtr text = sfnode(*s.rootNodes[0], "geometry");
  const auto& strings = fieldOf(*text, "string").get<FieldType::MFString>();
  REQUIRE(strings.size() == 3);
  CHECK(strings[0] == "a b");
  CHECK(strings[1] == "c\"d");
  CHECK(strings[2].empty());
  CHECK(fieldOf(*text, "solid").get<FieldType::SFBool>());
  const NodePtr ils = sfnode(*s.rootNodes[1], "geometry");
  CHECK(fieldOf(*ils, "coordIndex").get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{0, 1, -1});
  const auto& pts = fieldOf(*sfnode(*ils, "coord"), "point").get<FieldType::MFVec3f>();
  REQUIRE(pts.size() == 2);
  CHECK(pts[1][1] == -2000.0f);
  CHECK(pts[1][2] == 0.25f);
  CHECK(fieldOf(*s.rootNodes[2], "whichChoice").get<FieldType::SFInt32>() == -1);
  CHECK(fieldOf(*s.rootNodes[3], "title").get<FieldType::SFString>() == "line\nbreak\ttab");
}

TEST_CASE("X3D JSON: errors at file:line:column or naming the JSON path", "[x3d][json]") {
  SECTION("a syntax error") {
    const Scene s =
        parseVrml("{\"X3D\": {\n  \"Scene\": {\n    \"-children\": [ x ]\n}}}\n", "bad.x3dj");
    REQUIRE(s.diagnostics.items.size() == 1);
    const Diagnostic& d = s.diagnostics.items[0];
    INFO(d.format());
    CHECK(d.severity == Severity::error);
    CHECK(d.location.line == 3);
    CHECK(d.location.column == 20);
    CHECK(d.format().starts_with("bad.x3dj:3:20: "));
    CHECK(d.message.find("JSON syntax error") != std::string::npos);
    CHECK(s.rootNodes.empty());
  }
  SECTION("no X3D object") {
    const Scene s = parseVrml(R"({"scene": {"version": "2.0"}})", "other.x3dj");
    REQUIRE(s.diagnostics.items.size() == 1);
    CHECK(s.diagnostics.items[0].message.find("\"X3D\"") != std::string::npos);
  }
  SECTION("a glTF asset is not X3D JSON: it is read as glTF") {
    const Scene s = parseVrml(R"({"asset": {"version": "2.0"}})", "a.gltf");
    CHECK(s.diagnostics.items.empty());
    CHECK(s.x3d.encoding == "glTF");
  }
  SECTION("a node that is not an object: the rest loads") {
    const Scene s = json(R"({"Group": {}}, 5, {"Transform": "x"}, {"Shape": {}})");
    INFO(describe(s));
    CHECK(s.rootNodes.size() == 2);
    REQUIRE(s.diagnostics.errorCount() == 2);
    CHECK(s.diagnostics.items[0].message.find("X3D.Scene.-children[1] ") != std::string::npos);
    CHECK(s.diagnostics.items[1].message.find("X3D.Scene.-children[2].Transform ") !=
          std::string::npos);
  }
  SECTION("an unknown node and field are reported by the parser, on the JSON's lines") {
    const Scene s = parseVrml(
        "{\"X3D\": {\"@version\": \"4.0\", \"Scene\": {\"-children\": [\n"
        "  {\"Group\": {}},\n"
        "  {\"Transform\": {\"@bogus\": 1}},\n"
        "  {\"NoSuchNode\": {}}\n"
        "]}}}\n",
        "unknown.x3dj");
    INFO(describe(s));
    REQUIRE(s.diagnostics.errorCount() >= 2);
    std::set<int> lines;
    for (const Diagnostic& d : s.diagnostics.items) {
      CHECK(d.location.file == "unknown.x3dj");
      lines.insert(d.location.line);
    }
    CHECK(lines.contains(3));
    CHECK(lines.contains(4));
  }
  SECTION("a deep-nesting bomb is refused, not a crash") {
    std::string bomb = "{\"X3D\": {\"Scene\": {\"-children\": [";
    for (int i = 0; i < 200'000; ++i) bomb += "{\"Group\": {\"-children\": [";
    const Scene s = parseVrml(bomb, "bomb.x3dj");
    REQUIRE(s.diagnostics.items.size() == 1);
    CHECK(s.diagnostics.items[0].message.find("nested deeper") != std::string::npos);
    std::string brackets(1'000'000, '[');
    const Scene t = parseVrml("{" + brackets, "bomb2.x3dj");
    CHECK(t.diagnostics.errorCount() == 1);
    // Nested deeply, but within the bound: read.
    std::string deep = "{\"X3D\": {\"Scene\": {\"-children\": [";
    std::string close;
    for (int i = 0; i < 200; ++i) {
      deep += "{\"Group\": {\"-children\": [";
      close += "]}}";
    }
    const Scene u = parseVrml(deep + close + "]}}}", "deep.x3dj");
    INFO(describe(u));
    CHECK(u.diagnostics.items.empty());
    CHECK(gs::test::countNodes(u) == 200);
  }
}

TEST_CASE("X3D JSON: fed through StreamingParser in pieces it gives the scene parsed whole",
          "[x3d][json][streaming]") {
  const std::string text = kTwinJson;
  const Scene whole = parseVrml(text, "twin.x3dj");
  for (std::size_t step : {std::size_t{1}, std::size_t{7}, std::size_t{1000}}) {
    StreamingParser p("twin.x3dj");
    std::size_t roots = 0;
    for (std::size_t i = 0; i < text.size(); i += step)
      p.feed(std::string_view(text).substr(i, step));
    roots += p.finish();
    const Scene s = p.takeScene();
    CHECK(roots == whole.rootNodes.size());
    CHECK(s.x3d.encoding == "JSON");
    Same same;
    same.locations = true;
    CHECK(same.scenes(whole, s));
    INFO(same.diff << describe(s));
    CHECK(diagnosticSet(whole) == diagnosticSet(s));
  }
  SECTION("gzip and a syntax error") {
    const std::string gz = gs::test::gzip(text);
    const Scene a = parseVrml(gz, "twin.x3dj");
    Same same;
    CHECK(same.scenes(whole, a));
    const std::string bad = "{\"X3D\": {\n\"Scene\": }}";
    const Scene b = parseVrml(bad, "bad.x3dj");
    StreamingParser p("bad.x3dj");
    for (char c : bad) p.feed(std::string_view(&c, 1));
    p.finish();
    CHECK(diagnosticSet(b) == diagnosticSet(p.scene()));
    CHECK(b.diagnostics.items.size() == 1);
  }
}

TEST_CASE("X3D JSON: assets/worlds/x3d_features.x3dj is the world of its .x3dv twin",
          "[x3d][json]") {
  const auto dir = gs::test::sourceDir() / "assets/worlds";
  const Scene j = loadVrmlFile((dir / "x3d_features.x3dj").string());
  const Scene c = loadVrmlFile((dir / "x3d_features.x3dv").string());
  INFO(describe(j));
  CHECK(j.diagnostics.items.empty());
  CHECK(c.diagnostics.items.empty());
  CHECK(j.x3d.encoding == "JSON");
  CHECK(j.rootNodes.size() == c.rootNodes.size());
  CHECK(gs::test::countNodes(j) == gs::test::countNodes(c));
  CHECK(gs::test::countNodes(j) > 10);
  Same same;
  same.scenes(j, c);
  // (The META text names its own encoding; everything else is the same.)
  CHECK((same.diff.empty() || same.diff == "X3D header differs"));
  INFO(same.diff);
}
