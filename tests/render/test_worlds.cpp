// Whole worlds through the real parser and tessellator, rendered off-screen at 64x64:
// ImageTexture files, Inline with relative URLs, Fog, PointLight radius.
#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using gs::render::Image;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;
constexpr int kSize = gs::test::kWorldSize;

TEST_CASE("ImageTexture reads a PNG relative to the world", "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  gs::render::writePng((dir / "sub" / "green.png").string(), Image(2, 2, 0, 255, 0));
  writeText(dir / "textured.wrl", R"(#VRML V2.0 utf8
Viewpoint { position 0 0 3 }
Shape {
  appearance Appearance { texture ImageTexture { url [ "missing.png" "sub/green.png" ] } }
  geometry Box { size 4 4 1 }
}
)");
  const Rendered r = renderFile(dir / "textured.wrl");
  CHECK(close(r.image.pixel(32, 32), 0, 255, 0, 4));
  CHECK(r.diagnostics.items.empty());  // the second URL worked

  writeText(dir / "untextured.wrl", R"(#VRML V2.0 utf8
Viewpoint { position 0 0 3 }
Shape {
  appearance Appearance { texture ImageTexture { url "nowhere.png" } }
  geometry Box { size 4 4 1 }
}
)");
  const Rendered missing = renderFile(dir / "untextured.wrl");
  CHECK(close(missing.image.pixel(32, 32), 255, 255, 255, 4));  // unlit white
  REQUIRE(missing.diagnostics.items.size() == 1);
  CHECK(missing.diagnostics.items[0].message.find("nowhere.png") != std::string::npos);
}

TEST_CASE("Inline resolves URLs against the inlined file", "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "sub" / "part.wrl", R"(#VRML V2.0 utf8
Inline { url "../part2.wrl" }
)");
  writeText(dir / "part2.wrl", R"(#VRML V2.0 utf8
Shape {
  appearance Appearance { material Material { emissiveColor 1 0 0 diffuseColor 0 0 0 } }
  geometry Box { }
}
)");
  writeText(dir / "inliner.wrl", R"(#VRML V2.0 utf8
NavigationInfo { headlight FALSE }
Transform { translation 0 0 -1 children Inline { url "sub/part.wrl" } }
)");
  const Rendered r = renderFile(dir / "inliner.wrl");
  CHECK(close(r.image.pixel(32, 32), 255, 0, 0, 3));
  CHECK(close(r.image.pixel(0, 0), 0, 0, 0, 3));
}

TEST_CASE("LINEAR fog blends towards the fog colour with distance", "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // The box's front face is 9 m from the viewer: f0 = (20 - 9) / 20 = 0.55.
  writeText(dir / "fog.wrl", R"(#VRML V2.0 utf8
Viewpoint { position 0 0 10 }
Fog { color 0 0 0 fogType "LINEAR" visibilityRange 20 }
Shape {
  appearance Appearance { material Material { emissiveColor 1 1 1 diffuseColor 0 0 0 } }
  geometry Box { }
}
)");
  const Rendered r = renderFile(dir / "fog.wrl");
  INFO("centre " << int(r.image.pixel(32, 32)[0]));
  CHECK(close(r.image.pixel(32, 32), 140, 140, 140, 4));
}

TEST_CASE("a PointLight lights only within its radius", "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "pointlight.wrl", R"(#VRML V2.0 utf8
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
PointLight { location 0 0 1 radius 1.5 }
Shape {
  appearance Appearance { material Material { diffuseColor 1 1 1 ambientIntensity 0 } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -4 -4 0, 4 -4 0, 4 4 0, -4 4 0 ] }
    coordIndex [ 0 1 2 3 -1 ]
  }
}
)");
  const Rendered r = renderFile(dir / "pointlight.wrl");
  CHECK(close(r.image.pixel(32, 32), 255, 255, 255, 4));  // straight below the light
  CHECK(close(r.image.pixel(4, 4), 0, 0, 0, 2));          // beyond the radius
}

