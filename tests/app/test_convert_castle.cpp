// `ghostspace convert` against the reference converter: castle-model-viewer's `tovrmlx3d`
// (Debian's view3dscene) reads what convert writes, in both X3D encodings, with no more
// warnings than it gives for the original world (docs/x3d.md, "Conversion").
#include "process.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// The lines tovrmlx3d writes to stderr reading `path` (each a warning or an error), or -1
// when it did not exit 0.
int castleWarnings(const std::string& tovrmlx3d, const fs::path& path, const fs::path& scratch) {
  const fs::path err = scratch / "tovrmlx3d.err";
  const std::string command =
      "'" + tovrmlx3d + "' '" + path.string() + "' > /dev/null 2> '" + err.string() + "'";
  if (std::system(command.c_str()) != 0) return -1;
  const std::string text = gs::test::readBytes(err);
  int lines = 0;
  for (char c : text) lines += c == '\n' ? 1 : 0;
  return lines;
}

}  // namespace

TEST_CASE("convert: castle's tovrmlx3d reads what convert writes", "[app][convert]") {
  const std::string tovrmlx3d = gs::test::fixtureProgram("GS_TOVRMLX3D", "/usr/bin/tovrmlx3d");
  if (!fs::exists(tovrmlx3d)) {
    gs::test::missingFixture("tovrmlx3d: " + tovrmlx3d +
                             " is absent (apt-get install view3dscene)");
    return;
  }
  // Worlds that name no other file (their copies in a temporary folder read the same).
  std::vector<fs::path> worlds = {gs::test::sourceDir() / "assets/worlds/x3d_features.x3dv",
                                  gs::test::sourceDir() / "assets/worlds/x3d_features.x3d",
                                  gs::test::sourceDir() / "assets/worlds/text.wrl",
                                  gs::test::sourceDir() / "assets/worlds/welcome.wrl"};
  for (const char* castle :
       {"x3d/castle/prototypes/proto_sfnode_default.x3dv",
        "x3d/castle/prototypes/proto_events_test.x3dv", "x3d/castle/x3d/tricky_def_use.x3dv"})
    if (fs::exists(gs::test::corpusDir() / castle))
      worlds.push_back(gs::test::corpusDir() / castle);
  gs::test::TempDir dir("convert-castle");
  for (const fs::path& world : worlds) {
    const int original = castleWarnings(tovrmlx3d, world, dir.path);
    REQUIRE(original >= 0);
    for (const char* extension : {".x3dv", ".x3d"}) {
      const fs::path out = dir.path / (world.stem().string() + extension);
      const auto r = gs::test::runGhostspace({"convert", world.string(), "-o", out.string()});
      INFO(world.string() << " -> " << out.string() << "\n" << r.err);
      REQUIRE(r.exitCode == 0);
      CHECK(castleWarnings(tovrmlx3d, out, dir.path) == original);
    }
  }
}
