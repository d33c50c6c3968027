// X3D's Environmental effects beyond VRML97's (X3D 4.0 clause 24): TextureBackground, a
// Background whose six faces are texture nodes (24.4.3), and LocalFog, fog scoped to its
// siblings (24.4.4), and castle-engine's volumetric Fog; drawn off-screen at 64x64.
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

TEST_CASE("LocalFog fogs its siblings and their descendants, and only them",
          "[render][offscreen][world][fog]") {
  // Two emissive blue quads 1 m in front of the viewer, left and right; a red LINEAR
  // LocalFog with visibilityRange 2 beside the left one: f0 = (2 - 1) / 2 = 0.5 there.
  const fs::path file = worldDir() / "local_fog.x3dv";
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
DEF Q Shape {
  appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 } }
  geometry IndexedFaceSet { coord Coordinate { point [-2 -2 0, 0 -2 0, 0 2 0, -2 2 0] }
    coordIndex [0 1 2 3 -1] } }
Group { children [
  LocalFog { color 1 0 0 visibilityRange 2 }
  Transform { translation 2 0 0 children USE Q }
] }
)");
  for (int frames : {1, 3}) {
    INFO("frames " << frames);
    const Rendered r = renderFile(file, frames);
    CHECK(r.diagnostics.items.empty());
    // Near the middle the distance is 1 m (1.001 at pixel 33: f0 = 0.4994).
    CHECK(close(r.image.pixel(30, 32), 0, 0, 255, 4));    // outside the LocalFog's group
    CHECK(close(r.image.pixel(33, 32), 128, 0, 127, 6));  // half fogged
    CHECK(close(r.image.pixel(60, 32), 0, 0, 255, 4) == false);
  }
}

TEST_CASE("FogCoordinate depths are the amount of fog, 0 none to 1 all",
          "[render][offscreen][world][fog]") {
  // As X_ITE and castle-model-viewer read them (castle's fog_coordinate.x3dv: "explicit fog
  // amount"). A red LINEAR Fog of visibility range 2; three emissive blue quads 1 m away:
  // without a FogCoordinate (half fogged by distance), with depths 0 (not fogged) and with
  // depths 0.75 (f0 = 0.25), whatever the visibility range.
  // The same with a PhysicalMaterial (the physical program).
  for (const char* material : {"Material { diffuseColor 0 0 0 emissiveColor 0 0 1 }",
                               "PhysicalMaterial { baseColor 0 0 0 emissiveColor 0 0 1 }"}) {
    const fs::path file = worldDir() / "fog_coordinate.x3dv";
    writeText(file, R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT EnvironmentalEffects:4
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Fog { color 1 0 0 visibilityRange 2 }
DEF A Appearance { material )" +
                        std::string(material) + R"( }
Shape { appearance USE A geometry IndexedFaceSet { coordIndex [0 1 2 3 -1]
  coord Coordinate { point [-1 -1 0, -0.34 -1 0, -0.34 1 0, -1 1 0] } } }
Shape { appearance USE A geometry IndexedFaceSet { coordIndex [0 1 2 3 -1]
  coord Coordinate { point [-0.33 -1 0, 0.33 -1 0, 0.33 1 0, -0.33 1 0] }
  fogCoord FogCoordinate { depth [0 0 0 0] } } }
Shape { appearance USE A geometry IndexedFaceSet { coordIndex [0 1 2 3 -1]
  coord Coordinate { point [0.34 -1 0, 1 -1 0, 1 1 0, 0.34 1 0] }
  fogCoord FogCoordinate { depth [0.75 0.75 0.75 0.75] } } }
)");
    for (int frames : {1, 3}) {
      INFO(material << ", frames " << frames);
      const Rendered r = renderFile(file, frames);
      CHECK(r.diagnostics.items.empty());
      // Pixel 32 is at distance 1.0002: f0 = 0.4999 without a FogCoordinate; here depth 0.
      CHECK(close(r.image.pixel(32, 32), 0, 0, 255, 4));
      // Left quad at pixel 12: x = -0.609, distance 1.171, f0 = 0.4145.
      CHECK(close(r.image.pixel(12, 32), 149, 0, 106, 4));
      // Right quad: depth 0.75, f0 = 0.25 (red 0.75, blue 0.25) wherever it is seen.
      CHECK(close(r.image.pixel(52, 32), 191, 0, 64, 4));
      CHECK(close(r.image.pixel(52, 5), 191, 0, 64, 4));
    }
  }
}

TEST_CASE("castle's volumetric Fog: the fog distance is the height along its direction",
          "[render][offscreen][world][fog]") {
  // An emissive blue quad 1 m ahead filling the 90-degree view; a red LINEAR Fog of range
  // 2, volumetric downwards (0 -1 0) from height 0: a point at height y is fogged by
  // f0 = (2 - (-y)) / 2, none above y = 0, whatever its distance to the viewer.
  const fs::path file = worldDir() / "fog_volumetric.x3dv";
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Fog { color 1 0 0 visibilityRange 2 volumetric TRUE volumetricDirection 0 -3 0 }
Shape { appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 } }
  geometry IndexedFaceSet { coord Coordinate { point [-2 -2 0, 2 -2 0, 2 2 0, -2 2 0] }
    coordIndex [0 1 2 3 -1] } }
)");
  const Rendered r = renderFile(file);
  CHECK(r.diagnostics.items.empty());
  // Row 16 is at y = +0.484 (the eye-distance fog would give f0 = 0.44 there): no fog.
  CHECK(close(r.image.pixel(32, 16), 0, 0, 255, 4));
  CHECK(close(r.image.pixel(5, 16), 0, 0, 255, 4));
  // Row 47 at y = -0.484: f0 = 0.758 (red 62, blue 193), the same at the side (x = -0.83).
  CHECK(close(r.image.pixel(32, 47), 62, 0, 193, 5));
  CHECK(close(r.image.pixel(5, 47), 62, 0, 193, 5));
  // Row 60 at y = -0.891: f0 = 0.555.
  CHECK(close(r.image.pixel(32, 60), 114, 0, 141, 5));
  // volumetricVisibilityStart -1 moves the fog's start up to y = 1: row 16 is now at
  // fog distance 1 - 0.484 = 0.516, f0 = 0.742 (red 66, blue 189).
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Fog { color 1 0 0 visibilityRange 2 volumetric TRUE volumetricVisibilityStart -1 }
Shape { appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 } }
  geometry IndexedFaceSet { coord Coordinate { point [-2 -2 0, 2 -2 0, 2 2 0, -2 2 0] }
    coordIndex [0 1 2 3 -1] } }
)");
  const Rendered shifted = renderFile(file);
  CHECK(close(shifted.image.pixel(32, 16), 66, 0, 189, 5));
}
