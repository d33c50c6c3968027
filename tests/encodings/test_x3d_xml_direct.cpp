// The X3D XML reader's direct path (encodings/src/parser_xml_build.cpp): plain statements built
// straight from their elements, the others translated into Classic VRML, in document order.
// Each world is checked against its Classic VRML twin, whole and fed byte by byte, with
// the diagnostics it gives at XML file:line:column.
#include "scene_compare.hpp"
#include "test_support.hpp"

#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"
#include "encodings/writer.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <set>
#include <string>
#include <vector>

using namespace gs::vrml;

namespace gs::vrml::parsing {
// Internal to gs_encodings (parser_impl.hpp): the direct path on or off.
void setXmlDirectBuild(bool on);
}  // namespace gs::vrml::parsing

namespace {

std::string directDescribe(const Scene& s) {
  std::string out;
  for (const Diagnostic& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

std::multiset<std::string> directDiagnostics(const Scene& s) {
  std::multiset<std::string> out;
  for (const Diagnostic& d : s.diagnostics.items) out.insert(d.format());
  return out;
}

// The diagnostics of `s`, formatted, in their order.
std::vector<std::string> directDiagnosticList(const Scene& s) {
  std::vector<std::string> out;
  for (const Diagnostic& d : s.diagnostics.items) out.push_back(d.format());
  return out;
}

// `a` and `b` are the same scene, locations included, with the same diagnostics: in the
// same order when `inOrder`, else as multisets.
void directSameScene(const Scene& a, const Scene& b, bool inOrder) {
  gs::test::Same same;
  same.locations = true;
  const bool equal = same.scenes(a, b);
  INFO(same.diff);
  CHECK(equal);
  if (inOrder)
    CHECK(directDiagnosticList(a) == directDiagnosticList(b));
  else
    CHECK(directDiagnostics(a) == directDiagnostics(b));
}

// `text` parsed with every statement translated (the direct path off for the call).
Scene directParseTranslated(const std::string& text, const std::string& name) {
  gs::vrml::parsing::setXmlDirectBuild(false);
  Scene s = parseVrml(text, name);
  gs::vrml::parsing::setXmlDirectBuild(true);
  return s;
}

// An X3D document around `scene` (its <Scene> starts on line 4).
std::string directDoc(const std::string& scene, const std::string& version = "4.0",
                      const std::string& head = "") {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<X3D profile=\"Immersive\" version=\"" +
         version + "\">\n<head>" + head + "</head>\n<Scene>\n" + scene + "\n</Scene>\n</X3D>\n";
}

// Parses `text` whole and byte by byte; both must give the same scene and diagnostics.
Scene directParse(const std::string& text) {
  Scene whole = parseVrml(text, "direct.x3d");
  StreamingParser p("direct.x3d");
  for (char c : text) p.feed(std::string_view(&c, 1));
  p.finish();
  const Scene streamed = p.takeScene();
  directSameScene(whole, streamed, false);
  return whole;
}

// The XML world and its Classic twin give the same nodes and values.
void directSameAsClassic(const Scene& xml, const std::string& classic) {
  const Scene c = parseVrml(classic, "twin.x3dv");
  INFO(directDescribe(xml) << "--\n" << directDescribe(c));
  gs::test::Same same;
  CHECK(same.scenes(xml, c));
  INFO(same.diff);
  CHECK(same.diff.empty());
}

const FieldValue& directField(const NodePtr& n, std::string_view name) {
  REQUIRE(n != nullptr);
  const FieldValue* v = n->field(name);
  REQUIRE(v != nullptr);
  return *v;
}

}  // namespace

TEST_CASE("X3D XML direct: DEF and USE across translated statements", "[x3d][xml]") {
  // The second statement needs its translation (a Script with source); the others are
  // built from their elements; each USEs what the one before DEFined.
  const Scene s = directParse(directDoc(R"(<Transform DEF="A" translation="1 2 3"/>
<Group DEF="G"><Transform USE="A"/><Script DEF="S"><![CDATA[ecmascript:
function initialize() {}]]></Script></Group>
<Group><Script USE="S"/><Transform USE="A"/><Group USE="G"/></Group>
<ROUTE fromNode="A" fromField="translation_changed" toNode="A" toField="set_translation"/>)"));
  INFO(directDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 3);
  const NodePtr a = s.rootNodes[0];
  CHECK(a->defName == "A");
  CHECK(a->location.line == 5);
  CHECK(a->location.column == 1);
  const auto& g = directField(s.rootNodes[1], "children").get<FieldType::MFNode>();
  REQUIRE(g.size() == 2);
  CHECK(g[0] == a);
  const auto& last = directField(s.rootNodes[2], "children").get<FieldType::MFNode>();
  REQUIRE(last.size() == 3);
  CHECK(last[0] == g[1]);
  CHECK(last[1] == a);
  CHECK(last[2] == s.rootNodes[1]);
  CHECK(s.routes.size() == 1);
  directSameAsClassic(s, R"(#X3D V4.0 utf8
PROFILE Immersive
DEF A Transform { translation 1 2 3 }
DEF G Group { children [ USE A DEF S Script { url "ecmascript:
function initialize() {}" } ] }
Group { children [ USE S USE A USE G ] }
ROUTE A.translation_changed TO A.set_translation
)");
}

TEST_CASE("X3D XML direct: values, containerField and number forms", "[x3d][xml]") {
  const Scene s = directParse(directDoc(R"(<Shape DEF="S">
  <Appearance><Material diffuseColor="1 0.5 0.25" transparency="0.5"/></Appearance>
  <IndexedFaceSet coordIndex="0 1 2 -1, 0x2 +1 0 -1" solid="false" creaseAngle="0.5">
    <Coordinate point="1e-05 +2 .5, -0 3.25e2 7, 1.234567891 -1 0"/>
    <Color color="1 0 0 0 1 0 0 0 1"/>
  </IndexedFaceSet>
</Shape>
<Collision enabled="false"><Shape containerField="proxy"/><Group/></Collision>
<WorldInfo title='a "title" \ with a backslash' info='"one" "two, three"'/>
<Switch whichChoice="0"><Group/></Switch>)"));
  INFO(directDescribe(s));
  CHECK(s.diagnostics.items.empty());
  directSameAsClassic(s, R"(#X3D V4.0 utf8
PROFILE Immersive
DEF S Shape {
  appearance Appearance { material Material { diffuseColor 1 0.5 0.25 transparency 0.5 } }
  geometry IndexedFaceSet {
    coordIndex [ 0 1 2 -1 0x2 +1 0 -1 ] solid FALSE creaseAngle 0.5
    coord Coordinate { point [ 1e-05 +2 .5 -0 3.25e2 7 1.234567891 -1 0 ] }
    color Color { color [ 1 0 0 0 1 0 0 0 1 ] }
  }
}
Collision { enabled FALSE proxy Shape { } children [ Group { } ] }
WorldInfo { title "a \"title\" \\ with a backslash" info [ "one" "two, three" ] }
Switch { whichChoice 0 children [ Group { } ] }
)");
  const NodePtr ifs = directField(s.rootNodes[0], "geometry").get<FieldType::SFNode>();
  const auto& points = directField(directField(ifs, "coord").get<FieldType::SFNode>(), "point")
                           .get<FieldType::MFVec3f>();
  REQUIRE(points.size() == 3);
  CHECK(points[0] == glm::vec3(1e-05f, 2.0f, 0.5f));
  CHECK(std::signbit(points[1].x));
  CHECK(points[1].y == 325.0f);
  CHECK(points[2].x == 1.234567891f);
  CHECK(directField(ifs, "coordIndex").get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{0, 1, 2, -1, 2, 1, 0, -1});
}

TEST_CASE("X3D XML direct: metadata containerField in X3D 3 and 4", "[x3d][xml]") {
  const char* body = R"(<Transform DEF="T"><MetadataSet name="set">
  <MetadataInteger name="i" value="1 2"/></MetadataSet><Shape/></Transform>)";
  for (const char* version : {"3.3", "4.0"}) {
    const Scene s = directParse(directDoc(body, version));
    INFO(version << "\n" << directDescribe(s));
    CHECK(s.diagnostics.items.empty());
    REQUIRE(s.rootNodes.size() == 1);
    const NodePtr t = s.rootNodes[0];
    CHECK(directField(t, "children").get<FieldType::MFNode>().size() == 1);
    // Transform has no `value`: the set goes to `metadata` in both versions.
    const NodePtr set = directField(t, "metadata").get<FieldType::SFNode>();
    REQUIRE(set != nullptr);
    CHECK(set->typeName() == "MetadataSet");
    // Inside the set: X3D 3 puts metadata nodes in `metadata`, X3D 4 in `value`.
    const NodePtr meta = directField(set, "metadata").get<FieldType::SFNode>();
    const auto& values = directField(set, "value").get<FieldType::MFNode>();
    if (version[0] == '3') {
      CHECK(meta != nullptr);
      CHECK(values.empty());
    } else {
      CHECK(meta == nullptr);
      REQUIRE(values.size() == 1);
      CHECK(directField(values[0], "value").get<FieldType::MFInt32>() ==
            std::vector<std::int32_t>{1, 2});
    }
  }
}

TEST_CASE("X3D XML direct: problems are reported at the XML's place", "[x3d][xml]") {
  SECTION("an unknown attribute") {
    const Scene s = directParse(directDoc(R"(<Group DEF="A"/>
  <Transform translation="1 2 3" bogus="1 2"><Shape DEF="Kept"/></Transform>)"));
    INFO(directDescribe(s));
    REQUIRE(s.diagnostics.items.size() == 1);
    CHECK(s.diagnostics.items[0].format() ==
          "direct.x3d:6:3: error: unknown field 'bogus' in "
          "Transform");
    REQUIRE(s.rootNodes.size() == 2);
    const auto& kids = directField(s.rootNodes[1], "children").get<FieldType::MFNode>();
    REQUIRE(kids.size() == 1);
    CHECK(kids[0]->defName == "Kept");
    CHECK(directField(s.rootNodes[1], "translation").get<FieldType::SFVec3f>() ==
          glm::vec3(1, 2, 3));
  }
  SECTION("a bad number, and numbers read before it in the same statement") {
    const Scene s = directParse(directDoc(R"(<Shape>
  <IndexedFaceSet coordIndex="0 1 2 -1"><Coordinate point="0 0 0 1 x 0 0 1e-05 0"/></IndexedFaceSet>
</Shape>)"));
    INFO(directDescribe(s));
    REQUIRE(s.diagnostics.errorCount() == 1);
    CHECK(s.diagnostics.items[0].format().starts_with(
        "direct.x3d:6:41: error: expected a number, got 'x'"));
    REQUIRE(s.rootNodes.size() == 1);
    const NodePtr ifs = directField(s.rootNodes[0], "geometry").get<FieldType::SFNode>();
    CHECK(directField(ifs, "coordIndex").get<FieldType::MFInt32>() ==
          std::vector<std::int32_t>{0, 1, 2, -1});
  }
  SECTION("a USE inside its own definition") {
    const Scene s = directParse(directDoc(R"(<Group DEF="Loop">
  <Transform><Group USE="Loop"/></Transform>
</Group>)"));
    INFO(directDescribe(s));
    REQUIRE(s.diagnostics.errorCount() == 1);
    CHECK(s.diagnostics.items[0].format() ==
          "direct.x3d:6:14: error: USE 'Loop' inside its own definition would make a cycle");
    REQUIRE(s.rootNodes.size() == 1);
  }
  SECTION("a node where its field takes none of its kind, and an unknown USE") {
    const Scene s = directParse(directDoc(R"(<Group><Material/></Group>
<Transform><Shape USE="Nowhere"/></Transform>)"));
    INFO(directDescribe(s));
    REQUIRE(s.diagnostics.items.size() == 2);
    CHECK(s.diagnostics.items[0].format().starts_with(
        "direct.x3d:5:8: warning: Material node is not allowed in 'children' of Group"));
    CHECK(s.diagnostics.items[1].format() ==
          "direct.x3d:6:12: error: USE of unknown DEF name 'Nowhere'");
  }
  SECTION("a PROTO named like a built-in node takes its own field types") {
    const Scene s = directParse(directDoc(R"(<ProtoDeclare name="Coordinate">
  <ProtoInterface><field name="point" type="MFInt32" accessType="initializeOnly"/></ProtoInterface>
  <ProtoBody><Group/></ProtoBody>
</ProtoDeclare>
<Shape><IndexedFaceSet><Coordinate point="1.5 2"/></IndexedFaceSet></Shape>)"));
    INFO(directDescribe(s));
    REQUIRE(s.diagnostics.errorCount() == 1);
    CHECK(s.diagnostics.items[0].message.starts_with("expected an integer"));
  }
}

TEST_CASE("X3D XML direct: UNIT statements convert plain statements too", "[x3d][xml]") {
  const Scene s = directParse(directDoc(
      R"(<Transform DEF="T" rotation="0 1 0 90"><Shape/></Transform>
<Background skyAngle="45 90" skyColor="0 0 1 1 1 1 0 1 0"/>)",
      "4.0",
      R"(<unit category="angle" name="degree" conversionFactor="0.017453292519943295"/>
<unit category="length" name="centimetre" conversionFactor="0.01"/>)"));
  INFO(directDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 2);
  // A child node at the root: inside a Transform that scales centimetres to metres.
  const NodePtr scale = s.rootNodes[0];
  CHECK(scale->defName.empty());
  CHECK(directField(scale, "scale").get<FieldType::SFVec3f>() == glm::vec3(0.01f));
  const NodePtr t = directField(scale, "children").get<FieldType::MFNode>().at(0);
  CHECK(t->defName == "T");
  CHECK(directField(t, "rotation").get<FieldType::SFRotation>().w ==
        Approx(1.5707963).epsilon(1e-6));
  // (Background is a child node too: scaled the same way.)
  const NodePtr background = directField(s.rootNodes[1], "children").get<FieldType::MFNode>().at(0);
  const auto& sky = directField(background, "skyAngle").get<FieldType::MFFloat>();
  REQUIRE(sky.size() == 2);
  CHECK(sky[1] == Approx(1.5707963).epsilon(1e-6));
  directSameAsClassic(s, R"(#X3D V4.0 utf8
PROFILE Immersive
UNIT angle degree 0.017453292519943295
UNIT length centimetre 0.01
DEF T Transform { rotation 0 1 0 90 children Shape { } }
Background { skyAngle [ 45 90 ] skyColor [ 0 0 1 1 1 1 0 1 0 ] }
)");
}

TEST_CASE("X3D XML direct: castle's and KiCad's worlds as when every statement was translated",
          "[x3d][xml][corpus]") {
  std::vector<std::pair<std::string, std::string>> worlds;  // name, XML text
  if (gs::test::haveCorpus("x3d/castle")) {
    const auto root = gs::test::corpusDir() / "x3d/castle";
    for (const auto& f : gs::test::filesWithSuffix(root, ".x3d"))
      worlds.emplace_back(f.string(), gs::test::readBytes(f));
    CHECK(worlds.size() >= 30);
  }
  if (gs::test::haveCorpus("vrml/kicad")) {
    const auto files = gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml/kicad", ".wrl");
    for (std::size_t i = 0; i < files.size() && i < 6; ++i) {
      WriteOptions o;
      o.encoding = Encoding::xml;
      worlds.emplace_back(files[i].string() + ".x3d",
                          writeScene(loadVrmlFile(files[i].string()), o).text);
    }
  }
  for (const auto& [name, text] : worlds) {
    const Scene translated = directParseTranslated(text, name);
    const Scene direct = parseVrml(text, name);
    INFO(name << "\n" << directDescribe(direct) << "--\n" << directDescribe(translated));
    directSameScene(direct, translated, true);
    // Streamed in pieces, with the direct path: the same scene.
    StreamingParser p(name);
    for (std::size_t i = 0; i < text.size(); i += 61) p.feed(std::string_view(text).substr(i, 61));
    p.finish();
    const Scene streamed = p.takeScene();
    directSameScene(streamed, translated, false);
  }
}

TEST_CASE("X3D XML direct: damaged worlds read as when every statement was translated",
          "[x3d][xml]") {
  // A world with most of what the direct path reads, damaged byte by byte (a fixed
  // sequence): whatever the damage, both paths give the same scene and diagnostics, whole
  // and streamed. (Streamed and whole differ where a bad header stops the stream before an
  // XML syntax error: as before the direct path.)
  const std::string base = directDoc(R"(<Transform DEF="T" translation="1 2 3" rotation="0 1 0 0.5">
  <Shape DEF="S"><Appearance><Material DEF="M" diffuseColor="1 0 0"/></Appearance>
    <IndexedFaceSet coordIndex="0 1 2 -1 2 1 3 -1" solid="false">
      <Coordinate point="0 0 0, 1 0 0, 0 1 0, 1e-05 1 0"/></IndexedFaceSet></Shape>
  <Shape><Appearance><Material USE="M"/></Appearance><Box size="1 2 3"/></Shape>
  <MetadataString name="m" value='"x" "y"'/>
</Transform>
<Group><Transform USE="T"/><WorldInfo title="t" info='"a" "b"'/></Group>
<ROUTE fromNode="T" fromField="translation_changed" toNode="T" toField="set_translation"/>
<Shape USE="S"/>)");
  const char kBytes[] = {'"', '#', '<', '>', '/', ' ', '1', '.', '-', 'e', '[', '{', '\\', '\''};
  std::uint32_t rng = 12345;
  auto next = [&rng] {
    rng = rng * 1664525u + 1013904223u;
    return rng >> 8;
  };
  for (int round = 0; round < 300; ++round) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(next() % 3);
    for (int e = 0; e < edits; ++e) {
      const std::size_t at = next() % text.size();
      const char c = kBytes[next() % sizeof kBytes];
      switch (next() % 3) {
        case 0:
          text[at] = c;
          break;
        case 1:
          text.insert(at, 1, c);
          break;
        default:
          text.erase(at, 1);
          break;
      }
    }
    const Scene translated = directParseTranslated(text, "damaged.x3d");
    const Scene direct = parseVrml(text, "damaged.x3d");
    INFO(text << "\n" << directDescribe(direct) << "--\n" << directDescribe(translated));
    directSameScene(direct, translated, true);
    auto stream = [&text] {
      StreamingParser p("damaged.x3d");
      for (std::size_t i = 0; i < text.size(); i += 7) p.feed(std::string_view(text).substr(i, 7));
      p.finish();
      return p.takeScene();
    };
    const Scene streamed = stream();
    gs::vrml::parsing::setXmlDirectBuild(false);
    const Scene streamedOld = stream();
    gs::vrml::parsing::setXmlDirectBuild(true);
    directSameScene(streamed, streamedOld, false);
  }
}