TEST_CASE("a node other than Material in Appearance.material leaves the shape unlit white",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "not_a_material.wrl", R"(#VRML V2.0 utf8
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 3 }
Shape { appearance Appearance { material Box { } } geometry Box { size 4 4 0.1 } }
)");
  const Rendered r = renderFile(dir / "not_a_material.wrl");
  // Unlit white (clause 4.14.1), not a Material's default grey without lights (black).
  CHECK(close(r.image.pixel(kSize / 2, kSize / 2), 255, 255, 255, 8));
}

TEST_CASE("the X3D asset draws the same in the Classic VRML, XML and JSON encodings",
          "[render][offscreen][world][x3d]") {
  const fs::path dir = gs::test::sourceDir() / "assets/worlds";
  const Rendered classic = renderFile(dir / "x3d_features.x3dv");
  const Rendered xml = renderFile(dir / "x3d_features.x3d");
  const Rendered json = renderFile(dir / "x3d_features.x3dj");
  REQUIRE(classic.image.width == xml.image.width);
  CHECK(classic.image.rgba == xml.image.rgba);
  CHECK(classic.image.rgba == json.image.rgba);
  // Each of the four X3D shapes shows in its colour: the red IndexedTriangleSet, the
  // green Box Switch.children chose, the blue Rectangle2D and the yellow LineSet.
  int red = 0, green = 0, blue = 0, yellow = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const std::uint8_t* p = classic.image.pixel(x, y);
      red += close(p, 255, 0, 0, 60) ? 1 : 0;
      green += close(p, 0, 255, 0, 60) ? 1 : 0;
      blue += close(p, 0, 0, 255, 60) ? 1 : 0;
      yellow += close(p, 255, 255, 0, 60) ? 1 : 0;
    }
  CHECK(red > 20);
  CHECK(green > 20);
  CHECK(blue > 20);
  CHECK(yellow > 0);
}

TEST_CASE("TextureProperties: nearest and linear magnification, mirrored repeat",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // A 2x1 texture (black, white) across the whole view (s from 0 to `sMax`).
  auto world = [](const std::string& properties, int sMax) {
    const std::string s = std::to_string(sMax);
    return "#X3D V4.0 utf8\nPROFILE Immersive\n"
           "Viewpoint { position 0 0 1 fieldOfView 1.5708 }\n"
           "Shape { appearance Appearance { texture PixelTexture { image 2 1 1 0x00 0xFF " +
           properties +
           " } }\n"
           "  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] "
           "}\n"
           "    coordIndex [0 1 2 3 -1] texCoord TextureCoordinate { point [0 0, " +
           s + " 0, " + s + " 1, 0 1] } texCoordIndex [0 1 2 3 -1] } }\n";
  };
  // (Linear asked for: without TextureProperties a texture this small is drawn with nearest
  // texels in an X3D world, as X_ITE draws it; test_multi_texture.cpp.)
  writeText(dir / "tp_linear.x3dv",
            world("textureProperties TextureProperties { magnificationFilter \"AVG_PIXEL\" "
                  "boundaryModeS \"CLAMP_TO_EDGE\" }",
                  1));
  writeText(dir / "tp_nearest.x3dv",
            world("textureProperties TextureProperties { magnificationFilter \"NEAREST_PIXEL\" "
                  "boundaryModeS \"CLAMP_TO_EDGE\" }",
                  1));
  writeText(
      dir / "tp_repeat.x3dv",
      world("textureProperties TextureProperties { magnificationFilter \"NEAREST_PIXEL\" }", 2));
  writeText(dir / "tp_mirrored.x3dv",
            world("textureProperties TextureProperties { magnificationFilter \"NEAREST_PIXEL\" "
                  "boundaryModeS \"MIRRORED_REPEAT\" }",
                  2));
  // Just left and right of the middle: blended grey when linear, black then white when
  // nearest.
  const Rendered linear = renderFile(dir / "tp_linear.x3dv");
  INFO("linear " << int(linear.image.pixel(30, 32)[0]) << " "
                 << int(linear.image.pixel(33, 32)[0]));
  CHECK(linear.image.pixel(30, 32)[0] > 60);
  CHECK(linear.image.pixel(33, 32)[0] < 195);
  const Rendered nearest = renderFile(dir / "tp_nearest.x3dv");
  CHECK(nearest.image.pixel(30, 32)[0] < 10);
  CHECK(nearest.image.pixel(33, 32)[0] > 245);
  // s in [1.25, 1.5) at x = 40..47: REPEAT reads texel 0 (black), MIRRORED_REPEAT texel 1.
  const Rendered repeat = renderFile(dir / "tp_repeat.x3dv");
  const Rendered mirrored = renderFile(dir / "tp_mirrored.x3dv");
  CHECK(repeat.image.pixel(44, 32)[0] < 10);
  CHECK(mirrored.image.pixel(44, 32)[0] > 245);
}

