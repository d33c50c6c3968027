// X3D TextureCoordinate3D and TextureCoordinate4D (X3D 4.0 clauses 33.4.6, 33.4.7) read
// by 3D and 2D textures, and castle-engine's primitive fields (Box.texCoord with a
// TextureCoordinateGenerator, Box.ccw FALSE), drawn off-screen at 64x64.
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace fs = std::filesystem;

using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// Draws an X3D world of `body` (after an unlit set-up: no headlight unless `headlight`,
/// the camera at `viewpoint`, 90 degrees wide).
Rendered drawStrqWorld(const std::string& name, const std::string& body,
                       const std::string& viewpoint = "0 0 1", bool headlight = false) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file,
            "#X3D V3.2 utf8\nPROFILE Interchange\nCOMPONENT Texturing3D:2\n"
            "NavigationInfo { headlight " +
                std::string(headlight ? "TRUE" : "FALSE") + " }\nViewpoint { position " +
                viewpoint + " fieldOfView 1.5708 }\n" + body + "\n");
  return renderFile(file);
}

/// An unlit quad filling the view at z = 0 with texture `texture` and texCoord `texCoord`
/// (one point per corner: (-1,-1), (1,-1), (1,1), (-1,1)).
Rendered drawStrqQuad(const std::string& name, const std::string& texture,
                      const std::string& texCoord) {
  return drawStrqWorld(
      name, "Shape { appearance Appearance { texture " + texture +
                " }\n  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 "
                "0, -1 1 0] } coordIndex [0 1 2 3 -1] texCoord " +
                texCoord + " } }");
}

/// A 2x1x2 texture sampled nearest: at r = 0 red (s < 0.5) and green, at r = 1 blue and
/// yellow; s and r repeat (the default).
const std::string kFourTexels =
    "PixelTexture3D { image [ 3 2 1 2 0xFF0000 0x00FF00 0x0000FF 0xFFFF00 ] textureProperties "
    "TextureProperties { magnificationFilter \"NEAREST_PIXEL\" minificationFilter "
    "\"NEAREST_PIXEL\" } }";

}  // namespace

TEST_CASE("TextureCoordinate3D on an IndexedFaceSet reads the PixelTexture3D texel it names",
          "[render][offscreen][world][texture3d][texcoord3d]") {
  // Every corner at (0.75, 0.5, 0.75): texel s = 1, r = 1, yellow. Without the
  // coordinates the quad's box gives r = 0 and s from x: red and green halves.
  const Rendered yellow = drawStrqQuad(
      "strq_yellow", kFourTexels,
      "TextureCoordinate3D { point [0.75 0.5 0.75, 0.75 0.5 0.75, 0.75 0.5 0.75, 0.75 0.5 0.75] }");
  CHECK(yellow.diagnostics.items.empty());
  CHECK(gs::test::close(yellow.image.pixel(32, 32), 255, 255, 0, 4));
  CHECK(gs::test::close(yellow.image.pixel(8, 8), 255, 255, 0, 4));
  // (0.25, 0.5, 0.75): s = 0, r = 1, blue.
  const Rendered blue = drawStrqQuad(
      "strq_blue", kFourTexels,
      "TextureCoordinate3D { point [0.25 0.5 0.75, 0.25 0.5 0.75, 0.25 0.5 0.75, 0.25 0.5 0.75] }");
  CHECK(gs::test::close(blue.image.pixel(32, 32), 0, 0, 255, 4));
  // s running 0 to 1 across the quad, r = 0.25: red on the left, green on the right.
  const Rendered across =
      drawStrqQuad("strq_across", kFourTexels,
                   "TextureCoordinate3D { point [0 0 0.25, 1 0 0.25, 1 1 0.25, 0 1 0.25] }");
  CHECK(gs::test::close(across.image.pixel(12, 32), 255, 0, 0, 4));
  CHECK(gs::test::close(across.image.pixel(52, 32), 0, 255, 0, 4));
}

TEST_CASE("TextureCoordinate4D: (s, t, r) divided by q, for 3D and 2D textures",
          "[render][offscreen][world][texture3d][texcoord3d]") {
  // (3, 0, 1, 4) is (0.75, 0, 0.25): s = 1, r = 0, green. Undivided, s = 3 and r = 1
  // would repeat to 0: red.
  const std::string point = "3 0 1 4";
  const std::string fourD =
      "TextureCoordinate4D { point [" + point + ", " + point + ", " + point + ", " + point + "] }";
  const Rendered green3d = drawStrqQuad("strq_4d", kFourTexels, fourD);
  CHECK(green3d.diagnostics.items.empty());
  CHECK(gs::test::close(green3d.image.pixel(32, 32), 0, 255, 0, 4));
  // A 2D texture red | green reads s = 0.75: green (undivided s = 3 repeats to red).
  const Rendered green2d = drawStrqQuad(
      "strq_4d_2d",
      "PixelTexture { image 2 1 3 0xFF0000 0x00FF00 textureProperties TextureProperties { "
      "magnificationFilter \"NEAREST_PIXEL\" minificationFilter \"NEAREST_PIXEL\" } }",
      fourD);
  CHECK(gs::test::close(green2d.image.pixel(32, 32), 0, 255, 0, 4));
}

TEST_CASE("castle's Box.texCoord: a COORD generator replaces the box's own 3D mapping",
          "[render][offscreen][world][texture3d][castle]") {
  // A box 2 x 2 x 1.6 whose front face (z = 0.8) fills the view. COORD gives r = 0.8:
  // blue; the box's own mapping (X3D 4.0 clause 33.2.4: r from the back) gives r = 0
  // there: red.
  const std::string redBlue =
      "PixelTexture3D { image [ 3 1 1 2 0xFF0000 0x0000FF ] textureProperties "
      "TextureProperties { magnificationFilter \"NEAREST_PIXEL\" minificationFilter "
      "\"NEAREST_PIXEL\" boundaryModeR \"CLAMP_TO_EDGE\" } }";
  auto box = [&](const std::string& texCoord) {
    return "Shape { appearance Appearance { texture " + redBlue +
           " } geometry Box { size 2 2 1.6 " + texCoord + " } }";
  };
  const Rendered coord = drawStrqWorld(
      "strq_box_coord", box("texCoord TextureCoordinateGenerator { mode \"COORD\" }"), "0 0 1.8");
  CHECK(coord.diagnostics.items.empty());
  CHECK(gs::test::close(coord.image.pixel(32, 32), 0, 0, 255, 4));
  const Rendered own = drawStrqWorld("strq_box_own", box(""), "0 0 1.8");
  CHECK(gs::test::close(own.image.pixel(32, 32), 255, 0, 0, 4));
}

TEST_CASE("castle's Box.ccw FALSE: seen and lit from inside",
          "[render][offscreen][world][castle]") {
  // The camera at the centre of a 4 m box, the headlight on: the inside-out box shows its
  // far face lit red; the ordinary (solid) box culls every face it sees from inside.
  auto box = [](const std::string& ccw) {
    return "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } } geometry "
           "Box { size 4 4 4 " +
           ccw + " } }";
  };
  const Rendered inside = drawStrqWorld("strq_ccw_false", box("ccw FALSE"), "0 0 0", true);
  CHECK(inside.diagnostics.items.empty());
  const std::uint8_t* p = inside.image.pixel(32, 32);
  CHECK(p[0] > 200);
  CHECK(p[1] < 40);
  const Rendered culled = drawStrqWorld("strq_ccw_true", box(""), "0 0 0", true);
  CHECK(gs::test::close(culled.image.pixel(32, 32), 0, 0, 0, 4));
}
