// Checks of the declarative node table's text (vrml/src/node_table_data.cpp): the 54 VRML97
// nodes of ISO/IEC 14772-1:1997 clause 6, their declarations' syntax and well-known defaults.
// These look only at the text; parsing it into NodeTypes is tested with builtInNodeType.
#include "encodings/node_types.hpp"
#include "vrml/field.hpp"
#include "vrml/node_table.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <set>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace {

using gs::vrml::FieldType;
using gs::vrml::NodeTableEntry;

constexpr std::array<std::string_view, 54> kClause6Names = {
    "Anchor",
    "Appearance",
    "AudioClip",
    "Background",
    "Billboard",
    "Box",
    "Collision",
    "Color",
    "ColorInterpolator",
    "Cone",
    "Coordinate",
    "CoordinateInterpolator",
    "Cylinder",
    "CylinderSensor",
    "DirectionalLight",
    "ElevationGrid",
    "Extrusion",
    "Fog",
    "FontStyle",
    "Group",
    "ImageTexture",
    "IndexedFaceSet",
    "IndexedLineSet",
    "Inline",
    "LOD",
    "Material",
    "MovieTexture",
    "NavigationInfo",
    "Normal",
    "NormalInterpolator",
    "OrientationInterpolator",
    "PixelTexture",
    "PlaneSensor",
    "PointLight",
    "PointSet",
    "PositionInterpolator",
    "ProximitySensor",
    "ScalarInterpolator",
    "Script",
    "Shape",
    "Sound",
    "Sphere",
    "SphereSensor",
    "SpotLight",
    "Switch",
    "Text",
    "TextureCoordinate",
    "TextureTransform",
    "TimeSensor",
    "TouchSensor",
    "Transform",
    "Viewpoint",
    "VisibilitySensor",
    "WorldInfo",
};

// One declaration line split at whitespace.
struct Declaration {
  std::string line;
  std::vector<std::string> tokens;
};