TEST_CASE("shader variants draw the pixels of the generic program, from the second frame on",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  gs::render::writePng((dir / "sub" / "rgb.png").string(), Image(2, 2, 200, 120, 40));
  // Every light kind, a texture, colours per vertex, fog and an unlit line: each shape
  // its own variant.
  writeText(dir / "variants.wrl", R"(#VRML V2.0 utf8
Viewpoint { position 0 0 6 }
Fog { color 0.2 0.2 0.3 fogType "EXPONENTIAL" visibilityRange 30 }
PointLight { location 2 2 3 color 1 0.8 0.6 attenuation 0 0.2 0 }
SpotLight { location -2 2 4 direction 0.3 -0.3 -1 cutOffAngle 0.6 beamWidth 0.3 }
DirectionalLight { direction 0 -1 -0.5 intensity 0.5 }
Transform { translation -1.5 0.8 0 children Shape {
  appearance Appearance { material Material { diffuseColor 0.9 0.3 0.2 specularColor 1 1 1 shininess 0.5 } }
  geometry Sphere { radius 0.9 } } }
Transform { translation 1.5 0.8 0 children Shape {
  appearance Appearance { material Material {} texture ImageTexture { url "sub/rgb.png" } }
  geometry Box { size 1.4 1.4 1.4 } } }
Transform { translation 0 -1.2 0 children Shape {
  appearance Appearance { material Material {} }
  geometry IndexedFaceSet { coord Coordinate { point [-2 -0.6 0, 2 -0.6 0, 2 0.6 0, -2 0.6 0] }
    coordIndex [0 1 2 3 -1] color Color { color [1 0 0, 0 1 0, 0 0 1, 1 1 0] } } } }
Shape { appearance Appearance { material Material { emissiveColor 1 1 1 } }
  geometry IndexedLineSet { coord Coordinate { point [-3 2.2 0, 3 2.2 0] } coordIndex [0 1 -1] } }
)");
  static auto context = gs::render::createOffscreenContext(kSize, kSize);
  context->makeCurrent();
  auto scene =
      std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile((dir / "variants.wrl").string()));
  REQUIRE(scene->diagnostics.errorCount() == 0);
  gs::render::SceneRenderer r(scene);
  const auto camera = r.initialCamera(1.0f);
  r.draw(camera, 0, 0, kSize, kSize);
  CHECK(r.statistics().shaderVariants == 0);  // the first frame: the generic program only
  const Image generic = gs::render::readPixels(0, 0, kSize, kSize);
  for (int frame = 0; frame < 4; ++frame) r.draw(camera, 0, 0, kSize, kSize);
  CHECK(r.statistics().shaderVariants >= 4);
  const Image specialized = gs::render::readPixels(0, 0, kSize, kSize);
  if (const char* dump = std::getenv("GS_RENDER_TEST_DUMP"))
    gs::render::writePng((fs::path(dump) / "variants_specialized.png").string(), specialized);
  int worst = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(generic.pixel(x, y)[c] - specialized.pixel(x, y)[c]));
  CHECK(worst <= 2);
  // The picture is not empty: the variants drew something.
  CHECK(specialized.pixel(kSize / 2 - 16, kSize / 2 - 10)[0] > 40);

  gs::render::SceneRendererOptions options;
  options.shaderVariants = false;
  gs::render::SceneRenderer plain(scene, options);
  for (int frame = 0; frame < 5; ++frame) plain.draw(camera, 0, 0, kSize, kSize);
  CHECK(plain.statistics().shaderVariants == 0);
}

