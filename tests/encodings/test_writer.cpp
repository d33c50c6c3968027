// The writers of encodings/writer.hpp (`ghostspace convert`): parse -> write -> parse gives the
// same scene graph (tests/scene_compare.hpp) for the project's X3D feature world in
// each encoding, PROTOs with IS and ROUTEs to their interfaces, exact float values,
// XML / JSON escaping, and over the corpus worlds (../shared/corpus/x3d and vrml*); an X3D
// world written as VRML97 names what it leaves out.
#include "scene_compare.hpp"
#include "test_support.hpp"

#include "encodings/parser.hpp"
#include "encodings/writer.hpp"

#include <catch2/catch.hpp>

#include <cstring>
#include <map>
#include <set>

using namespace gs::vrml;
namespace fs = std::filesystem;

namespace {

std::string extensionOf(Encoding e) {
  switch (e) {
    case Encoding::vrml97:
      return ".wrl";
    case Encoding::classic:
      return ".x3dv";
    case Encoding::xml:
      return ".x3d";
    case Encoding::json:
      return ".x3dj";
  }
  return "";
}

std::string diagnosticsOf(const Scene& s) {
  std::string out;
  for (const Diagnostic& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

struct Trip {
  Scene back;
  WriteResult written;
  std::string diff;  // empty when the scenes are the same
};

// Writes `scene` in `e` and reads it back as if it lay beside `url` (relative URLs resolve
// the same way).
Trip roundTrip(const Scene& scene, Encoding e, const std::string& url) {
  Trip t;
  t.written = writeScene(scene, WriteOptions{e});
  const fs::path p(url);
  t.back = parseVrml(t.written.text,
                     (p.parent_path() / (p.stem().string() + "-rt" + extensionOf(e))).string());
  gs::test::Same same;
  if (!same.scenes(scene, t.back)) t.diff = same.diff;
  if (t.diff.empty() && t.back.diagnostics.errorCount() > scene.diagnostics.errorCount())
    t.diff = "new errors: " + diagnosticsOf(t.back);
  return t;
}

}  // namespace

TEST_CASE("writer: encodings by file name", "[writer]") {
  CHECK(encodingForPath("a/b.wrl") == Encoding::vrml97);
  CHECK(encodingForPath("B.X3DV") == Encoding::classic);
  CHECK(encodingForPath("c.x3d") == Encoding::xml);
  CHECK(encodingForPath("d.x3dj") == Encoding::json);
  CHECK_FALSE(encodingForPath("e.x3dz").has_value());
  CHECK_FALSE(encodingForPath("dir.wrl/file").has_value());
}

TEST_CASE("writer: the X3D feature world round-trips in every X3D encoding", "[writer]") {
  for (const char* name : {"x3d_features.x3dv", "x3d_features.x3d", "x3d_features.x3dj"}) {
    const std::string path = (gs::test::sourceDir() / "assets/worlds" / name).string();
    const Scene s = loadVrmlFile(path);
    REQUIRE(s.diagnostics.errorCount() == 0);
    REQUIRE_FALSE(s.rootNodes.empty());
    for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
      INFO(name << " as " << encodingName(e));
      const Trip t = roundTrip(s, e, path);
      INFO(t.written.text);
      CHECK(t.diff == "");
      CHECK(t.back.x3d.encoding == (e == Encoding::classic ? "Classic VRML"
                                    : e == Encoding::xml   ? "XML"
                                                           : "JSON"));
    }
  }
}

TEST_CASE("writer: VRML97 worlds of assets/ round-trip as .wrl", "[writer]") {
  for (const char* name :
       {"features.wrl", "animation.wrl", "ghostspace-extensions.wrl", "text.wrl", "welcome.wrl"}) {
    const std::string path = (gs::test::sourceDir() / "assets/worlds" / name).string();
    const Scene s = loadVrmlFile(path);
    INFO(name);
    REQUIRE(s.diagnostics.errorCount() == 0);
    const Trip t = roundTrip(s, Encoding::vrml97, path);
    CHECK(t.diff == "");
    CHECK(t.written.text.starts_with("#VRML V2.0 utf8\n"));
  }
}

TEST_CASE("writer: PROTOs stay declarations, instances and ROUTEs name interfaces", "[writer]") {
  const Scene s = parseVrml(R"(#VRML V2.0 utf8
PROTO Mover [ exposedField SFVec3f where 0 0 0  eventIn SFFloat set_f  field SFNode what NULL ]
{
  DEF T Transform {
    translation IS where
    children [ DEF Inner Shape { geometry IS what } ]
  }
  DEF S Script { eventIn SFFloat f IS set_f  eventOut SFVec3f p  url "javascript:function f(v){}" }
  ROUTE S.p TO T.set_translation
}
PROTO Pair [ exposedField SFVec3f at 1 2 3 ] { Group { children [ Mover { where IS at } ] } }
DEF M Mover { where 0.1 0.2 1.0000001 what Box { size 1e-7 3.4e38 0.5 } }
DEF P Pair { }
DEF TS TimeSensor { loop TRUE }
DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 1 1 1 ] }
ROUTE TS.fraction_changed TO PI.set_fraction
ROUTE PI.value_changed TO M.where
ROUTE TS.fraction_changed TO M.set_f
)",
                            "protos.wrl");
  REQUIRE(s.diagnostics.errorCount() == 0);
  {
    const Trip t = roundTrip(s, Encoding::vrml97, "protos.wrl");
    INFO(t.written.text);
    CHECK(t.diff == "");
    CHECK(t.written.text.find("PROTO Mover [") != std::string::npos);
    CHECK(t.written.text.find("DEF M Mover {") != std::string::npos);
    CHECK(t.written.text.find("ROUTE PI.value_changed TO M.where") != std::string::npos);
    CHECK(t.written.text.find("ROUTE TS.fraction_changed TO M.set_f") != std::string::npos);
    CHECK(t.written.text.find("where IS at") != std::string::npos);
    CHECK(t.written.text.find("where 0.1 0.2 1.0000001") != std::string::npos);
    CHECK(t.written.diagnostics.items.empty());
  }
}

