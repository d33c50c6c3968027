// The CPU side of the splat pass: depth sorting (DepthSorter) and the reference renderer
// of equation (1) (renderSplatsReference). No OpenGL context.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "../../render/src/simd4.hpp"
#include "render/splat_reference.hpp"
#include "render/splat_sort.hpp"

using gs::qnv::DecodedVector;
using gs::render::DepthSorter;
using gs::render::Image;
using gs::render::SplatCompositing;
using gs::render::SplatLight;
using gs::render::SplatStyle;
using gs::scene::Camera;

namespace {

constexpr std::uint32_t kRed = 0xff0000ffu;    // opaque red, R in the low byte
constexpr std::uint32_t kGreen = 0xff00ff00u;  // opaque green

DecodedVector vec(glm::vec3 position, glm::vec3 normal = {0, 0, 1}, std::uint32_t rgba = kRed,
                  float magnitude = 1.0f) {
  return DecodedVector{position, magnitude, normal, rgba};
}

float eyeZ(const glm::mat4& view, const DecodedVector& v) {
  return (view * glm::vec4(v.position, 1.0f)).z;
}

/// The expected order: std::stable_sort of the indices by eye-space z.
std::vector<std::uint32_t> expectedOrder(const std::vector<DecodedVector>& v, std::size_t n,
                                         const glm::mat4& view, bool frontToBack) {
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const float za = eyeZ(view, v[a]) + 0.0f, zb = eyeZ(view, v[b]) + 0.0f;
    return frontToBack ? za > zb : za < zb;
  });
  return order;
}

glm::mat4 tiltedView() {
  Camera c;
  c.position = {3.0f, -2.0f, 12.0f};
  c.orientation = glm::angleAxis(0.3f, glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  return gs::scene::viewMatrix(c);
}

std::vector<DecodedVector> randomVectors(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-5.0f, 5.0f);
  std::vector<DecodedVector> v(n);
  for (auto& d : v) d = vec({u(rng), u(rng), u(rng)});
  return v;
}

/// A volume style: spread s = 1 world unit, peak = opacity * sqrt(magnitude).
SplatStyle volumeStyle(float opacity) {
  SplatStyle s;
  s.kind = gs::qnv::StreamKind::volume;
  s.sigma = 0.5f;
  s.voxelSize = 1.0f;
  s.magnitudeMax = 1.0f;
  s.opacityScale = opacity;
  s.ambient = 0.2f;  // as SplatStyle::fromHeader gives volumes
  return s;
}

/// A light along the view direction: shadeSplat gives rgb * (0.2 ambient + 0.8 * 1) = rgb
/// for a volume splat (volumeStyle) facing the camera (the diffuse share is 1 - ambient),
/// rgb * 0.8 for a surface splat (no ambient).
const std::vector<SplatLight> kHeadLight = {SplatLight{{0.0f, 0.0f, -1.0f}, glm::vec3(1.0f)}};
const std::vector<SplatLight> kSurfaceLight = {SplatLight{{0.0f, 0.0f, -1.0f}, glm::vec3(0.8f)}};

constexpr int kSize = 65;  // odd: the centre pixel's ray is the view axis
constexpr int kMid = kSize / 2;
const glm::vec3 kBlue(0.0f, 0.0f, 1.0f);

std::uint8_t level(float c) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c, 0.0f, 1.0f) * 255.0f));
}

bool pixelIs(const Image& image, int x, int y, glm::vec3 c, int tolerance = 1) {
  const std::uint8_t* p = image.pixel(x, y);
  const std::uint8_t e[3] = {level(c.r), level(c.g), level(c.b)};
  for (int i = 0; i < 3; ++i) {
    if (std::abs(int(p[i]) - int(e[i])) > tolerance) {
      UNSCOPED_INFO("pixel " << x << "," << y << " = " << int(p[0]) << " " << int(p[1]) << " "
                             << int(p[2]) << ", expected " << int(e[0]) << " " << int(e[1]) << " "
                             << int(e[2]));
      return false;
    }
  }
  return p[3] == 255;
}