namespace {

/// A world with one sphere of `material` at the origin, seen from 0 0 3.2 (radius about 24
/// pixels), lit only by an EnvironmentLight whose cube faces are one colour each.
std::string environmentWorld(const std::string& material, const std::string& faces,
                             const std::string& light = "") {
  return "#X3D V4.0 utf8\nPROFILE Immersive\nNavigationInfo { headlight FALSE }\n"
         "Viewpoint { position 0 0 3.2 }\n"
         "EnvironmentLight { global TRUE " +
         light + " specularTexture ComposedCubeMapTexture {\n" + faces +
         "} }\nShape { appearance Appearance { material PhysicalMaterial { " + material +
         " } } geometry Sphere { } }\n";
}

// +X red, -X blue, +Y white, -Y green, -Z (front) yellow, +Z (back) grey.
const std::string kColouredFaces =
    "rightTexture PixelTexture { image 1 1 3 0xFF0000 }\n"
    "leftTexture PixelTexture { image 1 1 3 0x0000FF }\n"
    "topTexture PixelTexture { image 1 1 3 0xFFFFFF }\n"
    "bottomTexture PixelTexture { image 1 1 3 0x00FF00 }\n"
    "frontTexture PixelTexture { image 1 1 3 0xFFFF00 }\n"
    "backTexture PixelTexture { image 1 1 3 0x808080 }\n";

}  // namespace

TEST_CASE("EnvironmentLight: a mirror reflects each cube face from its direction",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "env_mirror.x3dv",
            environmentWorld("baseColor 1 1 1 metallic 1 roughness 0", kColouredFaces));
  const Rendered r = renderFile(dir / "env_mirror.x3dv");
  CHECK(r.diagnostics.items.empty());
  // The normal at 45 degrees to the view reflects the view ray by 90 degrees.
  const std::uint8_t* right = r.image.pixel(49, 32);
  const std::uint8_t* left = r.image.pixel(15, 32);
  const std::uint8_t* top = r.image.pixel(32, 15);
  const std::uint8_t* bottom = r.image.pixel(32, 49);
  INFO("right " << int(right[0]) << " " << int(right[1]) << " " << int(right[2]));
  INFO("left " << int(left[0]) << " " << int(left[1]) << " " << int(left[2]));
  INFO("top " << int(top[0]) << " " << int(top[1]) << " " << int(top[2]));
  INFO("bottom " << int(bottom[0]) << " " << int(bottom[1]) << " " << int(bottom[2]));
  CHECK((right[0] > 200 && right[1] < 60 && right[2] < 60));
  CHECK((left[2] > 200 && left[0] < 60 && left[1] < 60));
  CHECK((top[0] > 200 && top[1] > 200 && top[2] > 200));
  CHECK((bottom[1] > 200 && bottom[0] < 60 && bottom[2] < 60));
  // Straight back along the view ray: the +Z face behind the viewer, grey 0x80.
  CHECK(close(r.image.pixel(32, 32), 128, 128, 128, 12));
}

