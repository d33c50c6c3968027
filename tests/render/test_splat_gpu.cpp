// The OpenGL splat pass against the CPU reference of equation (1) (splat_reference.hpp):
// the same vectors, style, lights and camera must give the same picture, on both paths
// (SplatPath: point sprites, the geometry shader and the CPU rasterizer).
#include <catch2/catch.hpp>

#include <glad/gl.h>

#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_reference.hpp"
#include "render/splat_renderer.hpp"

using namespace gs;
using namespace gs::render;
using namespace gs::scene;

namespace {

constexpr int kSize = 128;
const glm::vec3 kBackground(0.1f, 0.2f, 0.3f);

std::uint32_t rgba(int r, int g, int b, int a = 255) {
  return static_cast<std::uint32_t>(r) | (static_cast<std::uint32_t>(g) << 8) |
         (static_cast<std::uint32_t>(b) << 16) | (static_cast<std::uint32_t>(a) << 24);
}

// A noisy sphere shell of surface splats, several layers deep where they overlap.
SplatSet shell(std::size_t n) {
  SplatSet set;
  std::mt19937 rng(11);
  std::normal_distribution<float> g(0.0f, 1.0f);
  std::uniform_int_distribution<int> c(40, 255);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    set.vectors.push_back({d, 0.02f + 0.01f * std::abs(g(rng)), d, rgba(c(rng), c(rng), c(rng))});
  }
  set.style.kind = qnv::StreamKind::surface;
  set.computeBounds();
  return set;
}

Camera camera() {
  Camera cam;
  cam.position = {0.3f, 0.5f, 3.0f};
  cam.orientation = glm::quatLookAt(glm::normalize(-cam.position), glm::vec3(0, 1, 0));
  cam.nearClip = 0.5f;
  cam.farClip = 10.0f;
  return cam;
}

Image drawGpu(const SplatSet& set, std::size_t count, std::span<const SplatLight> lights,
              SplatBlend blend, SplatPath path = SplatPath::geometry,
              const Camera& cam = camera()) {
  static auto context = createOffscreenContext(kSize, kSize);
  static SplatRenderer renderer;
  renderer.setPath(path);
  glViewport(0, 0, kSize, kSize);
  glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, count, glm::mat4(1.0f), cam, 1.0f, lights, blend);
  // `points` and `geometry` name the one GL path (instanced quads), reported as geometry.
  CHECK(renderer.statistics().path == (path == SplatPath::points ? SplatPath::geometry : path));
  return readPixels(0, 0, kSize, kSize);
}

}  // namespace

TEST_CASE("the splat pass matches the CPU reference of equation (1)", "[splat][gpu]") {
  const SplatPath path = GENERATE(SplatPath::geometry, SplatPath::gpu, SplatPath::cpu);
  INFO("path " << splatPathName(path));
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f)), glm::vec3(0.8f)}};
  const Image reference =
      renderSplatsReference(set.vectors, set.style, lights, camera(), kSize, kSize, kBackground);
  const Image gpu = drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, path);
  const ImageDifference d = compareImages(gpu, reference, 8);
  INFO("differing " << d.fractionDiffering << ", mean " << d.meanAbsolute);
  CHECK(d.fractionDiffering <= 0.01);
  // The picture is not just background.
  CHECK(compareImages(gpu, Image(kSize, kSize, 26, 51, 77), 16).fractionDiffering > 0.2);

  {
    // Float compositing as the reference does (the GL paths in their half-float layer,
    // render/src/splat_layer_gl.hpp): only the final 8-bit rounding of colour and coverage
    // differs. (When the GL paths blended in the 8-bit framebuffer, rounding at every
    // splat, they needed the tolerance of 8 above.)
    const ImageDifference c = compareImages(gpu, reference, 2);
    INFO("at 2 levels: differing " << c.fractionDiffering << ", mean " << c.meanAbsolute);
    CHECK(c.fractionDiffering <= 0.001);
  }
  const Image frontToBack = drawGpu(set, set.vectors.size(), lights, SplatBlend::frontToBack, path);
  const ImageDifference f = compareImages(frontToBack, reference, 8);
  INFO("front to back: differing " << f.fractionDiffering);
  CHECK(f.fractionDiffering <= 0.01);
}