bool allPixels(const Image& image, glm::vec3 c) {
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!pixelIs(image, x, y, c, 0)) return false;
  return true;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// DepthSorter

TEST_CASE("depth sort orders random depths in both directions", "[render][splat][sort]") {
  const auto v = randomVectors(20000, 7);
  const glm::mat4 view = tiltedView();
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  sorter.sortBackToFront(v, view, order);
  REQUIRE(order == expectedOrder(v, v.size(), view, false));
  for (std::size_t i = 1; i < order.size(); ++i)
    REQUIRE(eyeZ(view, v[order[i - 1]]) <= eyeZ(view, v[order[i]]));
  sorter.sortFrontToBack(v, view, order);
  REQUIRE(order == expectedOrder(v, v.size(), view, true));
  for (std::size_t i = 1; i < order.size(); ++i)
    REQUIRE(eyeZ(view, v[order[i - 1]]) >= eyeZ(view, v[order[i]]));
}

TEST_CASE("depth sort handles negative, positive and huge depths", "[render][splat][sort]") {
  const glm::mat4 view(1.0f);  // eye space = world space
  std::vector<DecodedVector> v;
  for (float z : {0.0f, -0.0f, 1.0f, -1.0f, 1e30f, -1e30f, 3.5f, -3.5f, 1e-30f, -1e-30f, INFINITY,
                  -INFINITY, 2.0f, -2.0f})
    v.push_back(vec({0.0f, 0.0f, z}));
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  sorter.sortBackToFront(v, view, order);
  CHECK(order == expectedOrder(v, v.size(), view, false));
  CHECK(v[order.front()].position.z == -INFINITY);
  sorter.sortFrontToBack(v, view, order);
  CHECK(order == expectedOrder(v, v.size(), view, true));
  CHECK(v[order.front()].position.z == INFINITY);
}

TEST_CASE("depth sort puts NaN depths farthest", "[render][splat][sort]") {
  const glm::mat4 view(1.0f);
  const std::vector<DecodedVector> v = {vec({0.0f, 0.0f, -1.0f}), vec({0.0f, 0.0f, NAN}),
                                        vec({0.0f, 0.0f, -INFINITY}), vec({0.0f, 0.0f, 2.0f}),
                                        vec({0.0f, 0.0f, -NAN})};
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  sorter.sortBackToFront(v, view, order);
  CHECK(order == std::vector<std::uint32_t>{1, 4, 2, 0, 3});
  sorter.sortFrontToBack(v, view, order);
  CHECK(order == std::vector<std::uint32_t>{3, 0, 2, 1, 4});
}

TEST_CASE("depth sort is stable for equal depths", "[render][splat][sort]") {
  const glm::mat4 view(1.0f);
  SECTION("all equal: the identity in both directions") {
    std::vector<DecodedVector> v;
    for (int i = 0; i < 1000; ++i) v.push_back(vec({float(i % 17), float(i % 5), -4.0f}));
    std::vector<std::uint32_t> identity(v.size());
    std::iota(identity.begin(), identity.end(), 0u);
    DepthSorter sorter;
    std::vector<std::uint32_t> order;
    sorter.sortBackToFront(v, view, order);
    CHECK(order == identity);
    sorter.sortFrontToBack(v, view, order);
    CHECK(order == identity);
  }
  SECTION("few distinct depths: ties keep index order") {
    std::mt19937 rng(3);
    std::vector<DecodedVector> v;
    for (int i = 0; i < 5000; ++i) v.push_back(vec({0.0f, 0.0f, float(int(rng() % 7) - 3)}));
    DepthSorter sorter;
    std::vector<std::uint32_t> order;
    sorter.sortBackToFront(v, view, order);
    CHECK(order == expectedOrder(v, v.size(), view, false));
    sorter.sortFrontToBack(v, view, order);
    CHECK(order == expectedOrder(v, v.size(), view, true));
  }
}

