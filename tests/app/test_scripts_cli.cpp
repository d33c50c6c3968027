// Scripts through the command line (docs/runtime-scripts.md): a Script's events reach the
// world; a hostile Script (an endless loop, a ROUTE back to itself) ends with a diagnostic
// naming the world's file:line while the picture is still written.
#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using gs::test::runGhostspace;

namespace {

fs::path writeWorld(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "scripts-cli";
  fs::create_directories(dir);
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("a Script's initialize() moves a Transform", "[app][script]") {
  const fs::path world = writeWorld("ok.wrl", R"(#VRML V2.0 utf8
DEF X Transform { children Shape { geometry Box {} } }
DEF S Script {
  eventOut SFVec3f where
  url "javascript: function initialize() { where = new SFVec3f(1, 2, 3); }"
}
ROUTE S.where TO X.set_translation
)");
  const fs::path trace = world.parent_path() / "ok.jsonl";
  auto r = runGhostspace({"--snapshot", (world.parent_path() / "ok.png").string(), "--size",
                          "32x32", "--trace-events", trace.string(), world.string()});
  REQUIRE(r.exitCode == 0);
  CHECK(readText(trace) ==
        "{\"time\":0.000,\"node\":\"S\",\"field\":\"where\",\"value\":\"1 2 3\"}\n"
        "{\"time\":0.000,\"node\":\"X\",\"field\":\"translation_changed\",\"value\":\"1 2 3\"}\n");
  // --no-scripts: nothing runs.
  auto off =
      runGhostspace({"--snapshot", (world.parent_path() / "off.png").string(), "--size", "32x32",
                     "--no-scripts", "--trace-events", trace.string(), world.string()});
  REQUIRE(off.exitCode == 0);
  CHECK(readText(trace).empty());
}

TEST_CASE("hostile Scripts end with a diagnostic; the world is still drawn", "[app][script]") {
  const fs::path world = writeWorld("hang.wrl", R"(#VRML V2.0 utf8
Shape { geometry Box {} }
DEF S Script {
  eventOut SFVec3f where
  url "javascript: function initialize() { while (true) {} }"
}
DEF L Script {
  eventIn SFFloat ping
  eventOut SFFloat pong
  url "javascript: function ping(v) { pong = v + 1; }"
}
ROUTE L.pong TO L.ping
DEF T TimeSensor { loop TRUE }
ROUTE T.fraction_changed TO L.ping
)");
  const fs::path png = world.parent_path() / "hang.png";
  fs::remove(png);
  auto r = runGhostspace({"--snapshot", png.string(), "--size", "32x32", "--time", "0:0.5:1",
                          "--script-time-limit", "0.2", world.string()});
  CHECK(r.exitCode == 0);
  CHECK(fs::exists(png));
  CHECK(r.err.find("hang.wrl:3:7:") != std::string::npos);
  CHECK(r.err.find("time limit") != std::string::npos);
}

TEST_CASE("snapshot: loads what the world's events reference (an Inline chosen by a Script)",
          "[app][script][inline]") {
  // Regression: loading followed the static scene only, so an Inline that a Switch shows
  // after a Script's initialize() was never fetched and the snapshot stayed empty.
  writeWorld("part.wrl", R"(#VRML V2.0 utf8
Shape { appearance Appearance { material Material { diffuseColor 1 0 0 emissiveColor 1 0 0 } }
        geometry Box { size 4 4 4 } }
)");
  const fs::path world = writeWorld("chosen.wrl", R"(#VRML V2.0 utf8
Viewpoint { position 0 0 12 }
DEF SW Switch { whichChoice -1 choice [ Inline { url "part.wrl" } ] }
DEF S Script { eventOut SFInt32 choice url "javascript: function initialize() { choice = 0; }" }
ROUTE S.choice TO SW.set_whichChoice
)");
  const fs::path png = world.parent_path() / "chosen.png";
  auto r = runGhostspace(
      {"--snapshot", png.string(), "--size", "64x64", "--no-progress", world.string()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const auto c = gs::test::centrePixel(png.string());
  CHECK(c[0] > 200);
  CHECK(c[1] < 60);
  CHECK(c[2] < 60);
}

TEST_CASE("an Inline whose url a Script sets in initialize() is fetched by --snapshot",
          "[app][script]") {
  // Issue 42, friction 3: the Inline stayed empty with "Inline has no url"; the node's
  // first (empty) resolution was cached and never made again for the new url.
  gs::test::TempDir dir("inline_set_url");
  dir.write("box.wrl",
            "#VRML V2.0 utf8\nShape { appearance Appearance { material Material { diffuseColor "
            "1 0 0 } } geometry Box { size 2 2 2 } }\n");
  const std::string world =
      dir.write("world.wrl",
                "#VRML V2.0 utf8\nViewpoint { position 0 0 8 }\nDEF I Inline { }\nDEF S Script {\n"
                "  eventOut MFString u\n"
                "  url \"javascript: function initialize() { u = new MFString('box.wrl'); }\"\n}\n"
                "ROUTE S.u TO I.set_url\n");
  const fs::path png = dir.path / "out.png";
  const auto r = runGhostspace({"--snapshot", png.string(), "--size", "64x64", world});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const auto c = gs::test::centrePixel(png.string());
  CHECK(c[0] > 100);  // the red box of the Inline
  CHECK(c[1] < 40);
  CHECK(r.err.find("Inline has no url") == std::string::npos);
}