TEST_CASE("EnvironmentLight: diffuse light is the cube's irradiance, at its intensity",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  std::string grey;
  for (const char* face : {"right", "left", "top", "bottom", "front", "back"})
    grey += std::string(face) + "Texture PixelTexture { image 1 1 3 0x808080 }\n";
  const std::string white = "baseColor 1 1 1 metallic 0 roughness 1";
  // A uniform environment of radiance L gives irradiance pi L: a white Lambertian sphere
  // shows L itself everywhere (the specular term adds f0 = 0.04 at most).
  writeText(dir / "env_grey.x3dv", environmentWorld(white, grey));
  const Rendered uniform = renderFile(dir / "env_grey.x3dv");
  INFO("centre " << int(uniform.image.pixel(32, 32)[0]));
  CHECK(close(uniform.image.pixel(32, 32), 129, 129, 129, 6));
  CHECK(close(uniform.image.pixel(12, 32), 129, 129, 129, 8));
  // Coloured faces: the side facing +X is redder than the side facing -X, and the other
  // way round for blue.
  writeText(dir / "env_diffuse.x3dv", environmentWorld(white, kColouredFaces));
  const Rendered coloured = renderFile(dir / "env_diffuse.x3dv");
  const std::uint8_t* right = coloured.image.pixel(52, 32);
  const std::uint8_t* left = coloured.image.pixel(12, 32);
  CHECK(right[0] > right[2] + 40);
  CHECK(left[2] > left[0] + 40);
  // Switched off, or at intensity 0, it gives nothing: black without other lights.
  writeText(dir / "env_off.x3dv", environmentWorld(white, kColouredFaces, "on FALSE"));
  CHECK(close(renderFile(dir / "env_off.x3dv").image.pixel(32, 32), 0, 0, 0, 2));
  writeText(dir / "env_zero.x3dv", environmentWorld(white, kColouredFaces, "intensity 0"));
  CHECK(close(renderFile(dir / "env_zero.x3dv").image.pixel(32, 32), 0, 0, 0, 2));
}

TEST_CASE("EnvironmentLight: a texture it cannot read is one warning, the world still draws",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "env_bad.x3dv",
            "#X3D V4.0 utf8\nPROFILE Immersive\nNavigationInfo { headlight FALSE }\n"
            "Viewpoint { position 0 0 3.2 }\n"
            "EnvironmentLight { specularTexture ImageCubeMapTexture { url \"sky.dds\" } }\n"
            "Shape { appearance Appearance { material PhysicalMaterial { baseColor 0 0 0 "
            "emissiveColor 1 1 1 } } "
            "geometry Sphere { } }\n");
  const Rendered r = renderFile(dir / "env_bad.x3dv");
  REQUIRE(r.diagnostics.items.size() == 1);
  CHECK(r.diagnostics.items[0].message.find("ImageCubeMapTexture") != std::string::npos);
  CHECK(close(r.image.pixel(32, 32), 255, 255, 255, 2));
}

TEST_CASE("ClipPlane clips its siblings and their descendants in its own coordinates",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // Two white quads at z = 0 and z = -0.01 spanning the view, seen from 0 0 5 (a metre is
  // about 15.5 pixels). The plane x >= 0 of a Transform moved by 1 keeps world x >= 1 of
  // the quad beside it; the quad outside that Transform is not clipped but lies behind.
  writeText(dir / "clip.x3dv", R"(#X3D V4.0 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
Transform {
  translation 1 0 0
  children [
    ClipPlane { plane 1 0 0 0 }
    Transform {
      translation -1 0 0
      children Shape {
        appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 1 1 } }
        geometry IndexedFaceSet { coord Coordinate { point [ -4 -4 0, 4 -4 0, 4 4 0, -4 4 0 ] }
                                  coordIndex [ 0 1 2 3 -1 ] }
      }
    }
  ]
}
Shape {
  appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 0 0 } }
  geometry IndexedFaceSet { coord Coordinate { point [ -4 -4 -0.01, 4 -4 -0.01, 4 4 -0.01, -4 4 -0.01 ] }
                            coordIndex [ 0 1 2 3 -1 ] }
}
)");
  const Rendered r = renderFile(dir / "clip.x3dv");
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(55, 32), 255, 255, 255, 2));  // x = 1.5: kept
  CHECK(close(r.image.pixel(40, 32), 255, 0, 0, 2));      // x = 0.5: clipped, red behind
  CHECK(close(r.image.pixel(10, 32), 255, 0, 0, 2));      // x = -1.4: clipped
  // Disabled, it clips nothing.
  std::ifstream in(dir / "clip.x3dv");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text.replace(text.find("plane 1 0 0 0"), 13, "plane 1 0 0 0 enabled FALSE");
  writeText(dir / "clip_off.x3dv", text);
  CHECK(close(renderFile(dir / "clip_off.x3dv").image.pixel(10, 32), 255, 255, 255, 2));
}