TEST_CASE("depth sort of nothing and of a prefix", "[render][splat][sort]") {
  const glm::mat4 view = tiltedView();
  DepthSorter sorter;
  std::vector<std::uint32_t> order = {1, 2, 3};
  sorter.sortBackToFront({}, view, order);
  CHECK(order.empty());
  const auto v = randomVectors(3000, 11);
  sorter.sortFrontToBack(v, view, order, 0);
  CHECK(order.empty());
  sorter.sortFrontToBack(v, view, order, 1);
  CHECK(order == std::vector<std::uint32_t>{0});
  sorter.sortBackToFront(v, view, order, 1234);
  REQUIRE(order.size() == 1234);
  CHECK(order == expectedOrder(v, 1234, view, false));
  CHECK(*std::max_element(order.begin(), order.end()) == 1233u);
  sorter.sortFrontToBack(v, view, order, 1234);
  CHECK(order == expectedOrder(v, 1234, view, true));
  sorter.sortFrontToBack(v, view, order, 999999);  // more than the span: all of it
  CHECK(order.size() == v.size());
}

TEST_CASE("depth sort does not allocate after the first call", "[render][splat][sort]") {
  const auto v = randomVectors(50000, 5);
  const glm::mat4 view = tiltedView();
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  sorter.sortBackToFront(v, view, order);
  const DepthSorter::ScratchInfo first = sorter.scratch();
  const std::uint32_t* orderData = order.data();
  const std::size_t orderCapacity = order.capacity();
  CHECK(first.capacity == v.size());
  CHECK(sorter.scratchBytes() >= 12 * v.size());

  for (int frame = 0; frame < 3; ++frame) {
    sorter.sortFrontToBack(v, tiltedView() * glm::mat4(float(frame + 1)), order);
    sorter.sortBackToFront(v, view, order, v.size() / 2);  // a coarser level of detail
    sorter.sortBackToFront(v, view, order);
    const DepthSorter::ScratchInfo now = sorter.scratch();
    CHECK(now.keys == first.keys);
    CHECK(now.keysAlt == first.keysAlt);
    CHECK(now.indices == first.indices);
    CHECK(now.capacity == first.capacity);
    CHECK(order.data() == orderData);
    CHECK(order.capacity() == orderCapacity);
  }
  CHECK(order == expectedOrder(v, v.size(), view, false));

  DepthSorter reserved;
  reserved.reserve(v.size());
  const DepthSorter::ScratchInfo before = reserved.scratch();
  reserved.sortFrontToBack(v, view, order);
  CHECK(reserved.scratch().keys == before.keys);
  CHECK(reserved.scratch().indices == before.indices);
}

// ---------------------------------------------------------------------------------------
// The reference renderer of equation (1)

