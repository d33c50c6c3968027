// What castle-engine's X3D worlds (../shared/corpus/x3d/castle) need to load with no
// diagnostic: URLs of an EXTERNPROTO's body resolved against the PROTO's file
// (Node::urlBase), castle's extension fields in X3D worlds only (Viewpoint
// autoCenterOfRotation, Fog volumetric*, HAnimSegment's transform), HAnimSite under
// HAnimJoint (X3D 3.3), and VRML 1.0's SFLong / MFLong in X3D worlds.
#include "test_support.hpp"

#include "base/fetch.hpp"
#include "base/url.hpp"
#include "encodings/parser.hpp"
#include "vrml/transform.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

using namespace gs::vrml;
namespace fs = std::filesystem;

namespace {

std::string castleDescribe(const Scene& s) {
  std::string out;
  for (const Diagnostic& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

Scene castleX3d(const std::string& body) {
  return parseVrml("#X3D V3.2 utf8\n" + body, "castle_test.x3dv");
}

void castleWrite(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}

/// The ImageTexture of root `i`'s Shape (root: a Shape or a Group whose first child is).
const Node& textureOf(const Scene& s, std::size_t i) {
  NodePtr n = s.rootNodes.at(i);
  if (n->typeId() == NodeTypeId::Group) n = n->mfnode("children").at(0);
  REQUIRE(n->typeId() == NodeTypeId::Shape);
  const NodePtr& t = n->sfnode("appearance")->sfnode("texture");
  REQUIRE(t);
  return *t;
}

}  // namespace

TEST_CASE("EXTERNPROTO bodies: url fields resolve against the file that wrote the node",
          "[x3d][proto][url]") {
  const fs::path d = fs::temp_directory_path() / "gs_castle_extern_urls";
  fs::remove_all(d);
  // sub/protos.x3dv declares Tex (a texture in its body, its url a literal or given by
  // IS) and Nested, itself an EXTERNPROTO of sub/deeper/nested.x3dv.
  castleWrite(d / "sub" / "deeper" / "nested.x3dv", R"(#X3D V3.2 utf8
PROTO Inner [ inputOutput MFString u [] ] {
  Shape { appearance Appearance { texture ImageTexture { url IS u } } geometry Box {} }
})");
  castleWrite(d / "sub" / "protos.x3dv", R"(#X3D V3.2 utf8
EXTERNPROTO Inner [ inputOutput MFString u ] "deeper/nested.x3dv#Inner"
PROTO Tex [ inputOutput MFString u [ "body.png" ] ] {
  Shape { appearance Appearance { texture ImageTexture { url IS u } } geometry Box {} }
}
PROTO ByNode [ inputOutput SFNode t NULL ] {
  Shape { appearance Appearance { texture IS t } geometry Box {} }
}
PROTO Nested [] { Group { children Inner { u "n.png" } } }
PROTO JustTexture [] { ImageTexture { url "alone.png" } }
)");
  const fs::path world = d / "world.x3dv";
  castleWrite(world, R"(#X3D V3.2 utf8
EXTERNPROTO Tex [ inputOutput MFString u ] "sub/protos.x3dv#Tex"
EXTERNPROTO ByNode [ inputOutput SFNode t ] "sub/protos.x3dv#ByNode"
EXTERNPROTO Nested [] "sub/protos.x3dv#Nested"
EXTERNPROTO JustTexture [] "sub/protos.x3dv#JustTexture"
Tex {}
Tex { u "given.png" }
ByNode { t ImageTexture { url "world.png" } }
Nested {}
Shape { appearance Appearance { texture JustTexture {} } geometry Box {} }
Shape { appearance Appearance { texture ImageTexture { url "plain.png" } } geometry Box {} }
)");
  const Scene s = loadVrmlFile(world.string());
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 6);
  const std::string w = world.string();
  const std::string sub = (d / "sub" / "protos.x3dv").string();
  const auto resolved = [&](const Node& t) {
    const auto& url = t.field("url")->get<FieldType::MFString>();
    REQUIRE(url.size() == 1);
    return gs::base::resolveUrl(t.urlBaseOr(w), url[0]);
  };
  // Written in sub/protos.x3dv: its default, and a value given by IS from the world.
  CHECK(resolved(textureOf(s, 0)) == (d / "sub" / "body.png").string());
  CHECK(resolved(textureOf(s, 1)) == (d / "sub" / "given.png").string());
  // Written in the world and passed in as an SFNode value: the world's directory.
  CHECK(textureOf(s, 2).urlBase == nullptr);
  CHECK(resolved(textureOf(s, 2)) == (d / "world.png").string());
  // Written in sub/deeper/nested.x3dv (an EXTERNPROTO of sub/protos.x3dv).
  CHECK(resolved(textureOf(s, 3)) == (d / "sub" / "deeper" / "n.png").string());
  // A PROTO whose first body node is the texture: the instance's node is still the body's.
  CHECK(resolved(textureOf(s, 4)) == (d / "sub" / "alone.png").string());
  CHECK(textureOf(s, 4).location.file == w);  // where the instance is, for diagnostics
  CHECK(resolved(textureOf(s, 5)) == (d / "plain.png").string());
  // The shapes of the bodies carry the PROTO file's base too; the world's own nodes none.
  CHECK(s.rootNodes[0]->urlBase != nullptr);
  CHECK(*s.rootNodes[0]->urlBase == sub);
  CHECK(s.rootNodes[5]->urlBase == nullptr);
  fs::remove_all(d);
}

TEST_CASE("EXTERNPROTO bodies fetched over http resolve against their http URL",
          "[x3d][proto][url]") {
  std::map<std::string, std::string> served = {
      {"http://example.com/lib/protos.x3dv", R"(#X3D V3.2 utf8
PROTO Tex [] {
  Shape { appearance Appearance { texture ImageTexture { url "tex.png" } } geometry Box {} }
})"}};
  gs::base::CallbackFetcher fetcher(
      [&](const std::string& url, const std::string&, gs::base::FetchMode) {
        auto it = served.find(url);
        return it == served.end() ? gs::base::fetchFailed(url + ": not served")
                                  : gs::base::fetchReady(it->second);
      });
  ParseOptions options;
  options.fetcher = &fetcher;
  const Scene s = parseVrml(R"(#X3D V3.2 utf8
EXTERNPROTO Tex [] "http://example.com/lib/protos.x3dv#Tex"
Tex {})",
                            "/local/world.x3dv", options);
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 1);
  const Node& t = textureOf(s, 0);
  const std::string worldUrl = "/local/world.x3dv";
  const std::string baseUrl = t.urlBaseOr(worldUrl);
  CHECK(baseUrl == "http://example.com/lib/protos.x3dv");
  CHECK(gs::base::resolveUrl(baseUrl, "tex.png") == "http://example.com/lib/tex.png");
  // The referrer is the http file: the one URL policy refuses a local file from it.
  const auto refused = gs::base::fetchLocally("/etc/hostname", baseUrl);
  REQUIRE(refused.has_value());
  CHECK(refused->state == gs::base::FetchState::refused);
}