TEST_CASE("the level of detail draws a prefix of the stream", "[splat][gpu]") {
  const SplatPath path = GENERATE(SplatPath::geometry, SplatPath::gpu, SplatPath::cpu);
  INFO("path " << splatPathName(path));
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  const Image some = drawGpu(set, 300, lights, SplatBlend::backToFront, path);
  const Image reference = renderSplatsReference(set.vectors, set.style, lights, camera(), kSize,
                                                kSize, kBackground, 300);
  CHECK(compareImages(some, reference, 8).fractionDiffering <= 0.01);
  const Image all = drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, path);
  CHECK(compareImages(some, all, 16).fractionDiffering > 0.05);
}

TEST_CASE("a wrong depth order would fail the comparison", "[splat][gpu]") {
  // Two opaque-ish splats, red in front of blue: compositing in the wrong order shows blue.
  SplatSet set;
  set.vectors.push_back({{0, 0, 0.5f}, 0.5f, {0, 0, 1}, rgba(255, 0, 0)});
  set.vectors.push_back({{0.05f, 0, -0.5f}, 0.5f, {0, 0, 1}, rgba(0, 0, 255)});
  set.style.kind = qnv::StreamKind::surface;
  set.style.opacityScale = 2.0f;
  set.computeBounds();
  const SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  const SplatPath path = GENERATE(SplatPath::geometry, SplatPath::gpu, SplatPath::cpu);
  INFO("path " << splatPathName(path));
  const Image gpu = drawGpu(set, 2, lights, SplatBlend::backToFront, path);
  const Image right =
      renderSplatsReference(set.vectors, set.style, lights, camera(), kSize, kSize, kBackground);
  const std::uint32_t wrongOrder[] = {1, 0};  // blue composited as if it were nearest
  const Image wrong =
      splatColorsToImage(compositeSplats(set.vectors, wrongOrder, SplatCompositing::frontToBack,
                                         set.style, lights, camera(), kSize, kSize, kBackground),
                         kSize, kSize);
  CHECK(compareImages(gpu, right, 8).fractionDiffering <= 0.01);
  CHECK(compareImages(gpu, wrong, 8).fractionDiffering > 0.02);
}

TEST_CASE("the cpu and GL paths draw oblique splats across the viewport's edges as the reference",
          "[splat][gpu]") {
  // Large oblique flat discs, some across the viewport's edges: both paths project them as
  // the reference does (EWA, 3-sigma box) and cut them at the viewport.
  SplatSet set;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 60; ++i) {
    const glm::vec3 p(1.4f * u(rng), 1.4f * u(rng), 1.2f * u(rng));
    const glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), 0.3f * u(rng)) + 1e-3f);
    set.vectors.push_back({p, 0.02f + 0.05f * std::abs(u(rng)), n, rgba(200, 120 + i, 60)});
  }
  set.style.kind = qnv::StreamKind::surface;
  set.computeBounds();
  const SplatLight lights[] = {{glm::normalize(glm::vec3(0.4f, -0.3f, -1.0f)), glm::vec3(1.0f)}};
  const Image reference =
      renderSplatsReference(set.vectors, set.style, lights, camera(), kSize, kSize, kBackground);
  const Image geometry =
      drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, SplatPath::geometry);
  const Image points =
      drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, SplatPath::points);
  const Image cpu =
      drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, SplatPath::cpu);
  CHECK(compareImages(geometry, reference, 8).fractionDiffering <= 0.01);
  CHECK(points.rgba == geometry.rgba);
  CHECK(compareImages(cpu, reference, 2).fractionDiffering <= 0.005);
  CHECK(compareImages(cpu, geometry, 8).fractionDiffering <= 0.01);
  CHECK(compareImages(geometry, Image(kSize, kSize, 26, 51, 77), 16).fractionDiffering > 0.1);
}

TEST_CASE("splats whose centres are nearer than the near plane are not drawn, on every path",
          "[splat][gpu]") {
  const SplatSet set = shell(500);
  Camera cam = camera();
  cam.position = glm::normalize(cam.position) * 1.02f;  // the nearest splats cross near
  cam.nearClip = 0.05f;
  const SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  const Image reference =
      renderSplatsReference(set.vectors, set.style, lights, cam, kSize, kSize, kBackground);
  for (const SplatPath path : {SplatPath::geometry, SplatPath::cpu}) {
    INFO("path " << splatPathName(path));
    const Image image =
        drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront, path, cam);
    const ImageDifference d = compareImages(image, reference, 8);
    INFO("differing " << d.fractionDiffering);
    CHECK(d.fractionDiffering <= 0.01);
  }
  SplatPath parsed = SplatPath::points;
  CHECK(parseSplatPath("geometry", parsed));
  CHECK(parsed == SplatPath::geometry);
  CHECK_FALSE(parseSplatPath("sprites", parsed));
}