TEST_CASE("one splat facing the camera: alpha colour over the background", "[render][splat]") {
  const float peak = 0.6f;
  const std::vector<DecodedVector> v = {vec({0, 0, 0}, {0, 0, 1}, kRed)};
  Camera camera;  // at (0, 0, 10) looking down -Z, 45 degrees
  const Image image = gs::render::renderSplatsReference(v, volumeStyle(peak), kHeadLight, camera,
                                                        kSize, kSize, kBlue);
  REQUIRE(image.width == kSize);
  REQUIRE(image.height == kSize);
  // The EWA projection of a disc of spread s = 1 unit facing the camera at distance 10:
  // a circular Gaussian of s_px = f / 10 pixels (f the focal length in pixels), widened by
  // the 0.3-pixel low-pass to s'^2 = s_px^2 + 0.3, its peak scaled by s_px^2 / s'^2 so the
  // integrated opacity is kept: alpha(d) = peak keep exp(-d^2 / (2 s'^2)), d in pixels.
  const float focal = 0.5f * kSize / std::tan(camera.fieldOfView / 2.0f);
  const float spx2 = (focal / 10.0f) * (focal / 10.0f), wide2 = spx2 + 0.3f;
  const float keep = spx2 / wide2;
  CHECK(
      pixelIs(image, kMid, kMid, peak * keep * glm::vec3(1, 0, 0) + (1.0f - peak * keep) * kBlue));
  for (const glm::ivec2 offset : {glm::ivec2(16, 0), glm::ivec2(0, -16), glm::ivec2(-11, 9)}) {
    const float d2 = glm::dot(glm::vec2(offset), glm::vec2(offset));
    const float alpha = peak * keep * std::exp(-d2 / (2.0f * wide2));
    CHECK(pixelIs(image, kMid + offset.x, kMid + offset.y,
                  alpha * glm::vec3(1, 0, 0) + (1.0f - alpha) * kBlue));
  }
  // Beyond the 3-sigma box, ceil(3 s') pixels: the background exactly.
  const int beyond = int(std::ceil(3.0f * std::sqrt(wide2))) + 1;
  CHECK(pixelIs(image, kMid + beyond, kMid, kBlue, 0));
  CHECK(pixelIs(image, kMid, kMid - beyond, kBlue, 0));
  CHECK(pixelIs(image, 0, 0, kBlue, 0));
  CHECK(pixelIs(image, kSize - 1, kSize - 1, kBlue, 0));
  // Lighting and transfer alpha: no light gives the 0.2 ambient; half the alpha byte
  // halves the peak.
  const std::vector<DecodedVector> dim = {vec({0, 0, 0}, {0, 0, 1}, 0x800000ffu)};
  const Image unlit =
      gs::render::renderSplatsReference(dim, volumeStyle(1.0f), {}, camera, kSize, kSize, kBlue);
  const float a = 128.0f / 255.0f * keep;
  CHECK(pixelIs(unlit, kMid, kMid, a * glm::vec3(0.2f, 0, 0) + (1.0f - a) * kBlue));
}

TEST_CASE("a surface splat has the area-preserving profile", "[render][splat]") {
  // Surfaces: s = R = sqrt(A / pi) and peak 1/2 for sigma 0.5; no ambient light, so the
  // headlight alone gives 0.8 green.
  const float area = 3.14159265f;  // R = 1
  const std::vector<DecodedVector> v = {vec({0, 0, 0}, {0, 0, -1}, kGreen, area)};
  SplatStyle style;  // surface, sigma 0.5, ambient 0
  const Image image =
      gs::render::renderSplatsReference(v, style, kSurfaceLight, Camera{}, kSize, kSize, kBlue);
  CHECK(pixelIs(image, kMid, kMid, glm::vec3(0, 0.4f, 0.5f)));  // two-sided shading
}

TEST_CASE("two overlapping splats: the front one dominates, order matters", "[render][splat]") {
  const float peak = 0.6f;
  // Red nearer (z = 1), green farther (z = 0); given in the wrong order on purpose.
  const std::vector<DecodedVector> v = {vec({0, 0, 0}, {0, 0, 1}, kGreen),
                                        vec({0, 0, 1}, {0, 0, 1}, kRed)};
  const SplatStyle style = volumeStyle(peak);
  const Camera camera;
  const Image image =
      gs::render::renderSplatsReference(v, style, kHeadLight, camera, kSize, kSize, kBlue);
  const glm::vec3 expected = peak * glm::vec3(1, 0, 0) + (1.0f - peak) * peak * glm::vec3(0, 1, 0) +
                             (1.0f - peak) * (1.0f - peak) * kBlue;
  CHECK(pixelIs(image, kMid, kMid, expected));
  CHECK(image.pixel(kMid, kMid)[0] > image.pixel(kMid, kMid)[1]);

  // The same splats composited in a deliberately wrong order (green as if in front).
  const std::vector<std::uint32_t> wrong = {0, 1};
  const Image broken = gs::render::splatColorsToImage(
      gs::render::compositeSplats(v, wrong, SplatCompositing::frontToBack, style, kHeadLight,
                                  camera, kSize, kSize, kBlue),
      kSize, kSize);
  CHECK(broken.pixel(kMid, kMid)[1] > broken.pixel(kMid, kMid)[0]);
  const gs::render::ImageDifference d = gs::render::compareImages(image, broken, 4);
  CHECK(d.meanAbsolute > 1.0);
  CHECK(d.fractionDiffering > 0.1);
  // The right order given explicitly reproduces the image.
  const std::vector<std::uint32_t> right = {1, 0};
  const Image same = gs::render::splatColorsToImage(
      gs::render::compositeSplats(v, right, SplatCompositing::frontToBack, style, kHeadLight,
                                  camera, kSize, kSize, kBlue),
      kSize, kSize);
  CHECK(same.rgba == image.rgba);
  // Back to front with the front-to-back order is wrong too.
  const Image brokenOver = gs::render::splatColorsToImage(
      gs::render::compositeSplats(v, right, SplatCompositing::backToFront, style, kHeadLight,
                                  camera, kSize, kSize, kBlue),
      kSize, kSize);
  CHECK(gs::render::compareImages(image, brokenOver, 4).fractionDiffering > 0.1);
}

