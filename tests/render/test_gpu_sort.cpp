// The GPU radix sort of the GL splat path (render/src/gpu_sort.hpp) against the CPU's
// DepthSorter, on llvmpipe's compute shaders (OpenGL 4.5 core): the reverse of the CPU's
// front-to-back order (farthest first; equal depths in descending index order, so that they
// are composited in the order the cpu path and the geometry path composite them; NaN
// farthest); and the GL path drawn with it gives the same pixels as with the CPU's order,
// splats of equal depth included.
#include <catch2/catch.hpp>

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "../../render/src/gpu_sort.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_renderer.hpp"
#include "test_support.hpp"

// Inside gs::render (the suite is a unity build: no using-directives at file scope).
namespace gs::render {

namespace {

/// A texture buffer of 3 RGBA32F texels per splat holding `positions` (GaussianGlPass's
/// layout), sorted by the GPU; returns the order read back.
std::vector<std::uint32_t> gpuOrder(const std::vector<glm::vec3>& positions, const glm::mat4& view,
                                    std::size_t count) {
  std::vector<float> texels(positions.size() * 12, 0.0f);
  for (std::size_t i = 0; i < positions.size(); ++i)
    for (int k = 0; k < 3; ++k) texels[i * 12 + static_cast<std::size_t>(k)] = positions[i][k];
  GLuint buffer = 0, texture = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  glBufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(texels.size() * sizeof(float)),
               texels.data(), GL_STATIC_DRAW);
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, buffer);
  detail::GpuDepthSort sort;
  sort.sort(texture, count, view);
  std::vector<std::uint32_t> order(count);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, sort.order());
  glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                     static_cast<GLsizeiptr>(count * sizeof(std::uint32_t)), order.data());
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  sort.release();
  glDeleteTextures(1, &texture);
  glDeleteBuffers(1, &buffer);
  return order;
}

glm::mat4 tiltedView() {
  scene::Camera c;
  c.position = {3.0f, -2.0f, 12.0f};
  c.orientation = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  return scene::viewMatrix(c);
}

}  // namespace