TEST_CASE("writer: PROTOs, Scripts and strings in every X3D encoding", "[writer]") {
  const Scene s = parseVrml(R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT Scripting:1
META "title" "a <title> & \"quotes\""
PROTO Mover [ inputOutput SFVec3f where 0 0 0  inputOnly SFFloat set_f  initializeOnly SFNode what NULL ]
{
  DEF T Transform {
    translation IS where
    children [ Shape { geometry IS what } ]
  }
  DEF S Script {
    inputOnly SFFloat f IS set_f
    outputOnly SFVec3f p
    initializeOnly MFString texts [ "a\"b", "c\\d", "e&f<g>'h'" ]
    url "ecmascript:function f(v) { if (v < 1 && v > 0) p = new SFVec3f(v, 0, 0); }"
  }
  ROUTE S.p TO T.set_translation
}
DEF M Mover { where 0.1 0.2 0.30000001 what Box { size 1e-7 3.4e38 0.5 } }
DEF TS TimeSensor { loop TRUE description "line 1
line	2" }
DEF W WorldInfo { title "x\"y\\z" info [ "]]>", "" ] }
DEF SW Switch { whichChoice 0 children [ Group { } ] }
ROUTE TS.fraction_changed TO M.set_f
EXPORT TS AS Clock
)",
                            "protos.x3dv");
  REQUIRE(s.diagnostics.errorCount() == 0);
  for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
    INFO(encodingName(e));
    const Trip t = roundTrip(s, e, "protos.x3dv");
    INFO(t.written.text);
    CHECK(t.diff == "");
    CHECK(t.back.x3d.exports.size() == 1);
    CHECK(t.written.diagnostics.items.empty());
    if (e == Encoding::xml) {
      // The Script's source as CDATA; "]]>" in an attribute; escaped attribute text.
      CHECK(t.written.text.find("<![CDATA[ecmascript:function f(v) { if (v < 1 && v > 0)") !=
            std::string::npos);
      CHECK(t.written.text.find("info=\"&quot;]]&gt;&quot; &quot;&quot;\"") != std::string::npos);
      CHECK(t.written.text.find("description=\"line 1&#10;line&#9;2\"") != std::string::npos);
      CHECK(t.written.text.find("<Switch DEF=\"SW\" whichChoice=\"0\">") != std::string::npos);
    }
    if (e == Encoding::json) CHECK(t.written.text.find("\"#sourceCode\": [") != std::string::npos);
  }
}

