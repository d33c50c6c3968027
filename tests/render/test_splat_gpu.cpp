// The OpenGL splat pass against the CPU reference of equation (1) (splat_reference.hpp):
// the same vectors, style, lights and camera must give the same picture.
#include <catch2/catch.hpp>

#include <glad/gl.h>

#include <random>

#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_reference.hpp"
#include "render/splat_renderer.hpp"

using namespace gs;
using namespace gs::render;

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
              SplatBlend blend) {
  static auto context = createOffscreenContext(kSize, kSize);
  static SplatRenderer renderer;
  glViewport(0, 0, kSize, kSize);
  glClearColor(kBackground.r, kBackground.g, kBackground.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, count, glm::mat4(1.0f), camera(), 1.0f, lights, blend);
  return readPixels(0, 0, kSize, kSize);
}

}  // namespace

TEST_CASE("the OpenGL splat pass matches the CPU reference of equation (1)", "[splat][gpu]") {
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f)), glm::vec3(0.8f)}};
  const Image reference =
      renderSplatsReference(set.vectors, set.style, lights, camera(), kSize, kSize, kBackground);
  const Image gpu = drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront);
  const ImageDifference d = compareImages(gpu, reference, 8);
  INFO("differing " << d.fractionDiffering << ", mean " << d.meanAbsolute);
  CHECK(d.fractionDiffering <= 0.01);
  // The picture is not just background.
  CHECK(compareImages(gpu, Image(kSize, kSize, 26, 51, 77), 16).fractionDiffering > 0.2);

  const Image frontToBack = drawGpu(set, set.vectors.size(), lights, SplatBlend::frontToBack);
  const ImageDifference f = compareImages(frontToBack, reference, 8);
  INFO("front to back: differing " << f.fractionDiffering);
  CHECK(f.fractionDiffering <= 0.01);
}

TEST_CASE("the level of detail draws a prefix of the stream", "[splat][gpu]") {
  const SplatSet set = shell(3000);
  const SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  const Image some = drawGpu(set, 300, lights, SplatBlend::backToFront);
  const Image reference = renderSplatsReference(set.vectors, set.style, lights, camera(), kSize,
                                                kSize, kBackground, 300);
  CHECK(compareImages(some, reference, 8).fractionDiffering <= 0.01);
  const Image all = drawGpu(set, set.vectors.size(), lights, SplatBlend::backToFront);
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
  const Image gpu = drawGpu(set, 2, lights, SplatBlend::backToFront);
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
