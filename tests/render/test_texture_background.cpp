// X3D TextureBackground (X3D 4.0 clause 24.4.3): a Background whose six faces are texture
// nodes, drawn off-screen at 64x64 looking down -Z at its front face.
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace fs = std::filesystem;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

Rendered drawTextureBackground(const std::string& name, const std::string& fields) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, "#X3D V3.2 utf8\nPROFILE Immersive\nViewpoint { position 0 0 0 }\n" +
                      std::string("TextureBackground { skyColor [0 0 1] ") + fields + " }\n");
  return renderFile(file);
}

}  // namespace

TEST_CASE("TextureBackground draws its texture nodes on the panorama's faces",
          "[render][offscreen][world][background]") {
  // A red front face fills the 45-degree view straight ahead; the sky colour behind it
  // does not show.
  const Rendered front = drawTextureBackground(
      "texture_background_front", "frontTexture PixelTexture { image 1 1 3 0xFF0000 }");
  CHECK(front.diagnostics.items.empty());
  CHECK(close(front.image.pixel(32, 32), 255, 0, 0, 8));
  CHECK(close(front.image.pixel(2, 2), 255, 0, 0, 8));
  // Only a back face: the sky colour shows ahead.
  const Rendered back = drawTextureBackground("texture_background_back",
                                              "backTexture PixelTexture { image 1 1 3 0xFF0000 }");
  CHECK(close(back.image.pixel(32, 32), 0, 0, 255, 8));
  // A half-transparent texel blends over the sky (as Background's images do).
  const Rendered alpha = drawTextureBackground(
      "texture_background_alpha", "frontTexture PixelTexture { image 1 1 4 0xFF000080 }");
  const std::uint8_t* p = alpha.image.pixel(32, 32);
  CHECK(p[0] > 100);
  CHECK(p[0] < 160);
  CHECK(p[2] > 100);
  CHECK(p[2] < 160);
}