TEST_CASE("writer: an X3D world as VRML97 names what it leaves out", "[writer]") {
  const Scene s = parseVrml(R"(#X3D V4.0 utf8
PROFILE Immersive
META "author" "someone"
DEF T Transform { children [
  Shape { geometry Box { } appearance Appearance { material Material { } } }
  DEF D Disk2D { }
] visible FALSE }
Transform { translation 1 2 3 }
)",
                            "x.x3dv");
  REQUIRE(s.diagnostics.errorCount() == 0);
  const WriteResult w = writeScene(s, WriteOptions{Encoding::vrml97});
  std::string all;
  for (const Diagnostic& d : w.diagnostics.items) all += d.format() + "\n";
  INFO(all);
  INFO(w.text);
  CHECK(all.find("Disk2D") != std::string::npos);
  CHECK(all.find("x.x3dv:6:9: warning: X3D node Disk2D") != std::string::npos);
  CHECK(all.find("Transform.visible") != std::string::npos);
  CHECK(all.find("META") != std::string::npos);
  CHECK(w.text.find("Disk2D") == std::string::npos);
  const Scene back = parseVrml(w.text, "x.wrl");
  CHECK(back.diagnostics.items.empty());
  CHECK(back.x3d.version.empty());
  CHECK(back.rootNodes.size() == 2);
}

TEST_CASE("writer: floats and doubles read back to the same bits", "[writer]") {
  const Scene s = parseVrml(R"(#X3D V4.0 utf8
Transform { translation 0.1 -0 1.17549435e-38 scale 3.4028235e38 1e-45 16777217 }
TimeSensor { cycleInterval 1.0000000000000002 startTime 1.7e9 }
PixelTexture { image 2 1 4 0xFFFFFFFF 0x00000001 }
)",
                            "f.x3dv");
  REQUIRE(s.diagnostics.errorCount() == 0);
  for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
    INFO(encodingName(e));
    const Trip t = roundTrip(s, e, "f.x3dv");
    INFO(t.written.text);
    CHECK(t.diff == "");
  }
}

namespace {

// Parse -> write -> parse over every world with `suffix` under the corpus folder `sub`.
struct CorpusFigures {
  int worlds = 0;
  std::map<Encoding, int> same;
  std::map<Encoding, std::set<std::string>> differ;  // corpus-relative paths
  int vrml97Clean = 0;  // written as .wrl with no diagnostic and read back with none
};

CorpusFigures sweep(const std::string& sub, const std::vector<std::string>& suffixes,
                    const std::vector<Encoding>& encodings, bool toVrml97 = false,
                    const std::set<std::string>& known = {}) {
  CorpusFigures f;
  for (const std::string& suffix : suffixes) {
    for (const fs::path& p : gs::test::filesWithSuffix(gs::test::corpusDir() / sub, suffix)) {
      const Scene s = loadVrmlFile(p.string());
      if (s.rootNodes.empty() || s.diagnostics.errorCount() > 0) continue;
      ++f.worlds;
      const std::string name = p.lexically_relative(gs::test::corpusDir()).string();
      for (Encoding e : encodings) {
        const Trip t = roundTrip(s, e, p.string());
        f.same[e] += t.diff.empty() ? 1 : 0;
        if (!t.diff.empty()) {
          f.differ[e].insert(name);
          WARN(std::string(encodingName(e)) + ": " + name + ": " + t.diff);
        }
      }
      if (toVrml97 && !known.contains(name)) {
        const WriteResult w = writeScene(s, WriteOptions{Encoding::vrml97});
        const Scene back = parseVrml(w.text, p.string() + "-rt.wrl");
        // What VRML97 cannot hold is a diagnostic; what is written reads back cleanly.
        CHECK(back.diagnostics.errorCount() == 0);
        if (back.diagnostics.errorCount() > 0) WARN(name + ": " + diagnosticsOf(back));
        const bool onlyHeader = std::all_of(
            w.diagnostics.items.begin(), w.diagnostics.items.end(), [](const Diagnostic& d) {
              return d.message.find("PROFILE and COMPONENT") != std::string::npos;
            });
        f.vrml97Clean += onlyHeader && back.diagnostics.items.empty() ? 1 : 0;
      }
    }
  }
  return f;
}

}  // namespace