std::vector<std::string> splitWords(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

std::vector<Declaration> declarations(std::string_view interface) {
  std::vector<Declaration> out;
  std::size_t start = 0;
  while (start <= interface.size()) {
    std::size_t end = interface.find('\n', start);
    if (end == std::string_view::npos) end = interface.size();
    std::string line(interface.substr(start, end - start));
    out.push_back({line, splitWords(line)});
    start = end + 1;
  }
  return out;
}

const NodeTableEntry* findEntry(std::string_view name) {
  for (const NodeTableEntry& e : gs::vrml::nodeTableEntries())
    if (e.name == name) return &e;
  return nullptr;
}

// The declaration line of `member` in node `node`, or "" when either is missing.
std::string declarationOf(std::string_view node, std::string_view member) {
  const NodeTableEntry* e = findEntry(node);
  if (!e) return {};
  for (const Declaration& d : declarations(e->interface))
    if (d.tokens.size() >= 3 && d.tokens[2] == member) return d.line;
  return {};
}

// The default-value text of a field or exposedField (tokens from the fourth on, joined by
// single spaces).
std::string defaultText(const Declaration& d) {
  std::string out;
  for (std::size_t i = 3; i < d.tokens.size(); ++i) {
    if (i > 3) out += ' ';
    out += d.tokens[i];
  }
  return out;
}

bool isIdentifier(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

std::span<const NodeTableEntry> vrml97Entries() {
  return gs::vrml::nodeTableEntries().first(gs::vrml::vrml97NodeTypeCount());
}

}  // namespace

TEST_CASE("node table holds the 54 VRML97 nodes of clause 6 in order", "[node_table]") {
  auto all = gs::vrml::nodeTableEntries();
  REQUIRE(gs::vrml::vrml97NodeTypeCount() == 54);
  REQUIRE(all.size() >= 54);

  std::set<std::string_view> names;
  for (std::size_t i = 0; i < all.size(); ++i) {
    INFO("entry " << i << ": " << all[i].name);
    CHECK(names.insert(all[i].name).second);
    // VRML97 entries first, extensions after.
    CHECK(all[i].extension == (i >= 54));
  }

  auto vrml97 = vrml97Entries();
  for (std::size_t i = 0; i < vrml97.size(); ++i) {
    INFO("entry " << i);
    CHECK(vrml97[i].name == kClause6Names[i]);
  }
  CHECK(std::is_sorted(
      vrml97.begin(), vrml97.end(),
      [](const NodeTableEntry& a, const NodeTableEntry& b) { return a.name < b.name; }));
}

TEST_CASE("every node table declaration is well formed", "[node_table]") {
  for (const NodeTableEntry& e : gs::vrml::nodeTableEntries()) {
    INFO("node " << e.name);
    CHECK_FALSE(e.interface.empty());
    std::set<std::string> members;
    for (const Declaration& d : declarations(e.interface)) {
      INFO("line '" << d.line << "'");
      // No blank lines, no stray leading or trailing whitespace.
      CHECK_FALSE(d.tokens.empty());
      if (d.tokens.empty()) continue;
      CHECK(d.line.front() == d.tokens.front().front());
      CHECK(d.line.back() == d.tokens.back().back());
      REQUIRE(d.tokens.size() >= 3);

      const std::string& access = d.tokens[0];
      const bool isEvent = access == "eventIn" || access == "eventOut";
      const bool isField = access == "field" || access == "exposedField";
      CHECK((isEvent || isField));
      if (isEvent) CHECK(d.tokens.size() == 3);
      if (isField) CHECK(d.tokens.size() >= 4);

      FieldType type{};
      CHECK(gs::vrml::fieldTypeFromName(d.tokens[1], type));

      const std::string& name = d.tokens[2];
      CHECK(isIdentifier(name));
      CHECK(members.insert(name).second);  // no repeated member name

      if (!isField || d.tokens.size() < 4) continue;
      const std::string def = defaultText(d);
      // Node defaults are always empty: NULL for SFNode, [] for MFNode (clause 5.8).
      if (type == FieldType::SFNode) CHECK(def == "NULL");
      if (type == FieldType::MFNode) CHECK(def == "[]");
      if (type == FieldType::SFBool) CHECK((def == "TRUE" || def == "FALSE"));
      if (def.front() == '[') CHECK(def.back() == ']');
      if (def.front() == '"') CHECK(def.back() == '"');
    }
  }
}

TEST_CASE("node table text carries the standard's defaults", "[node_table]") {
  CHECK(declarationOf("Material", "diffuseColor") ==
        "exposedField SFColor diffuseColor 0.8 0.8 0.8");
  CHECK(declarationOf("Material", "ambientIntensity") ==
        "exposedField SFFloat ambientIntensity 0.2");
  CHECK(declarationOf("Material", "shininess") == "exposedField SFFloat shininess 0.2");
  CHECK(declarationOf("Viewpoint", "fieldOfView") == "exposedField SFFloat fieldOfView 0.785398");
  CHECK(declarationOf("Viewpoint", "position") == "exposedField SFVec3f position 0 0 10");
  CHECK(declarationOf("Viewpoint", "description") == "field SFString description \"\"");
  CHECK(declarationOf("Viewpoint", "set_bind") == "eventIn SFBool set_bind");
  CHECK(declarationOf("Viewpoint", "bindTime") == "eventOut SFTime bindTime");
  CHECK(declarationOf("Viewpoint", "isBound") == "eventOut SFBool isBound");
  CHECK(declarationOf("NavigationInfo", "type") ==
        "exposedField MFString type [\"WALK\", \"ANY\"]");
  CHECK(declarationOf("NavigationInfo", "avatarSize") ==
        "exposedField MFFloat avatarSize [0.25, 1.6, 0.75]");
  CHECK(declarationOf("NavigationInfo", "headlight") == "exposedField SFBool headlight TRUE");
  CHECK(declarationOf("Transform", "rotation") == "exposedField SFRotation rotation 0 0 1 0");
  CHECK(declarationOf("Transform", "bboxSize") == "field SFVec3f bboxSize -1 -1 -1");
  CHECK(declarationOf("Transform", "addChildren") == "eventIn MFNode addChildren");
  CHECK(declarationOf("Group", "removeChildren") == "eventIn MFNode removeChildren");
  CHECK(declarationOf("Cylinder", "radius") == "field SFFloat radius 1");
  CHECK(declarationOf("Cone", "bottomRadius") == "field SFFloat bottomRadius 1");
  CHECK(declarationOf("Box", "size") == "field SFVec3f size 2 2 2");
  CHECK(declarationOf("Extrusion", "crossSection") ==
        "field MFVec2f crossSection [1 1, 1 -1, -1 -1, -1 1, 1 1]");
  CHECK(declarationOf("Extrusion", "spine") == "field MFVec3f spine [0 0 0, 0 1 0]");
  CHECK(declarationOf("ElevationGrid", "xSpacing") == "field SFFloat xSpacing 1.0");
  CHECK(declarationOf("Collision", "collide") == "exposedField SFBool collide TRUE");
  CHECK(declarationOf("Collision", "proxy") == "field SFNode proxy NULL");
  CHECK(declarationOf("Collision", "collideTime") == "eventOut SFTime collideTime");
  CHECK(declarationOf("LOD", "level") == "exposedField MFNode level []");
  CHECK(declarationOf("LOD", "range") == "field MFFloat range []");
  CHECK(declarationOf("Switch", "whichChoice") == "exposedField SFInt32 whichChoice -1");
  CHECK(declarationOf("PixelTexture", "image") == "exposedField SFImage image 0 0 0");
  CHECK(declarationOf("SpotLight", "beamWidth") == "exposedField SFFloat beamWidth 1.570796");
  CHECK(declarationOf("TimeSensor", "cycleInterval") == "exposedField SFTime cycleInterval 1");
  CHECK(declarationOf("FontStyle", "family") == "field MFString family \"SERIF\"");
}

TEST_CASE("Script declares only url, directOutput and mustEvaluate", "[node_table]") {
  const NodeTableEntry* script = findEntry("Script");
  REQUIRE(script);
  std::vector<std::string> names;
  for (const Declaration& d : declarations(script->interface))
    if (d.tokens.size() >= 3) names.push_back(d.tokens[2]);
  CHECK(names == std::vector<std::string>{"url", "directOutput", "mustEvaluate"});
  CHECK(declarationOf("Script", "url") == "exposedField MFString url []");
  CHECK(declarationOf("Script", "directOutput") == "field SFBool directOutput FALSE");
  CHECK(declarationOf("Script", "mustEvaluate") == "field SFBool mustEvaluate FALSE");
}

TEST_CASE("node table member counts match clause 6", "[node_table]") {
  // Number of declarations per node in the standard's synopses: a cheap guard against a
  // dropped or duplicated line.
  const std::array<std::pair<std::string_view, std::size_t>, 54> counts = {{
      {"Anchor", 8},
      {"Appearance", 3},
      {"AudioClip", 8},
      {"Background", 12},
      {"Billboard", 6},
      {"Box", 1},
      {"Collision", 8},
      {"Color", 1},
      {"ColorInterpolator", 4},
      {"Cone", 4},
      {"Coordinate", 1},
      {"CoordinateInterpolator", 4},
      {"Cylinder", 5},
      {"CylinderSensor", 9},
      {"DirectionalLight", 5},
      {"ElevationGrid", 14},
      {"Extrusion", 14},
      {"Fog", 5},
      {"FontStyle", 9},
      {"Group", 5},
      {"ImageTexture", 3},
      {"IndexedFaceSet", 18},
      {"IndexedLineSet", 7},
      {"Inline", 3},
      {"LOD", 3},
      {"Material", 6},
      {"MovieTexture", 9},
      {"NavigationInfo", 7},
      {"Normal", 1},
      {"NormalInterpolator", 4},
      {"OrientationInterpolator", 4},
      {"PixelTexture", 3},
      {"PlaneSensor", 8},
      {"PointLight", 7},
      {"PointSet", 2},
      {"PositionInterpolator", 4},
      {"ProximitySensor", 8},
      {"ScalarInterpolator", 4},
      {"Script", 3},
      {"Shape", 2},
      {"Sound", 10},
      {"Sphere", 1},
      {"SphereSensor", 6},
      {"SpotLight", 10},
      {"Switch", 2},
      {"Text", 4},
      {"TextureCoordinate", 1},
      {"TextureTransform", 4},
      {"TimeSensor", 9},
      {"TouchSensor", 7},
      {"Transform", 10},
      {"Viewpoint", 8},
      {"VisibilitySensor", 6},
      {"WorldInfo", 2},
  }};
  for (const auto& [name, count] : counts) {
    INFO("node " << name);
    const NodeTableEntry* e = findEntry(name);
    REQUIRE(e);
    CHECK(declarations(e->interface).size() == count);
  }
}