TEST_CASE("the GPU radix sort gives the reverse of the CPU's front-to-back order", "[splat][gpu]") {
  auto context = createOffscreenContext(16, 16);
  if (!detail::GpuDepthSort::available()) {
    test::missingFixture("an OpenGL 4.3 context (compute shaders) for the GPU sort");
    return;
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  // More than one block (4,096) and a partial last one; a few exact ties and a NaN.
  std::vector<glm::vec3> positions(10000);
  for (auto& p : positions) p = {u(rng), u(rng), u(rng)};
  for (int i = 0; i < 50; ++i) positions[static_cast<std::size_t>(100 + i)] = positions[99];
  positions[5000] = glm::vec3(NAN);
  const glm::mat4 view = tiltedView();
  for (const std::size_t count : {positions.size(), std::size_t{4096}, std::size_t{1}}) {
    INFO("count " << count);
    // The CPU's front to back (DepthSorter's keys: descending eye z, NaN last, stable),
    // reversed: what the geometry path draws.
    std::vector<std::uint32_t> expected(count);
    std::iota(expected.begin(), expected.end(), 0u);
    const auto eyeZ = [&](std::uint32_t i) { return (view * glm::vec4(positions[i], 1.0f)).z; };
    std::stable_sort(expected.begin(), expected.end(), [&](std::uint32_t a, std::uint32_t b) {
      const float za = eyeZ(a), zb = eyeZ(b);
      if (std::isnan(za) || std::isnan(zb)) return std::isnan(zb) && !std::isnan(za);
      return za > zb;
    });
    std::reverse(expected.begin(), expected.end());
    const std::vector<std::uint32_t> order = gpuOrder(positions, view, count);
    REQUIRE(order.size() == count);
    // A permutation, ascending in eye z (NaN first), equal depths in descending index order.
    std::vector<bool> seen(count, false);
    float last = -INFINITY;
    bool ascending = true, permutation = true, stable = true;
    for (std::size_t k = 0; k < count; ++k) {
      const std::uint32_t i = order[k];
      if (i >= count || seen[i]) {
        permutation = false;
        break;
      }
      seen[i] = true;
      const float z = (view * glm::vec4(positions[i], 1.0f)).z;
      if (std::isnan(z)) {
        ascending = ascending && k == 0;
        continue;
      }
      // The GPU computes z in its own float arithmetic (fused multiply-adds): neighbours a
      // rounding apart may swap, nothing more.
      if (z < last - 1e-5f * std::abs(last)) ascending = false;
      if (k > 0 && z == last && order[k - 1] < i && positions[order[k - 1]] == positions[i])
        stable = false;
      last = std::max(last, z);
    }
    CHECK(permutation);
    CHECK(ascending);
    CHECK(stable);
    // The CPU's order, but for neighbours whose depths are a rounding apart (measured: 5 of
    // 10,000 places).
    std::size_t same = 0;
    for (std::size_t k = 0; k < count; ++k) same += order[k] == expected[k] ? 1 : 0;
    CHECK(same * 1000 >= count * 995);
  }
}

namespace {

/// `set` drawn by `path` at kSize x kSize over a blue-grey background, seen from `camera`.
Image drawSplats(const SplatSet& set, const scene::Camera& camera, SplatPath path, int size) {
  const SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  SplatRenderer renderer;
  renderer.setPath(path);
  glViewport(0, 0, size, size);
  glClearColor(0.1f, 0.2f, 0.3f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, set.vectors.size(), glm::mat4(1.0f), camera, 1.0f, lights);
  CHECK(renderer.statistics().path == path);
  Image image = readPixels(0, 0, size, size);
  renderer.release();
  return image;
}

}  // namespace

TEST_CASE("the GL path sorted on the GPU draws the pixels of the CPU-sorted one", "[splat][gpu]") {
  constexpr int kSize = 96;
  auto context = createOffscreenContext(kSize, kSize);
  if (!detail::GpuDepthSort::available()) {
    test::missingFixture("an OpenGL 4.3 context (compute shaders) for the GPU sort");
    return;
  }
  SECTION("a sphere of splats") {
    SplatSet set;
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0.0f, 1.0f);
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
      set.vectors.push_back({d, 0.03f, d, 0xff2080c0u + static_cast<std::uint32_t>(i % 64)});
    }
    set.style.kind = qnv::StreamKind::surface;
    set.computeBounds();
    scene::Camera camera;
    camera.position = {0.3f, 0.5f, 3.0f};
    camera.orientation = glm::quatLookAt(glm::normalize(-camera.position), glm::vec3(0, 1, 0));
    const Image gpu = drawSplats(set, camera, SplatPath::gpu, kSize);
    const Image geometry = drawSplats(set, camera, SplatPath::geometry, kSize);
    const ImageDifference d = compareImages(gpu, geometry, 1);
    INFO("differing " << d.fractionDiffering);
    CHECK(d.fractionDiffering <= 0.001);
    CHECK(compareImages(gpu, Image(kSize, kSize, 26, 51, 77), 16).fractionDiffering > 0.2);
  }
  SECTION("overlapping splats of equal depth (a voxel grid seen along an axis)") {
    // Two layers of a 24 x 24 grid facing the camera, each splat wider than the spacing,
    // alternately red and green: every pixel is covered by splats of exactly equal eye z,
    // whose compositing order decides its colour. The GPU's order must composite them as
    // the CPU's does (seen: 12% of the pixels differed when the GPU's ties ran the other
    // way).
    SplatSet set;
    for (int layer = 0; layer < 2; ++layer)
      for (int y = 0; y < 24; ++y)
        for (int x = 0; x < 24; ++x) {
          const glm::vec3 p(-0.6f + 0.05f * static_cast<float>(x),
                            -0.6f + 0.05f * static_cast<float>(y),
                            -0.2f * static_cast<float>(layer));
          const std::uint32_t colour = (x + y + layer) % 2 == 0 ? 0xff2020e0u : 0xff20e020u;
          set.vectors.push_back({p, 0.02f, glm::vec3(0, 0, 1), colour});
        }
    set.style.kind = qnv::StreamKind::surface;
    set.computeBounds();
    scene::Camera camera;
    camera.position = {0.0f, 0.0f, 3.0f};
    const Image gpu = drawSplats(set, camera, SplatPath::gpu, kSize);
    const Image geometry = drawSplats(set, camera, SplatPath::geometry, kSize);
    const Image cpu = drawSplats(set, camera, SplatPath::cpu, kSize);
    const ImageDifference d = compareImages(gpu, geometry, 1);
    INFO("gpu against geometry: differing " << d.fractionDiffering);
    CHECK(d.fractionDiffering <= 0.001);
    // The cpu path composites the ties in the same order (its own rounding apart).
    CHECK(compareImages(cpu, geometry, 16).fractionDiffering <= 0.01);
    CHECK(compareImages(gpu, Image(kSize, kSize, 26, 51, 77), 16).fractionDiffering > 0.2);
  }
}

