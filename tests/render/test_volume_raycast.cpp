// X3D volume render styles drawn by the ray caster (render/src/volume_raycast.hpp): X_ITE 15's
// style code per sample at its slices, composited front to back; drawn off-screen at 64x64.
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

/// An n x n x n PixelTexture3D of one grey `value` (0..255).
std::string constantVoxels(int n, int value) {
  std::string image = "PixelTexture3D { image [ 1 " + std::to_string(n) + " " + std::to_string(n) +
                      " " + std::to_string(n);
  for (int i = 0; i < n * n * n; ++i) image += " " + std::to_string(value);
  return image + " ] }";
}

Rendered drawStyled(const std::string& name, const std::string& node) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, "#X3D V4.0 utf8\nPROFILE Full\nViewpoint { position 0 0 2.5 }\n" + node + "\n");
  return renderFile(file);
}

std::string ball() {
  return "ImageTexture3D { url \"" +
         (gs::test::sourceDir() / "assets" / "volumes" / "ball32.nrrd").string() + "\" }";
}

}  // namespace

TEST_CASE("Volume ray caster: ProjectionVolumeStyle MAX of a constant volume is its value",
          "[render][offscreen][world][volume]") {
  // 128 everywhere: the maximum along any ray is 128 / 255, and the default opacity map's
  // alpha (128 / 255 per sample, hundreds of samples) makes the box opaque.
  const Rendered r =
      drawStyled("vr_projection", "VolumeData { dimensions 1 1 1 voxels " + constantVoxels(4, 128) +
                                      " renderStyle ProjectionVolumeStyle { type \"MAX\" } }");
  CHECK(r.diagnostics.items.empty());
  const std::uint8_t* centre = r.image.pixel(32, 32);
  INFO(int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]));
  CHECK(int(centre[0]) == Approx(128).margin(3));
  CHECK(int(centre[1]) == Approx(128).margin(3));
  // Outside the box: the black background.
  const std::uint8_t* corner = r.image.pixel(2, 2);
  CHECK(corner[0] + corner[1] + corner[2] == 0);
}

TEST_CASE("Volume ray caster: ToneMapped and Edge styles colour by the gradient and the view",
          "[render][offscreen][world][volume]") {
  // ToneMapped with a blue cool colour and a yellow warm colour under the headlight alone:
  // gradients facing the viewer (L.n = -1 or 1 at the ball's front) are coloured, and the
  // ball's edge, turned 90 degrees from the light, is their mix.
  const Rendered tone = drawStyled(
      "vr_tone",
      "VolumeData { dimensions 1.6 1.6 1.6 voxels " + ball() +
          " renderStyle ToneMappedVolumeStyle { coolColor 0 0 1 0 warmColor 1 1 0 0 } }");
  CHECK(tone.diagnostics.items.empty());
  const std::uint8_t* centre = tone.image.pixel(32, 32);
  INFO(int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]));
  CHECK(centre[2] > 60);
  CHECK(centre[2] > centre[0] + 30);
  // EdgeEnhancement in red: the silhouette of the shell (gradients across the view) is red,
  // the ball's middle (gradients along it) keeps its grey.
  const Rendered edge =
      drawStyled("vr_edge", "VolumeData { dimensions 1.6 1.6 1.6 voxels " + ball() +
                                " renderStyle EdgeEnhancementVolumeStyle { edgeColor 1 0 0 1 } }");
  CHECK(edge.diagnostics.items.empty());
  int red = 0;
  for (int y = 0; y < gs::test::kWorldSize; ++y)
    for (int x = 0; x < gs::test::kWorldSize; ++x) {
      const std::uint8_t* p = edge.image.pixel(x, y);
      red += p[0] > 60 && p[0] > 2 * p[1] + 10;
    }
  CHECK(red > 100);
  const std::uint8_t* middle = edge.image.pixel(32, 32);
  CHECK(std::abs(int(middle[0]) - int(middle[1])) < 20);
}

TEST_CASE("Volume ray caster: disabled styles are the default map, drawn as splats",
          "[render][offscreen][world][volume]") {
  // A disabled style leaves the volume to the paper's splats (no ray caster), with no error.
  const Rendered r =
      drawStyled("vr_disabled", "VolumeData { dimensions 1.6 1.6 1.6 voxels " + ball() +
                                    " renderStyle CartoonVolumeStyle { enabled FALSE } }");
  CHECK(r.diagnostics.items.empty());
  const std::uint8_t* centre = r.image.pixel(32, 32);
  CHECK(centre[0] + centre[1] + centre[2] > 30);
}

