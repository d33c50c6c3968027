// MultiTexture (X3D 4.0 clause 18.4.3): the stages' modes, sources and functions, per-stage
// texture transforms and coordinate sets, drawn off-screen. One unlit quad fills the view,
// so the first stage's "previous" colour is white; 1x1 PixelTextures give exact colours.
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <set>
#include <string>

namespace fs = std::filesystem;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// A world whose quad fills the 64x64 view, with `appearance` (the Appearance's body) and
/// `geometryExtra` (more IndexedFaceSet fields).
std::string quadWorld(const std::string& appearance, const std::string& geometryExtra = "") {
  return "#X3D V3.2 utf8\nPROFILE Interchange\n"
         "NavigationInfo { headlight FALSE }\n"
         "Viewpoint { position 0 0 1 fieldOfView 1.5708 }\n"
         "Shape { appearance Appearance { " +
         appearance +
         " }\n"
         "  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] "
         "}\n"
         "    coordIndex [0 1 2 3 -1] " +
         geometryExtra + " } }\n";
}

/// A 1x1 PixelTexture of RGB colour 0xRRGGBB.
std::string pixel(const std::string& rgb) {
  return "PixelTexture { image 1 1 3 " + rgb + " }";
}

/// The centre pixel of `appearance` drawn on the quad; `diagnostics` gets the renderer's.
Rendered draw(const std::string& name, const std::string& appearance,
              const std::string& geometryExtra = "") {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, quadWorld(appearance, geometryExtra));
  return renderFile(file);
}

const std::uint8_t* centre(const Rendered& r) {
  return r.image.pixel(32, 32);
}

}  // namespace

TEST_CASE("MultiTexture MODULATE multiplies each stage into the previous result",
          "[render][offscreen][world][multitexture]") {
  const Rendered r = draw("mt_modulate", "texture MultiTexture { texture [ " + pixel("0xFF8040") +
                                             " " + pixel("0x80FFFF") + " ] }");
  CHECK(r.diagnostics.items.empty());
  INFO(int(centre(r)[0]) << " " << int(centre(r)[1]) << " " << int(centre(r)[2]));
  CHECK(close(centre(r), 128, 128, 64, 3));
}

TEST_CASE("MultiTexture ADD, SUBTRACT (texture minus source), SELECTARG2 and OFF",
          "[render][offscreen][world][multitexture]") {
  const std::string two = pixel("0x408000") + " " + pixel("0x404080");
  const auto mode = [&](const std::string& name, const std::string& modes) {
    return draw(name, "texture MultiTexture { mode [ " + modes + " ] texture [ " + two + " ] }");
  };
  // 0x408000 then 0x404080: ADD gives 0x80C080.
  const Rendered add = mode("mt_add", "\"MODULATE\" \"ADD\"");
  CHECK(close(centre(add), 128, 192, 128, 3));
  // RGB SUBTRACT, alpha MODULATE (castle's "RGB / ALPHA" form): 0x404080 - 0x408000.
  const Rendered subtract = mode("mt_subtract", "\"MODULATE\" \"SUBTRACT / MODULATE\"");
  CHECK(close(centre(subtract), 0, 0, 128, 3));
  // SELECTARG2 keeps the source: the first stage's result.
  const Rendered select = mode("mt_select2", "\"MODULATE\" \"SELECTARG2\"");
  CHECK(close(centre(select), 64, 128, 0, 3));
  // OFF skips the stage.
  const Rendered off = mode("mt_off", "\"MODULATE\" \"OFF\"");
  CHECK(close(centre(off), 64, 128, 0, 3));
  // SUBTRACT in both channels: alpha 1 - 1 = 0, the quad vanishes into the black background.
  const Rendered gone = mode("mt_subtract_alpha", "\"MODULATE\" \"SUBTRACT\"");
  CHECK(close(centre(gone), 0, 0, 0, 3));
}

