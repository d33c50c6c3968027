// Multisample anti-aliasing (--samples N, docs/rendering.md "Anti-aliasing"): the
// off-screen framebuffer is multisampled and resolved before it is read, for the PNG and for
// the depth the cpu splat path composites against.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "baseline.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

fs::path writeWorld(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "antialiasing";
  fs::create_directories(dir);
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// A white, unlit Box turned 30 degrees about z on black: two colours without
// anti-aliasing, partly covered pixels along its edges with it.
const char* kBox = R"(#VRML V2.0 utf8
Viewpoint { position 0 0 6 }
NavigationInfo { headlight FALSE }
Transform {
  rotation 0 0 1 0.5236
  children Shape {
    appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 1 1 } }
    geometry Box { size 2 2 2 }
  }
}
)";

struct Levels {
  std::size_t black = 0, white = 0, between = 0;
};

Levels greyLevels(const std::string& png) {
  const gs::render::Image image = gs::render::readPng(png);
  Levels levels;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const int v = image.rgba[i];
    (v == 0 ? levels.black : v == 255 ? levels.white : levels.between) += 1;
  }
  return levels;
}

}  // namespace

TEST_CASE("snapshots are anti-aliased with samples 4 and not without",
          "[app][render][antialiasing]") {
  const std::string world = writeWorld("box.wrl", kBox).string();
  const std::string plain = gs::test::snapshot("aa_box_1", {"--size", "120x120", world});
  const std::string smooth =
      gs::test::snapshot("aa_box_4", {"--size", "120x120", "--samples", "4", world});
  const Levels a = greyLevels(plain), b = greyLevels(smooth);
  CHECK(a.between == 0);
  CHECK(a.white > 1000);
  // The edges' pixels: 4 sides of about 40 pixels each, most of them partly covered.
  CHECK(b.between > 100);
  // Only the edges differ: the box's inside and the background are the same.
  CHECK(gs::test::centrePixel(smooth) == std::array<int, 3>{255, 255, 255});
  CHECK(gs::test::fractionDiffering(plain, smooth) < 0.03);
  CHECK(gs::test::fractionDiffering(plain, smooth) > 0.002);
}

TEST_CASE("with --samples 4 a polygon still hides the splats behind it on every splat path",
          "[app][render][antialiasing][splat]") {
  // A wide red Gaussian 2 m behind a blue Box that covers the picture's centre.
  const std::string world = writeWorld("occlusion.x3dv", R"(#X3D V4.0 utf8
PROFILE Interchange
COMPONENT GaussianSplats:1
Viewpoint { position 0 0 6 }
NavigationInfo { headlight FALSE }
Shape {
  appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 } }
  geometry Box { size 1 1 1 }
}
Transform {
  translation 0 0 -2
  children GaussianSplats {
    positions [ 0 0 0 ]
    orientations [ 0 0 0 1 ]
    scales [ 1 1 0.1 ]
    opacities [ 1 ]
    sphericalHarmonicsDegree0Coef0 [ 1.77 -1.77 -1.77 ]
  }
}
)")
                                .string();
  for (const char* path : {"cpu", "geometry", "gpu"}) {
    INFO(path);
    const std::string png =
        gs::test::snapshot(std::string("aa_occlusion_") + path,
                           {"--size", "100x100", "--samples", "4", "--splat-path", path, world});
    CHECK(gs::test::centrePixel(png) == std::array<int, 3>{0, 0, 255});
    // The Gaussian shows around the Box (left of it, on the centre row).
    const gs::render::Image image = gs::render::readPng(png);
    const std::size_t left = (static_cast<std::size_t>(image.width) * 50 + 30) * 4;
    CHECK(int(image.rgba[left]) > 60);
  }
}
