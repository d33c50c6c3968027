// Output events that drawing computes reach the world's Scripts through the session
// (render::SceneRenderer::takeDrawnOutputs -> runtime::ExecutionModel::sendDrawnOutputs):
// a LOD's level_changed (X3D 4.0 clause 10.4.2).
#include <catch2/catch.hpp>

#include <string>

#include "process.hpp"
#include "test_support.hpp"

TEST_CASE("a Script hears the level a LOD shows, as the view moves", "[app][script][x3d]") {
  // Seen from 15 m the LOD shows level 1; an animated Viewpoint comes to 5 m at T = 2,
  // where it shows level 0.
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
DEF V Viewpoint { position 0 0 15 }
DEF T TimeSensor { cycleInterval 2 }
DEF P PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 15, 0 0 5 ] }
ROUTE T.fraction_changed TO P.set_fraction
ROUTE P.value_changed TO V.position
DEF L LOD { range [ 10 ] level [ Shape { geometry Box {} } Shape { geometry Sphere {} } ] }
DEF S Script {
  inputOnly SFInt32 level
  url "ecmascript:
function level (value, time) { print ('level ' + value); }"
}
ROUTE L.level_changed TO S.level
)";
  const gs::test::TempDir dir("lod_levels");
  const std::string file = dir.write("lod.x3dv", world);
  const gs::test::ProcessResult r =
      gs::test::runGhostspace({"--snapshot", (dir.path / "frame.png").string(), "--size", "32x32",
                               "--load-time", "0", "--time", "2.5", file});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::size_t far = r.err.find("level 1"), near = r.err.find("level 0");
  CHECK(far != std::string::npos);
  CHECK(near != std::string::npos);
  CHECK(far < near);
}