TEST_CASE("castle's Viewpoint.autoCenterOfRotation exists in X3D worlds only", "[x3d][castle]") {
  const Scene s = castleX3d(
      "Viewpoint { autoCenterOfRotation TRUE }\n"
      "OrthoViewpoint { autoCenterOfRotation TRUE }");
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 2);
  CHECK(s.rootNodes[0]->get<FieldType::SFBool>("autoCenterOfRotation", false));
  CHECK(s.rootNodes[1]->get<FieldType::SFBool>("autoCenterOfRotation", false));
  const Scene vrml97 =
      parseVrml("#VRML V2.0 utf8\nViewpoint { autoCenterOfRotation TRUE }", "a.wrl");
  REQUIRE(vrml97.diagnostics.errorCount() == 1);
  CHECK(vrml97.diagnostics.items[0].message.find("autoCenterOfRotation") != std::string::npos);
}

TEST_CASE("castle's volumetric Fog fields: X3D defaults and values, unknown in VRML97",
          "[x3d][castle][fog]") {
  const Scene s = castleX3d(
      "Fog { }\n"
      "Fog { volumetric TRUE volumetricDirection 0 1 0 "
      "volumetricVisibilityStart 100 }\n"
      "LocalFog { volumetric TRUE volumetricVisibilityStart -2 }");
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 3);
  const Node& plain = *s.rootNodes[0];
  CHECK_FALSE(plain.get<FieldType::SFBool>("volumetric", true));
  CHECK(plain.get<FieldType::SFVec3f>("volumetricDirection", glm::vec3(9)) == glm::vec3(0, -1, 0));
  CHECK(plain.get<FieldType::SFFloat>("volumetricVisibilityStart", 9.0f) == 0.0f);
  const Node& up = *s.rootNodes[1];
  CHECK(up.get<FieldType::SFBool>("volumetric", false));
  CHECK(up.get<FieldType::SFVec3f>("volumetricDirection", glm::vec3(9)) == glm::vec3(0, 1, 0));
  CHECK(up.get<FieldType::SFFloat>("volumetricVisibilityStart", 0.0f) == 100.0f);
  CHECK(s.rootNodes[2]->get<FieldType::SFFloat>("volumetricVisibilityStart", 0.0f) == -2.0f);
  const Scene vrml97 = parseVrml("#VRML V2.0 utf8\nFog { volumetric TRUE }", "a.wrl");
  CHECK(vrml97.diagnostics.errorCount() == 1);
}