TEST_CASE("the GPU-sorted path evaluates spherical harmonics on the GPU as the CPU does",
          "[splat][gpu]") {
  constexpr int kSize = 96;
  auto context = createOffscreenContext(kSize, kSize);
  if (!detail::GpuDepthSort::available()) {
    test::missingFixture("an OpenGL 4.3 context (compute shaders) for the GPU sort");
    return;
  }
  // Small opaque discs with strong view-dependent colour (SH degree 3), seen from two eyes:
  // the gpu path's colours come from its compute shader, the geometry path's from
  // splats::shColor on the CPU.
  for (const splats::ColorSpace space : {splats::ColorSpace::srgb, splats::ColorSpace::linear}) {
    splats::GaussianCloud cloud;
    cloud.shDegree = 3;
    cloud.colorSpace = space;
    cloud.resize(1500);
    std::mt19937 rng(11);
    std::normal_distribution<float> g(0.0f, 1.0f);
    std::uniform_real_distribution<float> u(-0.6f, 0.6f);
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      cloud.positions[i] = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
      cloud.scales[i] = glm::vec3(0.05f, 0.05f, 0.01f);
      cloud.rotations[i] = glm::normalize(glm::quat(g(rng), g(rng), g(rng), g(rng)));
      cloud.opacities[i] = 0.9f;
      cloud.shDc[i] = {u(rng), u(rng), u(rng)};
      for (int k = 0; k < 15; ++k)
        cloud.shRest[i * 15 + static_cast<std::size_t>(k)] = {u(rng), u(rng), u(rng)};
    }
    SplatSet set;
    set.gaussians = std::make_shared<const splats::GaussianCloud>(std::move(cloud));
    set.computeBounds();
    for (const glm::vec3 eye : {glm::vec3(0.3f, 0.5f, 3.0f), glm::vec3(-2.5f, 0.4f, -1.5f)}) {
      scene::Camera camera;
      camera.position = eye;
      camera.orientation = glm::quatLookAt(glm::normalize(-eye), glm::vec3(0, 1, 0));
      const auto draw = [&](SplatPath path) {
        SplatRenderer renderer;
        renderer.setPath(path);
        glViewport(0, 0, kSize, kSize);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        renderer.draw(set, set.size(), glm::mat4(1.0f), camera, 1.0f, {});
        CHECK(renderer.statistics().path == path);
        Image image = readPixels(0, 0, kSize, kSize);
        renderer.release();
        return image;
      };
      const Image gpu = draw(SplatPath::gpu);
      const Image geometry = draw(SplatPath::geometry);
      INFO("colour space " << static_cast<int>(space) << ", eye " << eye.x << " " << eye.y << " "
                           << eye.z);
      CHECK(compareImages(gpu, geometry, 2).fractionDiffering <= 0.002);
      CHECK(compareImages(gpu, Image(kSize, kSize, 0, 0, 0), 16).fractionDiffering > 0.2);
    }
  }
}

}  // namespace gs::render