TEST_CASE("MultiTexture sources FACTOR and DIFFUSE, functions COMPLEMENT and ALPHAREPLICATE",
          "[render][offscreen][world][multitexture]") {
  // FACTOR: MultiTexture.color; SELECTARG2 shows it.
  const Rendered factor =
      draw("mt_factor",
           "texture MultiTexture { color 0 0 1 source \"FACTOR\" mode \"SELECTARG2\" "
           "texture " +
               pixel("0xFFFFFF") + " }");
  CHECK(close(centre(factor), 0, 0, 255, 3));
  // DIFFUSE: the shape's own colour (here UnlitMaterial's 0.5 grey), not the previous
  // stage's result (black after stage 0's REPLACE).
  const Rendered diffuse =
      draw("mt_diffuse",
           "material UnlitMaterial { emissiveColor 0.5 0.5 0.5 } "
           "texture MultiTexture { source [ \"\" \"DIFFUSE\" ] mode [ \"REPLACE\" "
           "\"ADD\" ] texture [ " +
               pixel("0x000000") + " " + pixel("0x000000") + " ] }");
  CHECK(close(centre(diffuse), 128, 128, 128, 3));
  // COMPLEMENT acts on the stage's result: 1 - 0xFF8040.
  const Rendered complement =
      draw("mt_complement",
           "texture MultiTexture { function \"COMPLEMENT\" texture " + pixel("0xFF8040") + " }");
  CHECK(close(centre(complement), 0, 127, 191, 3));
  // ALPHAREPLICATE: an opaque result becomes white.
  const Rendered replicate =
      draw("mt_alphareplicate", "texture MultiTexture { function \"ALPHAREPLICATE\" texture " +
                                    pixel("0x204060") + " }");
  CHECK(close(centre(replicate), 255, 255, 255, 3));
}

TEST_CASE("MultiTexture: each stage its own MultiTextureTransform entry and coordinate set",
          "[render][offscreen][world][multitexture]") {
  // A 2x1 texture, black | white, sampled nearest: the left half of the quad black.
  const std::string halves =
      "PixelTexture { image 2 1 1 0x00 0xFF textureProperties TextureProperties { "
      "magnificationFilter \"NEAREST_PIXEL\" } }";
  const std::string coords =
      "texCoord MultiTextureCoordinate { texCoord [ "
      "TextureCoordinate { point [0 0, 1 0, 1 1, 0 1] } "
      "TextureCoordinate { point [1 0, 0 0, 0 1, 1 1] } ] } "
      "texCoordIndex [0 1 2 3 -1]";
  // Stage 1 REPLACEs with the halves read through the second set (mirrored in s).
  const Rendered mirrored =
      draw("mt_second_set",
           "texture MultiTexture { mode [ \"MODULATE\" \"REPLACE\" ] texture [ " +
               pixel("0xFFFFFF") + " " + halves + " ] }",
           coords);
  CHECK(close(mirrored.image.pixel(16, 32), 255, 255, 255, 3));
  CHECK(close(mirrored.image.pixel(48, 32), 0, 0, 0, 3));
  // Stage 1's transform shifts s by a half: the halves swap back; stage 0 takes the first
  // entry, and a plain TextureTransform on a MultiTexture would be ignored.
  const Rendered shifted = draw(
      "mt_transform",
      "texture MultiTexture { mode [ \"MODULATE\" \"REPLACE\" ] texture [ " + pixel("0xFFFFFF") +
          " " + halves +
          " ] } textureTransform MultiTextureTransform { textureTransform [ TextureTransform {} "
          "TextureTransform { translation 0.5 0 } ] }",
      coords);
  CHECK(close(shifted.image.pixel(16, 32), 0, 0, 0, 3));
  CHECK(close(shifted.image.pixel(48, 32), 255, 255, 255, 3));
  const Rendered ignored =
      draw("mt_plain_transform", "texture MultiTexture { texture " + halves +
                                     " } textureTransform TextureTransform { translation 0.5 0 }");
  CHECK(close(ignored.image.pixel(16, 32), 0, 0, 0, 3));
  CHECK(close(ignored.image.pixel(48, 32), 255, 255, 255, 3));
}