TEST_CASE("H-Anim as castle writes it: sites in joints, segments that transform",
          "[x3d][castle][hanim]") {
  const Scene s = castleX3d(R"(
DEF H HAnimHumanoid { skeleton DEF J HAnimJoint { children [
  DEF SEG HAnimSegment { translation 1 2 3 scale 2 2 2 children Shape { geometry Box {} } }
  DEF SITE HAnimSite { children Shape { geometry Box {} } }
] } joints USE J }
DEF P PositionInterpolator { key [0 1] keyValue [0 0 0, 1 1 1] }
ROUTE P.value_changed TO SEG.set_translation
ROUTE P.value_changed TO J.set_translation)");
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  const NodePtr joint = s.rootNodes.at(0)->mfnode("skeleton").at(0);
  const NodePtr segment = joint->mfnode("children").at(0);
  REQUIRE(segment->typeId() == NodeTypeId::HAnimSegment);
  CHECK(placesChildren(NodeTypeId::HAnimSegment));
  // T x S (no rotation, centre): (1, 1, 1) -> (2 + 1, 2 + 2, 2 + 3).
  const glm::vec4 p = transformMatrix(*segment) * glm::vec4(1, 1, 1, 1);
  CHECK(p.x == Approx(3.0));
  CHECK(p.y == Approx(4.0));
  CHECK(p.z == Approx(5.0));
  CHECK(s.routes.size() == 2);
  // X3D 4.0's own model narrows HAnimJoint's children to joints and segments; a VRML97
  // world has no H-Anim nodes at all.
}

TEST_CASE("SFLong and MFLong: read as SFInt32 / MFInt32, silently in X3D", "[x3d][castle]") {
  const std::string script = R"(Script {
  initializeOnly SFLong a 3
  initializeOnly MFLong b [ 1 2 ]
})";
  const Scene s = castleX3d(script);
  INFO(castleDescribe(s));
  CHECK(s.diagnostics.items.empty());
  const Node& x = *s.rootNodes.at(0);
  REQUIRE(x.field("a") != nullptr);
  CHECK(x.field("a")->type() == FieldType::SFInt32);
  CHECK(x.field("a")->get<FieldType::SFInt32>() == 3);
  CHECK(x.field("b")->type() == FieldType::MFInt32);
  // VRML97 never had them: read the same, with a warning each.
  const Scene v = parseVrml(
      "#VRML V2.0 utf8\nScript {\n  field SFLong a 3\n  field MFLong b [ 1 2 ]\n}", "a.wrl");
  CHECK(v.diagnostics.warningCount() == 2);
  CHECK(v.diagnostics.errorCount() == 0);
  CHECK(v.rootNodes.at(0)->field("a")->get<FieldType::SFInt32>() == 3);
}

TEST_CASE("the castle worlds this browser now reads cleanly give no diagnostic",
          "[x3d][castle][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle")) return;
  const fs::path dir = gs::test::corpusDir() / "x3d/castle";
  for (const char* path : {
           "prototypes/relative_urls_test/base.x3dv",
           "x3d/point_properties.x3dv",
           "x3d/points_colorrgba.x3dv",
           "fog/fog_volumetric/fog_volumetric_reused_geometry_final.x3dv",
           "x3d/hanim_transforms.x3dv",
           "shaders/types_test.x3dv",
           "x3d/triangle_quad_sets.x3dv",
       }) {
    const Scene s = loadVrmlFile((dir / path).string());
    INFO(path << "\n" << castleDescribe(s));
    CHECK(s.diagnostics.items.empty());
    CHECK_FALSE(s.rootNodes.empty());
  }
  // relative_urls_test: every ImageTexture and Inline (in its PROTO bodies, by EXTERNPROTO
  // from five subfolders, one nested deeper) names a file that exists where its node's
  // base puts it (the Inline of gray/ and the textures of each subfolder).
  const fs::path world = dir / "prototypes/relative_urls_test/base.x3dv";
  const Scene s = loadVrmlFile(world.string());
  std::set<const Node*> seen;
  int urls = 0;
  std::function<void(const NodePtr&)> visit = [&](const NodePtr& n) {
    if (!n || !seen.insert(n.get()).second) return;
    if (n->typeId() == NodeTypeId::ImageTexture || n->typeId() == NodeTypeId::Inline) {
      for (const std::string& u : n->field("url")->get<FieldType::MFString>()) {
        const std::string file = gs::base::resolveUrl(n->urlBaseOr(world.string()), u);
        INFO(n->typeName() << " " << u << " -> " << file);
        CHECK(fs::exists(file));
        ++urls;
      }
    }
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const FieldValue& f = n->fieldAt(i);
      if (f.type() == FieldType::SFNode) visit(f.get<FieldType::SFNode>());
      if (f.type() == FieldType::MFNode)
        for (const NodePtr& c : f.get<FieldType::MFNode>()) visit(c);
    }
  };
  for (const NodePtr& n : s.rootNodes) visit(n);
  CHECK(urls >= 12);
}
