// GeneratedCubeMapTexture (X3D 4.0 clause 34.4.1): the world drawn into a cube map from the
// shape's origin, which a mirror then reflects (render/src/generated_cube_maps.hpp); drawn
// off-screen at 64x64.
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

/// The viewer at the origin looks along world -X (its right is world -Z) at a mirror
/// quad at x = -1 filling its 90-degree view; behind the viewer, at x = 5 (6 metres from
/// the mirror's origin), a red wall around the axis, a green one above it and a yellow one
/// to the viewer's right (world -Z). `update` is the texture's update field.
Rendered drawMirror(const std::string& name, const std::string& update) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Interchange
COMPONENT CubeMapTexturing:3
NavigationInfo { headlight FALSE }
Background { skyColor 0.2 0.2 0.2 }
Viewpoint { position 0 0 0 orientation 0 1 0 1.5708 fieldOfView 1.5708 }
Transform { translation -1 0 0 rotation 0 1 0 1.5708 children Shape {
  appearance Appearance { texture GeneratedCubeMapTexture { update ")" +
                      update + R"(" size 32 } }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } }
Transform { translation 5 0 0 children Shape {
  appearance Appearance { material Material { emissiveColor 1 0 0 diffuseColor 0 0 0 } }
  geometry Box { size 1 2 2 } } }
Transform { translation 5 4 0 children Shape {
  appearance Appearance { material Material { emissiveColor 0 1 0 diffuseColor 0 0 0 } }
  geometry Box { size 1 4 8 } } }
Transform { translation 5 0 -4 children Shape {
  appearance Appearance { material Material { emissiveColor 1 1 0 diffuseColor 0 0 0 } }
  geometry Box { size 1 2 4 } } }
)");
  return renderFile(file);
}

}  // namespace

TEST_CASE(
    "GeneratedCubeMapTexture reflects the world around its shape, the right way up and "
    "round",
    "[render][offscreen][world][texgen]") {
  const Rendered r = drawMirror("generated_always", "ALWAYS");
  CHECK(r.diagnostics.items.empty());
  const auto at = [&](int x, int y) {
    const auto p = r.image.pixel(x, y);
    INFO(x << "," << y << ": " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]));
    return p;
  };
  CHECK(close(at(32, 32), 255, 0, 0, 8));    // straight back: the red wall
  CHECK(close(at(32, 6), 0, 255, 0, 8));     // up: the green one
  CHECK(close(at(58, 32), 255, 255, 0, 8));  // the viewer's right: the yellow one
  CHECK(close(at(6, 32), 51, 51, 51, 8));    // the left: the sky
}

TEST_CASE("GeneratedCubeMapTexture with update NONE (the default) is never drawn: black",
          "[render][offscreen][world][texgen]") {
  const Rendered r = drawMirror("generated_none", "NONE");
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(32, 32), 0, 0, 0, 8));
}
