// A TextureProjector's aspectRatio output (X3D 4.0 clause 42.4.1): its texture's width over
// height, sent once the texture has loaded (SceneRenderer::takeDrawnOutputs).
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

TEST_CASE("A TextureProjector says its texture's aspect ratio", "[render][offscreen][world]") {
  const std::filesystem::path file = worldDir() / "projector_aspect.x3dv";
  writeText(file, R"(#X3D V4.0 utf8
PROFILE Full
Viewpoint { position 0 0 3 }
DEF Wide TextureProjector { location 0 0 2 direction 0 0 -1
  texture PixelTexture { image 4 2 3 0xFF0000 0x00FF00 0x0000FF 0xFFFFFF
                                     0xFF0000 0x00FF00 0x0000FF 0xFFFFFF } }
DEF Off TextureProjectorParallel { on FALSE texture PixelTexture { image 1 3 1 0 0 0 } }
Shape { appearance Appearance { material Material {} } geometry Box {} }
)");
  const Rendered r = renderFile(file, 2);  // the same ratio in the second frame: no event
  // A projector that is off projects nothing and says nothing.
  CHECK(r.outputs == std::vector<std::string>{"Wide.aspectRatio=2.000000"});
}
