// ClipPlanes and fog on splats (render::SplatRenderer::setClipPlanes, setFog): a splat
// whose centre a ClipPlane in scope removes is not drawn, and a splat's colour is fogged by
// its centre's distance, on the cpu path and the geometry path, for Gaussian splats and
// for the paper's QNV vectors of a volume.
#include "test_support.hpp"
#include "world_files.hpp"

#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/scene_renderer.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace {

/// `body` (an X3D 4 world in the Classic encoding, its Viewpoint at 0 0 6) drawn at 64x64
/// on splat path `path`.
gs::render::Image drawClipWorld(const std::string& name, const std::string& body,
                                gs::render::SplatPath path) {
  static auto context = gs::render::createOffscreenContext(64, 64);
  context->makeCurrent();
  const std::filesystem::path file = gs::test::worldDir() / (name + ".x3dv");
  gs::test::writeText(file, "#X3D V4.0 utf8\nPROFILE Full\nViewpoint { position 0 0 6 }\n" + body);
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile(file.string()));
  for (const auto& d : scene->diagnostics.items) WARN(d.format());
  gs::render::SceneRendererOptions options;
  options.splatPath = path;
  gs::render::SceneRenderer r(scene, options);
  r.draw(r.initialCamera(1.0f), 0, 0, 64, 64);
  return gs::render::readPixels(0, 0, 64, 64);
}

int brightness(const gs::render::Image& image, int x, int y) {
  const std::uint8_t* p = image.pixel(x, y);
  return p[0] + p[1] + p[2];
}

}  // namespace

TEST_CASE("ClipPlanes remove the splats whose centres they cut", "[render][offscreen][splat]") {
  // Two white Gaussians at x = -1 and x = +1; a ClipPlane keeping x >= 0 leaves the right.
  const std::string splats =
      "GaussianSplats { positions [ -1 0 0, 1 0 0 ] orientations [ 0 0 0 1, 0 0 0 1 ]"
      " scales [ 0.3 0.3 0.3, 0.3 0.3 0.3 ] opacities [ 1 1 ]"
      " sphericalHarmonicsDegree0Coef0 [ 1.77 1.77 1.77, 1.77 1.77 1.77 ] }";
  for (const gs::render::SplatPath path :
       {gs::render::SplatPath::cpu, gs::render::SplatPath::geometry}) {
    INFO(gs::render::splatPathName(path));
    const gs::render::Image whole = drawClipWorld("clip_none", splats + "\n", path);
    const gs::render::Image clipped = drawClipWorld(
        "clip_half", "Group { children [ ClipPlane { plane 1 0 0 0 } " + splats + " ] }\n", path);
    // The splats' centres are 1 m either side of the axis, 6 m away: pixels 32 -+ 11.
    CHECK(brightness(whole, 21, 32) > 300);
    CHECK(brightness(whole, 43, 32) > 300);
    CHECK(brightness(clipped, 21, 32) == 0);
    CHECK(brightness(clipped, 43, 32) > 300);
  }
  // A volume's QNV vectors: the ball's left half is gone, but for the footprints of the
  // splats whose centres lie just right of the plane (a few pixels wide).
  const std::string ball = "VolumeData { dimensions 3 3 3 voxels ImageTexture3D { url \"" +
                           (gs::test::sourceDir() / "assets/volumes/ball32.nrrd").string() +
                           "\" } }";
  const gs::render::Image ballWhole =
      drawClipWorld("clip_ball", ball + "\n", gs::render::SplatPath::cpu);
  const gs::render::Image ballClipped = drawClipWorld(
      "clip_ball_half", "Group { children [ ClipPlane { plane 1 0 0 0 } " + ball + " ] }\n",
      gs::render::SplatPath::cpu);
  int leftWhole = 0, leftClipped = 0, rightWhole = 0, rightClipped = 0;
  for (int y = 16; y < 48; ++y)
    for (int x = 16; x < 28; ++x) {
      leftWhole += brightness(ballWhole, x, y);
      leftClipped += brightness(ballClipped, x, y);
      rightWhole += brightness(ballWhole, 63 - x, y);
      rightClipped += brightness(ballClipped, 63 - x, y);
    }
  INFO(leftWhole << " " << leftClipped << " " << rightWhole << " " << rightClipped);
  CHECK(leftWhole > 1000);
  CHECK(leftClipped * 50 < leftWhole);
  CHECK(rightClipped > rightWhole / 2);
}

TEST_CASE("Fog colours splats by their centres' distance", "[render][offscreen][splat]") {
  // A red LINEAR fog whose range is 12 m and splats about 6.1 m away: half the colour is
  // left (f = (12 - 6.08) / 12 = 0.49), the rest is the fog's red.
  const std::string splats =
      "GaussianSplats { positions [ -1 0 0, 1 0 0 ] orientations [ 0 0 0 1, 0 0 0 1 ]"
      " scales [ 0.3 0.3 0.3, 0.3 0.3 0.3 ] opacities [ 1 1 ]"
      " sphericalHarmonicsDegree0Coef0 [ 1.77 1.77 1.77, 1.77 1.77 1.77 ] }\n";
  const std::string fog = "Fog { color 1 0 0 visibilityRange 12 }\n";
  for (const gs::render::SplatPath path :
       {gs::render::SplatPath::cpu, gs::render::SplatPath::geometry}) {
    INFO(gs::render::splatPathName(path));
    const gs::render::Image clear = drawClipWorld("fog_none", splats, path);
    const gs::render::Image fogged = drawClipWorld("fog_red", fog + splats, path);
    const std::uint8_t* a = clear.pixel(43, 32);
    const std::uint8_t* b = fogged.pixel(43, 32);
    INFO(int(a[0]) << " " << int(a[1]) << " " << int(b[0]) << " " << int(b[1]));
    CHECK(int(b[0]) >= int(a[0]) - 2);
    CHECK(double(b[1]) / double(a[1]) == Approx(0.49).margin(0.05));
    CHECK(double(b[2]) / double(a[2]) == Approx(0.49).margin(0.05));
  }
  // A volume's QNV vectors on the cpu path: the fogged ball is redder.
  const std::string ball = "VolumeData { dimensions 3 3 3 voxels ImageTexture3D { url \"" +
                           (gs::test::sourceDir() / "assets/volumes/ball32.nrrd").string() +
                           "\" } }\n";
  const gs::render::Image ballClear = drawClipWorld("fog_ball", ball, gs::render::SplatPath::cpu);
  const gs::render::Image ballFogged =
      drawClipWorld("fog_ball_red", fog + ball, gs::render::SplatPath::cpu);
  const std::uint8_t* c = ballClear.pixel(32, 32);
  const std::uint8_t* d = ballFogged.pixel(32, 32);
  INFO(int(c[0]) << " " << int(c[1]) << " " << int(d[0]) << " " << int(d[1]));
  CHECK(int(d[0]) - int(d[1]) > int(c[0]) - int(c[1]) + 20);
}
