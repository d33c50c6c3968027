// X3D VolumeRendering data nodes drawn as QNV gradient vectors (render/src/volume_data.hpp):
// the voxels of PixelTexture3D, ImageTexture3D (NRRD, attached or detached) and
// ComposedTexture3D, IsoSurfaceVolumeData's value window, OpacityMapVolumeStyle's transfer
// function, and the errors a bad volume gives, drawn off-screen at 64x64.
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

/// A 6x6x6 PixelTexture3D: a bright 2x2x2 cube (200) in a dark one (0).
std::string cubeVoxels() {
  std::string image = "PixelTexture3D { image [ 1 6 6 6";
  for (int z = 0; z < 6; ++z)
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 6; ++x) {
        const bool inside = x >= 2 && x <= 3 && y >= 2 && y <= 3 && z >= 2 && z <= 3;
        image += inside ? " 200" : " 0";
      }
  return image + " ] }";
}

Rendered drawVolume(const std::string& name, const std::string& node) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file,
            "#X3D V4.0 utf8\nPROFILE Immersive\nViewpoint { position 0 0 2.5 }\n" + node + "\n");
  return renderFile(file);
}

/// Pixels of the picture brighter than the black background.
int litPixels(const Rendered& r) {
  int n = 0;
  for (int y = 0; y < gs::test::kWorldSize; ++y)
    for (int x = 0; x < gs::test::kWorldSize; ++x) {
      const std::uint8_t* p = r.image.pixel(x, y);
      n += (p[0] + p[1] + p[2]) > 30;
    }
  return n;
}

bool anyError(const Rendered& r, const std::string& text) {
  for (const auto& d : r.diagnostics.items)
    if (d.message.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("VolumeData of a PixelTexture3D is drawn as splats of its gradient vectors",
          "[render][offscreen][world][volume]") {
  const Rendered r =
      drawVolume("vd_pixel", "VolumeData { dimensions 1 1 1 voxels " + cubeVoxels() + " }");
  CHECK(r.diagnostics.items.empty());
  CHECK(litPixels(r) > 100);
  const std::uint8_t* centre = r.image.pixel(32, 32);
  CHECK(centre[0] + centre[1] + centre[2] > 30);
  // Far from the volume's box (1 m wide, seen from 2.5 m over 45 degrees): background.
  const std::uint8_t* corner = r.image.pixel(2, 2);
  CHECK(corner[0] + corner[1] + corner[2] < 10);
}

TEST_CASE("VolumeData: an OpacityMapVolumeStyle PixelTexture colours the vectors",
          "[render][offscreen][world][volume]") {
  const Rendered r = drawVolume(
      "vd_style", "VolumeData { dimensions 1 1 1 voxels " + cubeVoxels() +
                      " renderStyle OpacityMapVolumeStyle { transferFunction PixelTexture { "
                      "image 1 1 4 0x00FF00FF } } }");
  CHECK(r.diagnostics.items.empty());
  const std::uint8_t* centre = r.image.pixel(32, 32);
  INFO(int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]));
  CHECK(centre[1] > 40);
  CHECK(centre[1] > 3 * centre[0]);
  CHECK(centre[1] > 3 * centre[2]);
}

TEST_CASE("IsoSurfaceVolumeData keeps the voxels near its surface values",
          "[render][offscreen][world][volume]") {
  const Rendered near = drawVolume("vd_iso",
                                   "IsoSurfaceVolumeData { surfaceValues [ 100 ] "
                                   "surfaceTolerance 100 voxels " +
                                       cubeVoxels() + " }");
  CHECK(near.diagnostics.items.empty());
  CHECK(litPixels(near) > 100);
  // No voxel within 1 of 500: nothing drawn, one error naming why.
  const Rendered none = drawVolume("vd_iso_none",
                                   "IsoSurfaceVolumeData { surfaceValues [ 500 ] "
                                   "surfaceTolerance 1 voxels " +
                                       cubeVoxels() + " }");
  CHECK(anyError(none, "within surfaceTolerance"));
  CHECK(litPixels(none) == 0);
}

TEST_CASE("VolumeData reads a NRRD ImageTexture3D, with attached or detached data",
          "[render][offscreen][world][volume]") {
  const std::string volumes = (gs::test::sourceDir() / "assets" / "volumes").string();
  for (const char* file : {"sphere.nrrd", "sphere_gzip.nrrd", "sphere_detached.nhdr"}) {
    INFO(file);
    const Rendered r =
        drawVolume(std::string("vd_") + file,
                   "VolumeData { voxels ImageTexture3D { url \"" + volumes + "/" + file + "\" } }");
    CHECK(r.diagnostics.items.empty());
    CHECK(litPixels(r) > 100);
  }
}

TEST_CASE("VolumeData of a ComposedTexture3D stacks its slices",
          "[render][offscreen][world][volume]") {
  // Bright voxels have a gradient only beside a dark slice: the stream's default transfer
  // function shows high values, not the dark voxels' zero.
  const std::string dark = "PixelTexture { image 2 2 1 0x00 0x00 0x00 0x00 }";
  const std::string bright = "PixelTexture { image 2 2 1 0xC8 0xC8 0xC8 0xC8 }";
  const Rendered r =
      drawVolume("vd_composed", "VolumeData { voxels ComposedTexture3D { texture [ " + dark + " " +
                                    bright + " " + bright + " " + dark + " ] } }");
  CHECK(r.diagnostics.items.empty());
  CHECK(litPixels(r) > 50);
}

TEST_CASE("bad volume data is one error and the rest of the world still draws",
          "[render][offscreen][world][volume]") {
  const std::string box =
      "Shape { appearance Appearance { material Material { emissiveColor 1 0 0 "
      "} } geometry Box { size 0.2 0.2 0.2 } }";
  // Pixel count that disagrees with the header.
  const Rendered shortImage = drawVolume(
      "vd_short", box + " VolumeData { voxels PixelTexture3D { image [ 1 2 2 2 0 0 ] } }");
  CHECK(anyError(shortImage, "PixelTexture3D has 2 pixels, expected 8"));
  const std::uint8_t* centre = shortImage.image.pixel(32, 32);
  CHECK(centre[0] > 200);  // the red box
  CHECK(anyError(drawVolume("vd_none", "VolumeData {}"), "has no voxels"));
  CHECK(anyError(
      drawVolume("vd_missing", "VolumeData { voxels ImageTexture3D { url \"missing.nrrd\" } }"),
      "ImageTexture3D"));
}
