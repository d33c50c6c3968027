// The X3D browser options TextureQuality and Shading (--texture-quality, --shading;
// render/browser_options.hpp, docs/rendering.md "Browser options").
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "baseline.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace {

// An unlit floor seen at a grazing angle, textured with a 32x32 black-and-white
// checkerboard of 2-texel squares repeated 40 times: from the bottom of the picture up,
// its texels are magnified, then minified further and further.
std::string checkerFloor() {
  std::string texels;
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) texels += ((x / 2 + y / 2) % 2) != 0 ? " 0xFF" : " 0x00";
  return R"(#X3D V4.0 utf8
PROFILE Interchange
Viewpoint { position 0 1 10 orientation 1 0 0 -0.1 }
Shape {
  appearance Appearance {
    texture PixelTexture { image 32 32 1)" +
         texels + R"( }
    textureTransform TextureTransform { scale 40 40 }
  }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -100 0 -100, 100 0 -100, 100 0 100, -100 0 100 ] }
    coordIndex [ 3 2 1 0 -1 ]
    texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0 1 ] }
    solid FALSE
  }
}
)";
}

/// The standard deviation of the red channel over rows [top, bottom) of a PNG.
double rowsDeviation(const std::string& png, int top, int bottom) {
  const gs::render::Image image = gs::render::readPng(png);
  double sum = 0.0, squares = 0.0, n = 0.0;
  for (int y = top; y < bottom; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double v = image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
      sum += v;
      squares += v * v;
      n += 1.0;
    }
  const double mean = sum / n;
  return std::sqrt(std::max(0.0, squares / n - mean * mean));
}

}  // namespace

TEST_CASE(
    "the option TextureQuality picks the minification filter of textures without "
    "TextureProperties",
    "[app][render][texture]") {
  const gs::test::TempDir dir("texture_quality");
  const std::string world = dir.write("checker_floor.x3dv", checkerFloor());
  const auto shot = [&](const std::string& quality) {
    return gs::test::snapshot("texture_quality_" + quality,
                              {"--size", "160x160", "--texture-quality", quality, world});
  };
  const std::string high = shot("high"), medium = shot("medium"), low = shot("low");
  // The default is high.
  CHECK(gs::test::fractionDiffering(high, gs::test::snapshot("texture_quality_default",
                                                             {"--size", "160x160", world})) == 0.0);
  // Near the viewer the texels are magnified: bilinear in all three.
  CHECK(gs::test::fractionDiffering(high, medium) > 0.02);
  // The band where squares shrink to a texel or two: trilinear mipmaps blur them to grey,
  // medium keeps the nearest texels of its two mipmaps (more contrast), and low, without
  // mipmaps, keeps full black and white further up still.
  const int top = 84, bottom = 100;  // horizon at about row 68 of 160
  const double sHigh = rowsDeviation(high, top, bottom);
  const double sMedium = rowsDeviation(medium, top, bottom);
  const double sLow = rowsDeviation(low, 70, 84);
  INFO("deviation high " << sHigh << ", medium " << sMedium << ", low far " << sLow);
  CHECK(sMedium > sHigh + 15.0);
  CHECK(sLow > rowsDeviation(high, 70, 84) + 30.0);
}

TEST_CASE(
    "the option Shading GOURAUD multiplies the lit colour by the texture in VRML97 and X3D 3 "
    "worlds, PHONG the diffuse colour",
    "[app][render][texture]") {
  // A red emissive sphere without diffuse colour, textured pure blue: Phong's diffuse term
  // takes the texture (blue x 0 = nothing) and leaves the emissive red; Gouraud's texture
  // multiplies the lit colour, red x blue = black. X3D 4's lighting equation fixes the
  // texture's place (clause 17.2.2.4): such a world is red whatever the option.
  const gs::test::TempDir dir("shading");
  const auto world = [&](const std::string& name, const std::string& header) {
    return dir.write(name, header + R"(
Viewpoint { position 0 0 4 }
Background { skyColor [ 1 1 1 ] }
Shape {
  appearance Appearance {
    material Material { diffuseColor 0 0 0 emissiveColor 1 0 0 }
    texture PixelTexture { image 1 1 3 0x0000FF }
  }
  geometry Sphere { }
}
)");
  };
  const std::string x3d3 = world("emissive_textured_3.x3dv", "#X3D V3.3 utf8\nPROFILE Interchange");
  const std::string vrml97 = world("emissive_textured.wrl", "#VRML V2.0 utf8");
  const std::string x3d4 = world("emissive_textured_4.x3dv", "#X3D V4.0 utf8\nPROFILE Interchange");
  const auto shot = [](const std::string& name, const std::string& shading, const std::string& w) {
    return gs::test::snapshot(name, {"--size", "64x64", "--shading", shading, w});
  };
  const std::string phong = shot("shading_phong", "phong", x3d3);
  CHECK(gs::test::centrePixel(phong) == std::array<int, 3>{255, 0, 0});
  CHECK(gs::test::centrePixel(shot("shading_gouraud", "GOURAUD", x3d3)) ==
        std::array<int, 3>{0, 0, 0});
  CHECK(gs::test::centrePixel(shot("shading_gouraud_97", "gouraud", vrml97)) ==
        std::array<int, 3>{0, 0, 0});
  CHECK(gs::test::centrePixel(shot("shading_gouraud_4", "gouraud", x3d4)) ==
        std::array<int, 3>{255, 0, 0});
  CHECK(gs::test::fractionDiffering(
            phong, gs::test::snapshot("shading_default", {"--size", "64x64", x3d3})) == 0.0);
}

TEST_CASE("the options TextureQuality and Shading refuse names they do not know", "[app][cli]") {
  const gs::test::TempDir dir("browser_options");
  const std::string world = dir.write("empty.x3dv", "#X3D V4.0 utf8\nPROFILE Interchange\n");
  for (const std::vector<std::string>& bad : {std::vector<std::string>{"--texture-quality", "best"},
                                              std::vector<std::string>{"--shading", "smooth"}}) {
    std::vector<std::string> args = bad;
    args.push_back(world);
    const gs::test::ProcessResult r = gs::test::runGhostspace(args);
    INFO(r.err);
    CHECK(r.exitCode == 2);
  }
}