TEST_CASE("the cpu path hides splats behind the scene's depth as the GL paths do", "[splat][gpu]") {
  // A wall in the depth buffer, in front of the shell's centre, over the pixels left (or
  // right) of it: only the shell's near cap shows there. The GL path blends in
  // its float layer, the scene's depth copied in (render/src/splat_layer_gl.hpp): within
  // 2 levels of the cpu path's float compositing. The whole shell in view reads the whole
  // view's depth; a small one up in a corner reaches a few tiles, and the cpu path reads
  // the depth under those alone (SceneDepthReader), which must be read at their place.
  const bool corner = GENERATE(false, true);
  INFO((corner ? "a small shell in a corner" : "the whole shell"));
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f)), glm::vec3(0.8f)}};
  drawGpu(set, 1, lights, SplatBlend::backToFront);  // makes the test context current
  const Camera cam = camera();
  const glm::mat4 projection = projectionMatrix(cam, 1.0f);
  const glm::mat4 model =
      corner ? glm::scale(glm::translate(glm::mat4(1.0f), cam.orientation * glm::vec3(0.7f)),
                          glm::vec3(0.3f))
             : glm::mat4(1.0f);
  const glm::vec4 eyeCentre = viewMatrix(cam) * model * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const glm::vec4 clipCentre = projection * eyeCentre;
  const int centreX =
      static_cast<int>((0.5f * clipCentre.x / clipCentre.w + 0.5f) * static_cast<float>(kSize));
  // Between the shell's centre and its nearest point (radius 1, or 0.3 scaled; the whole
  // shell's centre is about 3.06 away).
  const float wallEye = corner ? eyeCentre.z + 0.15f : -2.6f;
  const glm::vec4 wall = projection * glm::vec4(0.0f, 0.0f, wallEye, 1.0f);
  const double wallDepth = 0.5 * (wall.z / wall.w) + 0.5;
  const auto draw = [&](SplatPath path) {
    SplatRenderer renderer;
    renderer.setPath(path);
    glViewport(0, 0, kSize, kSize);
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    if (corner)
      glScissor(centreX, 0, kSize - centreX, kSize);
    else
      glScissor(0, 0, kSize / 2, kSize);
    glClearDepth(wallDepth);
    glClear(GL_DEPTH_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    glClearDepth(1.0);
    renderer.draw(set, set.vectors.size(), model, cam, 1.0f, lights);
    CHECK(renderer.statistics().path == path);
    Image image = readPixels(0, 0, kSize, kSize);
    renderer.release();
    return image;
  };
  const Image geometry = draw(SplatPath::geometry);
  const Image cpu = draw(SplatPath::cpu);
  const ImageDifference d = compareImages(cpu, geometry, 2);
  INFO("differing " << d.fractionDiffering << ", mean " << d.meanAbsolute);
  CHECK(d.fractionDiffering <= 0.001);
  // The wall hides something: the picture differs from the unhidden one.
  SplatRenderer renderer;
  renderer.setPath(SplatPath::geometry);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, set.vectors.size(), model, cam, 1.0f, lights);
  const Image open = readPixels(0, 0, kSize, kSize);
  renderer.release();
  const ImageDifference hidden = compareImages(cpu, open, 8);
  INFO("hidden " << hidden.fractionDiffering);
  CHECK(hidden.fractionDiffering > (corner ? 0.003 : 0.008));  // measured 0.5%, 1.1%
}

TEST_CASE("splat path names and the automatic choice", "[splat]") {
  for (const SplatPath p : {SplatPath::points, SplatPath::geometry, SplatPath::gpu, SplatPath::cpu,
                            SplatPath::automatic}) {
    SplatPath parsed = SplatPath::points;
    CHECK(parseSplatPath(splatPathName(p), parsed));
    CHECK(parsed == p);
  }
  CHECK(automaticSplatPath("llvmpipe (LLVM 15.0.6, 256 bits)") == SplatPath::cpu);
  CHECK(automaticSplatPath("softpipe") == SplatPath::cpu);
  CHECK(automaticSplatPath("NVIDIA GeForce RTX 3080/PCIe/SSE2") == SplatPath::gpu);
  CHECK(automaticSplatPath(nullptr) == SplatPath::gpu);
}