TEST_CASE("TwoSidedMaterial lights back faces with its back colours when separateBackColor",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  const auto world = [](const std::string& separate) {
    // Left quad faces the viewer (counterclockwise), the right one turns its back.
    return R"(#X3D V4.0 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
Shape {
  appearance Appearance {
    material TwoSidedMaterial { separateBackColor )" +
           separate + R"( diffuseColor 0 0 0 emissiveColor 1 0 0
                                backDiffuseColor 0 0 0 backEmissiveColor 0 0 1 }
  }
  geometry IndexedFaceSet {
    solid FALSE
    coord Coordinate { point [ -2 -1 0, -0.2 -1 0, -0.2 1 0, -2 1 0,
                               0.2 -1 0, 2 -1 0, 2 1 0, 0.2 1 0 ] }
    coordIndex [ 0 1 2 3 -1, 7 6 5 4 -1 ]
  }
}
)";
  };
  writeText(dir / "two_sided.x3dv", world("TRUE"));
  const Rendered separate = renderFile(dir / "two_sided.x3dv");
  CHECK(separate.diagnostics.items.empty());
  CHECK(close(separate.image.pixel(18, 32), 255, 0, 0, 2));  // front: emissiveColor
  CHECK(close(separate.image.pixel(46, 32), 0, 0, 255, 2));  // back: backEmissiveColor
  writeText(dir / "two_sided_same.x3dv", world("FALSE"));
  const Rendered same = renderFile(dir / "two_sided_same.x3dv");
  CHECK(close(same.image.pixel(46, 32), 255, 0, 0, 2));  // both sides take the front values
}

TEST_CASE("X3D lights: global FALSE scopes a PointLight, global TRUE frees a DirectionalLight",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // Left quad: a scoped PointLight beside it. Right quad: in another group, lit only by a
  // global DirectionalLight from the left group when `directionalGlobal` is TRUE.
  const auto world = [](const std::string& directionalGlobal) {
    return R"(#X3D V3.2 utf8
PROFILE Interchange
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
Group { children [
  PointLight { location -1 0 1 global FALSE }
  DirectionalLight { direction 0 0 -1 intensity 0.5 global )" +
           directionalGlobal + R"( color 0 1 0 }
  Shape { appearance Appearance { material Material { diffuseColor 1 1 1 } }
          geometry IndexedFaceSet { coord Coordinate { point [ -2 -1 0, -0.2 -1 0, -0.2 1 0, -2 1 0 ] }
                                    coordIndex [ 0 1 2 3 -1 ] } }
] }
Group { children
  Shape { appearance Appearance { material Material { diffuseColor 1 1 1 } }
          geometry IndexedFaceSet { coord Coordinate { point [ 0.2 -1 0, 2 -1 0, 2 1 0, 0.2 1 0 ] }
                                    coordIndex [ 0 1 2 3 -1 ] } }
}
)";
  };
  writeText(dir / "lights_scoped.x3dv", world("FALSE"));
  const Rendered scoped = renderFile(dir / "lights_scoped.x3dv");
  CHECK(scoped.diagnostics.items.empty());
  CHECK(scoped.image.pixel(18, 32)[0] > 100);            // the PointLight lights its sibling
  CHECK(close(scoped.image.pixel(46, 32), 0, 0, 0, 2));  // ... and nothing else
  writeText(dir / "lights_global.x3dv", world("TRUE"));
  const Rendered global = renderFile(dir / "lights_global.x3dv");
  CHECK(close(global.image.pixel(46, 32), 0, 128, 0, 3));  // the global green light
}