TEST_CASE("front to back equals back to front", "[render][splat]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  std::uniform_real_distribution<float> m(0.05f, 1.0f);
  std::vector<DecodedVector> v;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 n = glm::normalize(glm::vec3(u(rng), u(rng), u(rng)) + glm::vec3(0, 0, 0.01f));
    v.push_back(
        vec({u(rng), u(rng), u(rng)}, n, static_cast<std::uint32_t>(rng()) | 0x40000000u, m(rng)));
  }
  Camera camera;
  camera.position = {1.0f, 2.0f, 9.0f};
  camera.orientation = glm::angleAxis(0.2f, glm::normalize(glm::vec3(1.0f, -1.0f, 0.3f)));
  const std::vector<SplatLight> lights = {
      SplatLight{glm::normalize(glm::vec3(1, -1, -1)), glm::vec3(0.7f)}};
  for (const SplatStyle& style : {SplatStyle{}, volumeStyle(0.8f)}) {
    const Image front =
        gs::render::renderSplatsReference(v, style, lights, camera, 80, 60, {0.1f, 0.2f, 0.3f});
    const Image back = gs::render::renderSplatsReferenceBackToFront(v, style, lights, camera, 80,
                                                                    60, {0.1f, 0.2f, 0.3f});
    REQUIRE(front.width == 80);
    REQUIRE(front.height == 60);
    CHECK(gs::render::compareImages(front, back, 1).fractionDiffering == 0.0);
    // Something was drawn.
    CHECK(gs::render::compareImages(front, Image(80, 60, 26, 51, 77), 2).fractionDiffering > 0.2);

    // The linear colours agree to float rounding.
    DepthSorter sorter;
    std::vector<std::uint32_t> nearFirst, farFirst;
    sorter.sortFrontToBack(v, gs::scene::viewMatrix(camera), nearFirst);
    sorter.sortBackToFront(v, gs::scene::viewMatrix(camera), farFirst);
    const auto a = gs::render::compositeSplats(v, nearFirst, SplatCompositing::frontToBack, style,
                                               lights, camera, 80, 60, {0.1f, 0.2f, 0.3f});
    const auto b = gs::render::compositeSplats(v, farFirst, SplatCompositing::backToFront, style,
                                               lights, camera, 80, 60, {0.1f, 0.2f, 0.3f});
    REQUIRE(a.size() == b.size());
    float worst = 0.0f;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
    CHECK(worst < 1e-5f);
  }
}