TEST_CASE("writer: the castle X3D corpus round-trips in every X3D encoding",
          "[heavy][writer][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle")) return;
  // Known differences (docs/x3d.md, "Conversion"): UNIT statements are not written (the
  // values are in base units already), and PROTOs declared inside an MFNode value are
  // written before the root node that held them, out of the scope of a DEF beside them.
  const std::set<std::string> expected = {"x3d/castle/x3d/routes_protos_within_mfnode.x3dv",
                                          "x3d/castle/x3d/units.x3d", "x3d/castle/x3d/units.x3dv"};
  const CorpusFigures f = sweep("x3d/castle", {".x3dv", ".x3d", ".x3dvz", ".x3dz"},
                                {Encoding::classic, Encoding::xml, Encoding::json}, true, expected);
  for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json})
    WARN(std::string(encodingName(e)) + ": " + std::to_string(f.same.at(e)) + " of " +
         std::to_string(f.worlds) + " worlds give the same scene graph");
  WARN("as VRML97: " + std::to_string(f.vrml97Clean) + " of " + std::to_string(f.worlds) +
       " worlds need no diagnostic but the one for PROFILE / COMPONENT");
  CHECK(f.worlds > 100);
  for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
    INFO(encodingName(e));
    CHECK(f.differ.at(e) == expected);
    CHECK(f.same.at(e) == f.worlds - static_cast<int>(expected.size()));
  }
}

TEST_CASE("writer: the VRML97 corpus round-trips as .wrl", "[heavy][writer][corpus]") {
  if (!gs::test::haveCorpus("vrml")) return;
  CorpusFigures f = sweep("vrml", {".wrl", ".wrl.gz", ".wrz"}, {Encoding::vrml97});
  WARN("VRML97: " + std::to_string(f.same.at(Encoding::vrml97)) + " of " +
       std::to_string(f.worlds) + " worlds give the same scene graph");
  CHECK(f.worlds > 100);
  // Every one (a PROTO declared in a node's body, as openvrml's proto-in-proto-default-
  // value.wrl has one in a PROTO's interface default, stays in a node's body).
  CHECK(f.differ[Encoding::vrml97].empty());
  CHECK(f.same.at(Encoding::vrml97) == f.worlds);
}

TEST_CASE("writer: worlds in both X3D encodings convert into each other", "[writer][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/multi_texturing")) return;
  int pairs = 0;
  for (const fs::path& p :
       gs::test::filesWithSuffix(gs::test::corpusDir() / "x3d/castle/multi_texturing", ".x3d")) {
    fs::path twin = p;
    twin.replace_extension(".x3dv");
    if (!fs::exists(twin)) continue;
    const Scene xml = loadVrmlFile(p.string());
    const Scene classic = loadVrmlFile(twin.string());
    // The XML world written as Classic reads as its Classic twin does, and the other way.
    const Scene a = parseVrml(writeScene(xml, WriteOptions{Encoding::classic}).text,
                              twin.string() + "-rt.x3dv");
    const Scene b =
        parseVrml(writeScene(classic, WriteOptions{Encoding::xml}).text, p.string() + "-rt.x3d");
    // (The twins' headers may differ: castle gave them different META.)
    gs::test::Same s1, s2;
    INFO(p.string());
    s1.scenes(classic, a);
    s2.scenes(xml, b);
    INFO(s1.diff);
    CHECK((s1.diff.empty() || s1.diff == "X3D header differs"));
    INFO(s2.diff);
    CHECK((s2.diff.empty() || s2.diff == "X3D header differs"));
    ++pairs;
  }
  CHECK(pairs >= 6);
}