TEST_CASE("a growing set on the GL path uploads its tail and draws what a fresh upload draws",
          "[splat][gpu]") {
  // A progressive stream appends vectors to the same storage (SplatSet): the GL pass sends
  // only the new ones, texels and colours. The picture must equal a fresh renderer's.
  const SplatSet whole = shell(3000);
  SplatSet growing;
  growing.style = whole.style;
  growing.vectors.reserve(whole.vectors.size());  // the same address while it grows
  const SplatLight lights[] = {{glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f)), glm::vec3(0.8f)}};
  drawGpu(whole, 1, lights, SplatBlend::backToFront);  // makes the test context current
  SplatRenderer renderer;
  renderer.setPath(SplatPath::geometry);
  const auto draw = [&](SplatRenderer& r, const SplatSet& set) {
    glViewport(0, 0, kSize, kSize);
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    r.draw(set, set.vectors.size(), glm::mat4(1.0f), camera(), 1.0f, lights);
    return readPixels(0, 0, kSize, kSize);
  };
  // 1,000 then 500 at a time: the buffers double when full, so the steps to 2,000 and
  // 3,000 go through the tail upload and the others through a new store.
  for (std::size_t size = 1000; size <= 3000; size += 500) {
    while (growing.vectors.size() < size)
      growing.vectors.push_back(whole.vectors[growing.vectors.size()]);
    growing.computeBounds();
    const Image grown = draw(renderer, growing);
    SplatRenderer fresh;
    fresh.setPath(SplatPath::geometry);
    const Image once = draw(fresh, growing);
    fresh.release();
    INFO("vectors " << growing.vectors.size());
    CHECK(grown.rgba == once.rgba);
  }
  renderer.release();
}

TEST_CASE("viewports of two sizes draw the cpu path's splats on the GL paths",
          "[splat][gpu][viewport]") {
  // One renderer draws the shell in a small viewport and then in a larger one beside it,
  // each under its scissor box, as the window's side-by-side viewports do: the GL paths'
  // float layer (render/src/splat_layer_gl.hpp) grows for the second and composites each
  // viewport's corner of it at that viewport's place.
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f)), glm::vec3(0.8f)}};
  drawGpu(set, 1, lights, SplatBlend::backToFront);  // makes the test context current
  const GLint viewports[2][4] = {{4, 40, 48, 48}, {56, 8, 70, 110}};
  const auto draw = [&](SplatPath path) {
    SplatRenderer renderer;
    renderer.setPath(path);
    glViewport(0, 0, kSize, kSize);
    glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    for (const auto& v : viewports) {
      glViewport(v[0], v[1], v[2], v[3]);
      glScissor(v[0], v[1], v[2], v[3]);
      renderer.draw(set, set.vectors.size(), glm::mat4(1.0f), camera(),
                    static_cast<float>(v[2]) / static_cast<float>(v[3]), lights);
      CHECK(renderer.statistics().path == path);
    }
    glDisable(GL_SCISSOR_TEST);
    glViewport(0, 0, kSize, kSize);
    Image image = readPixels(0, 0, kSize, kSize);
    renderer.release();
    return image;
  };
  const Image cpu = draw(SplatPath::cpu);
  // Both viewports show the shell; nothing is drawn outside them.
  const auto at = [&](int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * kSize + static_cast<std::size_t>(x)) * 4;
    return glm::ivec3(cpu.rgba[i], cpu.rgba[i + 1], cpu.rgba[i + 2]);
  };
  CHECK(at(28, 64) != at(1, 1));
  CHECK(at(91, 63) != at(1, 1));
  CHECK(at(28, 10) == at(1, 1));
  for (const SplatPath path : {SplatPath::geometry, SplatPath::gpu}) {
    const ImageDifference d = compareImages(draw(path), cpu, 2);
    INFO(splatPathName(path) << " against cpu: differing " << d.fractionDiffering << ", mean "
                             << d.meanAbsolute);
    CHECK(d.fractionDiffering <= 0.001);
  }
}