TEST_CASE("Volume ray caster: an IsoSurfaceVolumeData with a style draws its surface",
          "[render][offscreen][world][volume]") {
  // X_ITE discards the samples away from the surface, one slice at a time; in the march they
  // are transparent (a discard there would end the whole ray and draw nothing).
  const Rendered r = drawStyled(
      "vr_iso",
      "IsoSurfaceVolumeData { dimensions 1.6 1.6 1.6 surfaceValues [ 0.5 ] "
      "surfaceTolerance 0.1 voxels " +
          ball() + " renderStyle [ EdgeEnhancementVolumeStyle { edgeColor 1 0 0 1 } ] }");
  CHECK(r.diagnostics.items.empty());
  int lit = 0;
  for (int y = 0; y < gs::test::kWorldSize; ++y)
    for (int x = 0; x < gs::test::kWorldSize; ++x) {
      const std::uint8_t* p = r.image.pixel(x, y);
      lit += p[0] + p[1] + p[2] > 30;
    }
  CHECK(lit > 200);
}

TEST_CASE("Volume ray caster: ClipPlanes cut the samples and fog colours them",
          "[render][offscreen][world][volume]") {
  // The constant MAX projection (grey 128) under a ClipPlane keeping x >= 0: the left half
  // is the black background, the right half grey.
  const std::string volume = "VolumeData { dimensions 1 1 1 voxels " + constantVoxels(4, 128) +
                             " renderStyle ProjectionVolumeStyle { type \"MAX\" } }";
  const Rendered clipped =
      drawStyled("vr_clipped", "Group { children [ ClipPlane { plane 1 0 0 0 } " + volume + " ] }");
  CHECK(clipped.diagnostics.items.empty());
  const std::uint8_t* left = clipped.image.pixel(24, 32);
  const std::uint8_t* right = clipped.image.pixel(40, 32);
  CHECK(left[0] + left[1] + left[2] == 0);
  CHECK(int(right[0]) == Approx(128).margin(3));
  // A red linear fog whose range is 4 m, the box 2-3 m away: about 40% of the colour
  // is left, the rest is the fog's red.
  const Rendered fogged =
      drawStyled("vr_fogged", "Fog { color 1 0 0 visibilityRange 4 } " + volume);
  CHECK(fogged.diagnostics.items.empty());
  const std::uint8_t* centre = fogged.image.pixel(32, 32);
  INFO(int(centre[0]) << " " << int(centre[1]) << " " << int(centre[2]));
  CHECK(centre[0] > 180);
  CHECK(centre[1] > 30);
  CHECK(centre[1] < 90);
}

TEST_CASE("Volume ray caster: an opaque shape inside the box ends the rays",
          "[render][offscreen][world][volume]") {
  // A faint volume (3 / 255 of opacity per sample, drawn by the ray caster) around a red box
  // whose front face is at z = 0.15. The box's red shows through the samples in front of it
  // only: the same red as with a ClipPlane that removes every sample behind that face, and
  // far more than the whole depth of the volume leaves (measured: 118 of 255, against 36
  // when the rays ran through the box).
  const std::string volume = "VolumeData { dimensions 1 1 1 voxels " + constantVoxels(4, 3) +
                             " renderStyle ProjectionVolumeStyle { type \"MAX\" } }";
  const std::string box =
      "Shape { appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 0 "
      "0 } } geometry Box { size 0.3 0.3 0.3 } }";
  const Rendered inside = drawStyled("vr_inside", box + " " + volume);
  const Rendered front = drawStyled(
      "vr_front", box + " Group { children [ ClipPlane { plane 0 0 1 -0.15 } " + volume + " ] }");
  CHECK(inside.diagnostics.items.empty());
  const std::uint8_t* a = inside.image.pixel(32, 32);
  const std::uint8_t* b = front.image.pixel(32, 32);
  INFO(int(a[0]) << " " << int(a[1]) << " " << int(b[0]) << " " << int(b[1]));
  CHECK(int(a[0]) > 70);
  CHECK(int(a[0]) == Approx(int(b[0])).margin(3));
  CHECK(int(a[1]) == Approx(int(b[1])).margin(3));
}