TEST_CASE("a splat seen edge-on contributes nothing", "[render][splat]") {
  Camera camera;  // the eye at (0, 0, 10): planes through it are seen edge-on
  const std::vector<DecodedVector> v = {vec({0, 0, 0}, {1, 0, 0}, kRed),
                                        vec({0.5f, 0, 0}, {0, 1, 0}, kRed),
                                        vec({0, 1, 2}, {1, 0, 0}, kGreen)};
  const Image image = gs::render::renderSplatsReference(v, volumeStyle(1.0f), kHeadLight, camera,
                                                        kSize, kSize, kBlue);
  CHECK(allPixels(image, kBlue));
  // Turned a little, the same splat shows.
  const std::vector<DecodedVector> turned = {
      vec({0, 0, 0}, glm::normalize(glm::vec3(1, 0, 0.2f)), kRed)};
  const Image seen = gs::render::renderSplatsReference(turned, volumeStyle(1.0f), kHeadLight,
                                                       camera, kSize, kSize, kBlue);
  CHECK_FALSE(allPixels(seen, kBlue));
}

TEST_CASE("splats behind the eye or the near plane draw nothing", "[render][splat]") {
  Camera camera;
  // Behind the eye (z > 10), and in front of it but nearer than the near plane (0.125).
  const std::vector<DecodedVector> v = {vec({0, 0, 12}, {0, 0, 1}, kRed),
                                        vec({0, 0, 10.05f}, {0, 0, 1}, kRed),
                                        vec({0, 0, 9.95f}, {0, 0, 1}, kGreen)};
  const Image image = gs::render::renderSplatsReference(v, volumeStyle(1.0f), kHeadLight, camera,
                                                        kSize, kSize, kBlue);
  CHECK(allPixels(image, kBlue));
}

TEST_CASE("the level of detail draws a prefix of the vectors", "[render][splat]") {
  const std::vector<DecodedVector> v = {vec({0, 0, 0}, {0, 0, 1}, kRed),
                                        vec({0, 0, 1}, {0, 0, 1}, kGreen)};
  const SplatStyle style = volumeStyle(0.6f);
  const Camera camera;
  CHECK(allPixels(
      gs::render::renderSplatsReference(v, style, kHeadLight, camera, kSize, kSize, kBlue, 0),
      kBlue));
  CHECK(allPixels(gs::render::renderSplatsReferenceBackToFront(v, style, kHeadLight, camera, kSize,
                                                               kSize, kBlue, 0),
                  kBlue));
  const Image one =
      gs::render::renderSplatsReference(v, style, kHeadLight, camera, kSize, kSize, kBlue, 1);
  CHECK(pixelIs(one, kMid, kMid, 0.6f * glm::vec3(1, 0, 0) + 0.4f * kBlue));
  const Image both =
      gs::render::renderSplatsReference(v, style, kHeadLight, camera, kSize, kSize, kBlue, 2);
  CHECK(both.pixel(kMid, kMid)[1] > both.pixel(kMid, kMid)[0]);  // green is in front
  CHECK(gs::render::renderSplatsReference(v, style, kHeadLight, camera, kSize, kSize, kBlue).rgba ==
        both.rgba);
  CHECK(gs::render::renderSplatsReference(v, style, kHeadLight, camera, 0, 10, kBlue).empty());
}

TEST_CASE("the cpu path's exp4 keeps a sixtieth of an 8-bit level over the Gaussian's range",
          "[splat]") {
  // exp4 (render/src/simd4.hpp) weighs every fragment of the cpu path: relative error below
  // 6e-5 on [-8, 0], exactly 1 at 0, and lanes independent.
  double worst = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    const float x = -8.0f * static_cast<float>(i) / 200000.0f;
    const gs::render::detail::F4 v = {x, 0.25f * x, 0.5f * x, 0.75f * x};
    const gs::render::detail::F4 e = gs::render::detail::exp4(v);
    for (int lane = 0; lane < 4; ++lane)
      worst = std::max(
          worst,
          std::abs(static_cast<double>(e[lane]) / std::exp(static_cast<double>(v[lane])) - 1.0));
  }
  INFO("worst relative error " << worst);
  CHECK(worst < 6e-5);
  const gs::render::detail::F4 small = {0.0f, -0.0f, -1e-30f, -1e-7f};
  const gs::render::detail::F4 zero = gs::render::detail::exp4(small);
  for (int lane = 0; lane < 3; ++lane) CHECK(zero[lane] == 1.0f);
}
