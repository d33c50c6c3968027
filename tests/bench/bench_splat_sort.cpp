// Splat depth sorting and the CPU reference of equation (1) (docs: the splat pass).
// Prints the time of DepthSorter alone per frame at 1, 4 and 16 million random vectors
// (best of 5 after a warm-up call, one thread), and of renderSplatsReference for 100k
// surface splats of a unit sphere at 256x256. No GPU needed.
//
//   bench_splat_sort [max millions]      (default 16)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "render/splat_reference.hpp"
#include "render/splat_sort.hpp"
#include "scene/camera.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<gs::qnv::DecodedVector> randomCube(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<gs::qnv::DecodedVector> v(n);
  for (auto& d : v) d = {{u(rng), u(rng), u(rng)}, 1.0f, {0.0f, 0.0f, 1.0f}, 0xffffffffu};
  return v;
}

/// n splats on the unit sphere, each with 1/n of its area, facing out.
std::vector<gs::qnv::DecodedVector> sphere(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> g;
  std::vector<gs::qnv::DecodedVector> v(n);
  const float area = 4.0f * 3.14159265f / static_cast<float>(n);
  for (auto& d : v) {
    glm::vec3 p(g(rng), g(rng), g(rng));
    p = glm::length(p) > 0.0f ? glm::normalize(p) : glm::vec3(0, 0, 1);
    const std::uint32_t rgba = 0xff000000u | (rng() & 0x00ffffffu);
    d = {p, area, p, rgba};
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const int maxMillions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 16;
  gs::scene::Camera camera;
  camera.position = {0.3f, 0.4f, 3.0f};
  camera.orientation = glm::angleAxis(0.1f, glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f)));
  const glm::mat4 view = gs::scene::viewMatrix(camera);

  std::printf("DepthSorter (LSD radix, 3 x 11 bits, one thread), best of 5 after a warm-up\n");
  for (const int millions : {1, 4, 16}) {
    if (millions > maxMillions) break;
    const std::size_t n = static_cast<std::size_t>(millions) * 1000000;
    const auto vectors = randomCube(n, 1u + static_cast<std::uint32_t>(millions));
    gs::render::DepthSorter sorter;
    std::vector<std::uint32_t> order;
    sorter.sortFrontToBack(vectors, view, order);  // warm-up: allocates the scratch
    double best = 1e30, bestBack = 1e30;
    for (int i = 0; i < 5; ++i) {
      auto t0 = Clock::now();
      sorter.sortFrontToBack(vectors, view, order);
      best = std::min(best, since(t0));
      t0 = Clock::now();
      sorter.sortBackToFront(vectors, view, order);
      bestBack = std::min(bestBack, since(t0));
    }
    // Sanity: the result is ordered.
    bool sorted = true;
    for (std::size_t i = 1; i < n && sorted; ++i) {
      const float a = (view * glm::vec4(vectors[order[i - 1]].position, 1.0f)).z;
      const float b = (view * glm::vec4(vectors[order[i]].position, 1.0f)).z;
      sorted = a <= b;
    }
    std::printf(
        "  %2d M vectors: front to back %7.1f ms, back to front %7.1f ms (%.0f M vectors/s)%s\n",
        millions, best * 1e3, bestBack * 1e3, static_cast<double>(n) / best / 1e6,
        sorted ? "" : "  NOT SORTED");
  }

  {
    const std::size_t n = 100000;
    const int size = 256;
    const auto vectors = sphere(n, 9);
    gs::render::SplatStyle style;  // surface, sigma 0.5
    const std::vector<gs::render::SplatLight> lights = {
        {glm::normalize(glm::vec3(-1.0f, -1.0f, -1.0f)), glm::vec3(0.8f)}};
    gs::scene::Camera view2;
    view2.position = {0.0f, 0.0f, 2.8f};
    gs::render::Image image = gs::render::renderSplatsReference(vectors, style, lights, view2, size,
                                                                size, glm::vec3(0.1f));
    double best = 1e30;
    for (int i = 0; i < 3; ++i) {
      const auto t0 = Clock::now();
      image = gs::render::renderSplatsReference(vectors, style, lights, view2, size, size,
                                                glm::vec3(0.1f));
      best = std::min(best, since(t0));
    }
    std::printf("renderSplatsReference: %zu sphere splats at %dx%d: %.1f ms (best of 3)\n", n, size,
                size, best * 1e3);
  }
  return 0;
}