TEST_CASE("MultiTexture: an unknown mode is one warning and reads as MODULATE",
          "[render][offscreen][world][multitexture]") {
  const Rendered r = draw(
      "mt_unknown", "texture MultiTexture { mode \"SPARKLE\" texture " + pixel("0x808080") + " }");
  REQUIRE(r.diagnostics.items.size() == 1);
  CHECK(r.diagnostics.items[0].message.find("SPARKLE") != std::string::npos);
  CHECK(close(centre(r), 128, 128, 128, 3));
}

TEST_CASE("an X3D texture under 16 texels without TextureProperties is drawn with nearest texels",
          "[render][texture][x3d]") {
  // X_ITE 15's rule (its getMinTextureSize): a small X3D texture stays crisp. A VRML97
  // world's is filtered (bilinear between texel centres), as castle-model-viewer draws it.
  const std::string shape =
      "Viewpoint { position 0 0 2.4 }\n"
      "Shape { appearance Appearance { texture PixelTexture { image 2 2 1 0x99 0x66 0x66 0x99 }"
      " } geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }"
      " coordIndex [0 1 2 3] texCoord TextureCoordinate { point [0 0, 1 0, 1 1, 0 1] }"
      " texCoordIndex [0 1 2 3] } }\n";
  // The levels a row of the picture holds, between the quad's edges.
  const auto levels = [](const Rendered& r) {
    std::set<int> seen;
    const int y = gs::test::kWorldSize / 4;
    for (int x = gs::test::kWorldSize / 4; x < 3 * gs::test::kWorldSize / 4; ++x)
      seen.insert(r.image.pixel(x, y)[0]);
    return seen;
  };
  const fs::path x3d = worldDir() / "small_texture.x3dv";
  writeText(x3d, "#X3D V4.0 utf8\nPROFILE Interchange\n" + shape);
  const std::set<int> crisp = levels(renderFile(x3d));
  INFO("X3D levels: " << crisp.size());
  CHECK(crisp == std::set<int>{0x66, 0x99});
  const fs::path vrml = worldDir() / "small_texture.wrl";
  writeText(vrml, "#VRML V2.0 utf8\n" + shape);
  CHECK(levels(renderFile(vrml)).size() > 4);  // a ramp between the two greys
}

TEST_CASE(
    "an X3D RGB(A) texture multiplies Material.diffuseColor and its alpha the material's; "
    "VRML97's replaces them",
    "[render][texture][x3d]") {
  // X3D 4.0 clause 17.2.2.4, as X_ITE and castle-model-viewer draw X3D 3 files too; VRML97
  // table 4.5 keeps the replacing rule. The headlight lights the quad head on (N . L = 1), so
  // the pixel is diffuse x texture; a black Background shows the alpha.
  const std::string shape =
      "Viewpoint { position 0 0 1 fieldOfView 1.5708 }\n"
      "Shape { appearance Appearance { material Material { diffuseColor 1 0.5 0 "
      "transparency 0.5 } texture PixelTexture { image 1 1 4 0xFFFFFFFF } }\n"
      "  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }"
      " coordIndex [0 1 2 3 -1] } }\n";
  const fs::path x3d = worldDir() / "texture_modulates.x3dv";
  writeText(x3d, "#X3D V3.0 utf8\nPROFILE Interchange\n" + shape);
  const Rendered modulated = renderFile(x3d);
  // (1, 0.5, 0) x white at alpha 0.5 over black.
  CHECK(close(centre(modulated), 128, 64, 0, 8));
  const fs::path vrml = worldDir() / "texture_modulates.wrl";
  writeText(vrml, "#VRML V2.0 utf8\n" + shape);
  CHECK(close(centre(renderFile(vrml)), 255, 255, 255, 8));  // the texture's white, opaque
}