TEST_CASE("X3D 4 Material.diffuseTexture textures the shape and multiplies diffuseColor",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  writeText(dir / "diffuse_texture.x3dv", R"(#X3D V4.0 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
DirectionalLight { direction 0 0 -1 }
Shape {
  appearance Appearance {
    material Material { diffuseColor 1 0 0
                        diffuseTexture PixelTexture { image 2 1 3 0xFFFFFF 0x00FF00
                                                       repeatS FALSE repeatT FALSE } }
  }
  geometry IndexedFaceSet { coord Coordinate { point [ -2 -1 0, 2 -1 0, 2 1 0, -2 1 0 ] }
                            coordIndex [ 0 1 2 3 -1 ] }
}
)");
  const Rendered r = renderFile(dir / "diffuse_texture.x3dv");
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(6, 32), 255, 0, 0, 3));  // red x white
  CHECK(close(r.image.pixel(58, 32), 0, 0, 0, 3));   // red x green
}

TEST_CASE("ColorRGBA alpha makes a shape translucent", "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // A red quad behind a white one whose colours have alpha 0.25: mostly red shows.
  writeText(dir / "color_rgba.x3dv", R"(#X3D V3.2 utf8
PROFILE Interchange
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Shape { appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 0 0 } }
  geometry QuadSet { coord Coordinate { point [-1 -1 -0.5, 1 -1 -0.5, 1 1 -0.5, -1 1 -0.5] } } }
Shape { geometry QuadSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
  color ColorRGBA { color [1 1 1 0.25, 1 1 1 0.25, 1 1 1 0.25, 1 1 1 0.25] } } }
)");
  const Rendered r = renderFile(dir / "color_rgba.x3dv");
  CHECK(r.diagnostics.items.empty());
  // 0.25 white over red: (255, 64, 64).
  CHECK(close(r.image.pixel(32, 32), 255, 64, 64, 4));
}

TEST_CASE("H-Anim: a humanoid places its skeleton and skin, a joint moves its children",
          "[render][offscreen][world]") {
  const fs::path dir = worldDir();
  // Seen from 0 0 5 at 45 degrees on 64x64: a metre is about 15.5 pixels, world (1, 1) at
  // pixel (47, 17). The humanoid is at x 1; its joint lifts the segment's box by 1; its
  // skin's box stays at the humanoid's origin.
  writeText(dir / "hanim.x3dv", R"(#X3D V4.0 utf8
PROFILE Full
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 5 }
HAnimHumanoid { translation 1 0 0
  skeleton HAnimJoint { translation 0 1 0 children HAnimSegment { children Shape {
    appearance Appearance { material Material { emissiveColor 1 0 0 diffuseColor 0 0 0 } }
    geometry Box { size 0.4 0.4 0.4 } } } }
  skin Shape { appearance Appearance { material Material { emissiveColor 0 1 0 diffuseColor 0 0 0 } }
    geometry Box { size 0.4 0.4 0.4 } } }
)");
  const Rendered r = renderFile(dir / "hanim.x3dv");
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(47, 17), 255, 0, 0, 8));  // the segment's box at (1, 1, 0)
  CHECK(close(r.image.pixel(47, 32), 0, 255, 0, 8));  // the skin's at (1, 0, 0)
  CHECK(close(r.image.pixel(32, 32), 0, 0, 0, 8));    // nothing at the origin
}