TEST_CASE("writer: VRML97 worlds written as X3D keep every VRML97 field",
          "[heavy][writer][corpus]") {
  if (!gs::test::haveCorpus("vrml")) return;
  int worlds = 0;
  std::map<Encoding, int> same;
  std::map<Encoding, std::set<std::string>> differ;
  for (const std::string suffix : {".wrl", ".wrl.gz", ".wrz"}) {
    for (const fs::path& p : gs::test::filesWithSuffix(gs::test::corpusDir() / "vrml", suffix)) {
      const Scene s = loadVrmlFile(p.string());
      if (s.rootNodes.empty() || s.diagnostics.errorCount() > 0) continue;
      ++worlds;
      const std::string name = p.lexically_relative(gs::test::corpusDir()).string();
      for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
        const WriteResult w = writeScene(s, WriteOptions{e});
        const Scene back = parseVrml(w.text, p.string() + "-rt" + extensionOf(e));
        gs::test::Same cmp;
        cmp.fieldsByName = true;
        if (cmp.scenes(s, back) && back.diagnostics.errorCount() == 0) {
          ++same[e];
        } else {
          differ[e].insert(name);
          WARN(std::string(encodingName(e)) + ": " + name + ": " + cmp.diff + " " +
               diagnosticsOf(back));
        }
      }
    }
  }
  for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json})
    WARN("VRML97 as " + std::string(encodingName(e)) + ": " + std::to_string(same[e]) + " of " +
         std::to_string(worlds) + " worlds keep every VRML97 field and ROUTE");
  CHECK(worlds > 100);
  // The one known difference: a PROTO declared inside a node's body (in an interface
  // default) stays there in the Classic encoding, but the XML and JSON encodings have no
  // PROTO before a node's children: it is written at the top, one PROTO more in the file.
  const std::set<std::string> expected = {"vrml/openvrml/good/proto-in-proto-default-value.wrl"};
  CHECK(differ[Encoding::classic].empty());
  CHECK(same[Encoding::classic] == worlds);
  for (Encoding e : {Encoding::xml, Encoding::json}) {
    INFO(encodingName(e));
    CHECK(differ[e] == expected);
    CHECK(same[e] == worlds - 1);
  }
}

TEST_CASE("writer: a USE that a reordered DEF would capture is a diagnostic", "[writer]") {
  // The file gives X to the proxy, then to the Group, and USEs the Group; the writer writes
  // Collision's fields in the node type's order (children before proxy), so at the USE the
  // name X is the proxy's.
  const Scene s = parseVrml(R"(#VRML V2.0 utf8
Collision { proxy DEF X Shape { } children [ DEF X Group { } ] }
Transform { children [ USE X ] }
)",
                            "defs.wrl");
  REQUIRE(s.diagnostics.items.empty());
  const WriteResult w = writeScene(s, WriteOptions{Encoding::vrml97});
  REQUIRE(w.diagnostics.items.size() == 1);
  CHECK(w.diagnostics.items[0].format() ==
        "defs.wrl:2:52: warning: a USE of this node (DEF X): that DEF name was given to another "
        "node in between: the file read back will USE that one");
  // Files without such a clash write without a word (castle's own DEF/USE torture test
  // included, in the corpus test).
  const Scene plain =
      parseVrml("#VRML V2.0 utf8\nDEF X Group { }\nDEF X Group { }\nTransform { children USE X }\n",
                "plain.wrl");
  CHECK(writeScene(plain, WriteOptions{Encoding::vrml97}).diagnostics.items.empty());
}

TEST_CASE("writer: glTF worlds convert to X3D that reads back cleanly", "[heavy][writer][corpus]") {
  if (!gs::test::haveCorpus("gltf")) return;
  int worlds = 0, renamed = 0;
  for (const std::string suffix : {".gltf", ".glb"}) {
    for (const fs::path& p : gs::test::filesWithSuffix(gs::test::corpusDir() / "gltf", suffix)) {
      const Scene s = loadVrmlFile(p.string());
      if (s.rootNodes.empty() || s.diagnostics.errorCount() > 0) continue;
      ++worlds;
      for (Encoding e : {Encoding::classic, Encoding::xml, Encoding::json}) {
        const WriteResult w = writeScene(s, WriteOptions{e});
        const Scene back = parseVrml(w.text, p.string() + "-rt" + extensionOf(e));
        INFO(p.string() << " as " << encodingName(e) << "\n" << diagnosticsOf(back));
        // glTF names such as "Cube.001" are no Classic identifiers: renamed, with a warning.
        CHECK(back.diagnostics.errorCount() == 0);
        CHECK(back.rootNodes.size() == s.rootNodes.size());
        CHECK(back.routes.size() == s.routes.size());
        // The same graph and values, DEF names aside.
        gs::test::Same same;
        same.fieldsByName = true;
        same.defNames = false;
        const bool equal = same.scenes(s, back);
        INFO(same.diff);
        CHECK(equal);
        for (const Diagnostic& d : w.diagnostics.items)
          renamed += d.message.find("no identifier") != std::string::npos ? 1 : 0;
      }
    }
  }
  WARN(std::to_string(worlds) + " glTF worlds, " + std::to_string(renamed) + " names renamed");
  CHECK(worlds >= 10);
  CHECK(renamed > 0);
}
