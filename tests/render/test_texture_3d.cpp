// X3D Texturing3D textures on polygons (X3D 4.0 clause 33): PixelTexture3D and
// ComposedTexture3D as GL 3D textures, read at COORD-generated or bounding-box
// coordinates through the 3D texture transform, drawn off-screen at 64x64.
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

/// An unlit quad filling the view at z = 0 textured with `texture`, `extra` more
/// Appearance fields and `geometryExtra` more IndexedFaceSet fields.
Rendered drawTextured3D(const std::string& name, const std::string& texture,
                        const std::string& extra = "", const std::string& geometryExtra = "") {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file,
            "#X3D V3.2 utf8\nPROFILE Interchange\nNavigationInfo { headlight FALSE }\n"
            "Viewpoint { position 0 0 1 fieldOfView 1.5708 }\n"
            "Shape { appearance Appearance { texture " +
                texture + " " + extra +
                " }\n  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 "
                "0, 1 1 0, -1 1 0] } coordIndex [0 1 2 3 -1] " +
                geometryExtra + " } }\n");
  return renderFile(file);
}

/// A 1x1x2 texture: red at r = 0, blue at r = 1, sampled nearest.
const std::string kRedBlue =
    "PixelTexture3D { image [ 3 1 1 2 0xFF0000 0x0000FF ] textureProperties TextureProperties { "
    "magnificationFilter \"NEAREST_PIXEL\" minificationFilter \"NEAREST_PIXEL\" "
    "boundaryModeR \"CLAMP_TO_EDGE\" } }";

}  // namespace

TEST_CASE("PixelTexture3D: the flat shape's box gives r = 0; a TextureTransform3D moves r",
          "[render][offscreen][world][texture3d]") {
  const Rendered box = drawTextured3D("t3d_box", kRedBlue);
  CHECK(box.diagnostics.items.empty());
  CHECK(close(box.image.pixel(32, 32), 255, 0, 0, 4));
  const Rendered moved = drawTextured3D(
      "t3d_moved", kRedBlue, "textureTransform TextureTransform3D { translation 0 0 0.9 }");
  CHECK(close(moved.image.pixel(32, 32), 0, 0, 255, 4));
}

TEST_CASE("PixelTexture3D read at COORD coordinates: r is the local z",
          "[render][offscreen][world][texture3d]") {
  // A quad at z = 0 with COORD: r = 0, red; the same shape translated in r by the
  // TextureTransformMatrix3D's last row (row-major in the file): blue.
  const std::string coord = "texCoord TextureCoordinateGenerator { mode \"COORD\" }";
  const Rendered red = drawTextured3D("t3d_coord", kRedBlue, "", coord);
  CHECK(close(red.image.pixel(32, 32), 255, 0, 0, 4));
  const Rendered blue = drawTextured3D(
      "t3d_coord_matrix", kRedBlue,
      "textureTransform TextureTransformMatrix3D { matrix 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0.9 1 }",
      coord);
  CHECK(close(blue.image.pixel(32, 32), 0, 0, 255, 4));
}

TEST_CASE("ComposedTexture3D stacks 2D textures as r slices; a bad PixelTexture3D is a warning",
          "[render][offscreen][world][texture3d]") {
  const Rendered composed = drawTextured3D(
      "t3d_composed",
      "ComposedTexture3D { texture [ PixelTexture { image 1 1 3 0x00FF00 } PixelTexture { image "
      "1 1 3 0xFFFF00 } ] textureProperties TextureProperties { magnificationFilter "
      "\"NEAREST_PIXEL\" minificationFilter \"NEAREST_PIXEL\" } }");
  CHECK(close(composed.image.pixel(32, 32), 0, 255, 0, 4));  // slice 0 at r = 0
  const Rendered bad = drawTextured3D("t3d_bad", "PixelTexture3D { image [ 3 2 2 2 0xFF ] }");
  REQUIRE(bad.diagnostics.items.size() == 1);
  CHECK(bad.diagnostics.items[0].message.find("PixelTexture3D has 1 pixels, expected 8") !=
        std::string::npos);
  CHECK(close(bad.image.pixel(32, 32), 255, 255, 255, 4));  // untextured, unlit white
}
