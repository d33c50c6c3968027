// The level-of-detail tree of merged Gaussians (splats/lod_tree.hpp, docs/splats-lod.md):
// prints the build time per million splats for synthetic clouds of 1 to 5 million splats
// (one thread), and for 100k-splat clouds the cut's size at 1.5 to 96 box diagonals (512
// pixels, 60 degrees, threshold 1 pixel, unbounded budget), the cut's time, its summed
// opacity x projected footprint against the full cloud's, and the cut's alpha image
// against the full cloud's as Kerbl et al.'s rasterizer draws them. No GPU.
//
//   bench_lod_tree [max millions]      (default 5)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "../splats/lod_views.hpp"
#include "splats/lod_tree.hpp"

namespace {

using namespace gs::splats;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

using gs::test::randomRotation;

/// A synthetic cloud in the box [-0.5, 0.5]^3: `surface` of the splats flat, nearly opaque
/// discs on the sphere of radius 0.5 and the plane y = -0.5 (a capture's surfaces), the rest
/// a haze of weak splats filling the box (opacity 0.025..0.075, about the mean spacing in
/// size: at 30k splats an optical depth of about 2 across the box).
GaussianCloud syntheticCloud(std::size_t n, double surface, int shDegree, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f), unit(0.0f, 1.0f);
  std::normal_distribution<float> g;
  GaussianCloud cloud;
  cloud.shDegree = shDegree;
  cloud.resize(n);
  const std::size_t discs = static_cast<std::size_t>(surface * static_cast<double>(n));
  const std::size_t haze = n - discs;
  const float discSize = std::sqrt((std::numbers::pi_v<float> + 1.0f) /
                                   static_cast<float>(std::max<std::size_t>(discs, 1)));
  const float spacing = std::cbrt(1.0f / static_cast<float>(std::max<std::size_t>(haze, 1)));
  const float hazeOpacity = 0.05f;
  for (std::size_t i = 0; i < n; ++i) {
    if (i < discs) {
      glm::vec3 normal(0.0f, 1.0f, 0.0f);
      if (unit(rng) < std::numbers::pi_v<float> / (std::numbers::pi_v<float> + 1.0f)) {
        normal = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
        cloud.positions[i] = 0.5f * normal;
      } else {
        cloud.positions[i] = {u(rng), -0.5f, u(rng)};
      }
      cloud.rotations[i] =
          normal.z > -0.9999f
              ? glm::normalize(glm::quat(1.0f + normal.z, -normal.y, normal.x, 0.0f))
              : glm::quat(0.0f, 1.0f, 0.0f, 0.0f);
      cloud.scales[i] =
          discSize * glm::vec3(0.5f + 0.5f * unit(rng), 0.5f + 0.5f * unit(rng), 0.0f);
      cloud.opacities[i] = 0.9f;
    } else {
      cloud.positions[i] = {u(rng), u(rng), u(rng)};
      cloud.scales[i] = spacing * glm::vec3(0.3f + 0.7f * unit(rng), 0.3f + 0.7f * unit(rng),
                                            0.3f + 0.7f * unit(rng));
      cloud.rotations[i] = randomRotation(rng);
      cloud.opacities[i] = hazeOpacity * (0.5f + unit(rng));
    }
    cloud.shDc[i] = {u(rng), u(rng), u(rng)};
  }
  for (auto& c : cloud.shRest) c = {0.1f * u(rng), 0.1f * u(rng), 0.1f * u(rng)};
  return cloud;
}

using View = gs::test::LodTestView;
using gs::test::projectedCoverage;

View viewAt(double diagonals, int pixels, float fovY) {
  return gs::test::lodViewAt(diagonals, pixels, fovY);
}

/// The alpha image (1 - transmittance, order-independent) of `cloud` as Kerbl et al.'s
/// rasterizer draws it (projectGaussian: 0.3 pixel^2 low-pass, 3-sigma box, alpha capped at
/// 0.99, below 1/255 skipped).
std::vector<float> alphaImage(const GaussianCloud& cloud, const View& view, int pixels) {
  ProjectionView projection;
  projection.modelView = view.view;
  projection.fx = projection.fy = view.focal;
  projection.cx = projection.cy = 0.5f * static_cast<float>(pixels);
  projection.width = projection.height = pixels;
  projection.nearClip = 0.01f;
  std::vector<float> transmittance(static_cast<std::size_t>(pixels) * pixels, 1.0f);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    ProjectedGaussian p;
    if (!projectGaussian(cloud.positions[i], covariance(cloud.scales[i], cloud.rotations[i]),
                         projection, p))
      continue;
    const float opacity = cloud.opacities[i];
    const int x0 = std::max(0, static_cast<int>(p.center.x - p.extent.x));
    const int x1 = std::min(pixels - 1, static_cast<int>(p.center.x + p.extent.x));
    const int y0 = std::max(0, static_cast<int>(p.center.y - p.extent.y));
    const int y1 = std::min(pixels - 1, static_cast<int>(p.center.y + p.extent.y));
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const float dx = static_cast<float>(x) + 0.5f - p.center.x;
        const float dy = static_cast<float>(y) + 0.5f - p.center.y;
        const float q = p.conic.x * dx * dx + 2.0f * p.conic.y * dx * dy + p.conic.z * dy * dy;
        const float alpha = std::min(0.99f, opacity * std::exp(-0.5f * q));
        if (alpha < 1.0f / 255.0f) continue;
        transmittance[static_cast<std::size_t>(y) * pixels + x] *= 1.0f - alpha;
      }
    }
  }
  for (float& t : transmittance) t = 1.0f - t;
  return transmittance;
}

struct ImageDifference {
  double alphaRatio = 0.0;      // summed alpha, cut over full
  double meanDifference = 0.0;  // mean |difference| over pixels where either shows, 0..1
  double differing = 0.0;       // fraction of those pixels off by more than 16/255
};

ImageDifference compareImages(const std::vector<float>& full, const std::vector<float>& cut) {
  ImageDifference out;
  double sumFull = 0.0, sumCut = 0.0, sumDifference = 0.0;
  std::size_t shown = 0, differing = 0;
  for (std::size_t k = 0; k < full.size(); ++k) {
    sumFull += full[k];
    sumCut += cut[k];
    if (full[k] < 1.0f / 255.0f && cut[k] < 1.0f / 255.0f) continue;
    ++shown;
    const double d = std::abs(static_cast<double>(full[k]) - cut[k]);
    sumDifference += d;
    differing += d > 16.0 / 255.0;
  }
  const double count = static_cast<double>(std::max<std::size_t>(shown, 1));
  out.alphaRatio = sumCut / std::max(sumFull, 1e-30);
  out.meanDifference = sumDifference / count;
  out.differing = static_cast<double>(differing) / count;
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const int maxMillions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;

  std::printf("Build (one thread; capture-like cloud: 70%% surface discs, 30%% haze)\n\n");
  std::printf(
      "| splats | SH degree | build s | s per million | nodes | merged | depth | tree MB |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (int millions = 1; millions <= maxMillions; millions += (millions == 1 ? 1 : 3)) {
    for (const int degree : {0, 3}) {
      if (degree == 3 && millions > 2) continue;
      const std::size_t n = static_cast<std::size_t>(millions) * 1000000;
      const GaussianCloud cloud = syntheticCloud(n, 0.7, degree, 1);
      const auto t0 = Clock::now();
      const LodTree tree = buildLodTree(cloud);
      const double seconds = since(t0);
      std::printf("| %zu | %d | %.2f | %.2f | %zu | %zu | %d | %.0f |\n", n, degree, seconds,
                  seconds / static_cast<double>(millions), tree.nodes.size(), tree.merged.size(),
                  tree.depth, static_cast<double>(tree.memoryBytes()) / 1e6);
    }
  }

  const float fovY = glm::radians(60.0f);
  struct Kind {
    const char* name;
    double surface;
  };
  for (const Kind kind : {Kind{"surfaces", 1.0}, Kind{"capture-like (70% surface, 30% haze)", 0.7},
                          Kind{"haze", 0.0}}) {
    const std::size_t n = 100000;
    const GaussianCloud cloud = syntheticCloud(n, kind.surface, 0, 2);
    const LodTree tree = buildLodTree(cloud);
    std::printf("\nCut of 100k splats, %s (512 px, 60 degrees, 1 px)\n\n", kind.name);
    std::printf(
        "| distance / diagonal | cut splats | of the cloud | cut ms | coverage ratio | "
        "alpha ratio | mean abs diff | pixels > 16/255 |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const double distance : {1.5, 3.0, 6.0, 12.0, 24.0, 48.0, 96.0}) {
      const View view = viewAt(distance, 512, fovY);
      const auto t0 = Clock::now();
      const LodCut cut = selectCut(tree, view.cut, n);
      const double ms = since(t0) * 1e3;
      GaussianCloud drawn;
      assembleCut(tree, cloud, cut, drawn);
      const double ratio = projectedCoverage(drawn, view) / projectedCoverage(cloud, view);
      const ImageDifference plain =
          compareImages(alphaImage(cloud, view, 512), alphaImage(drawn, view, 512));
      std::printf("| %.1f | %zu | %.2f%% | %.2f | %.3f | %.3f | %.4f | %.2f%% |\n", distance,
                  cut.size(), 100.0 * static_cast<double>(cut.size()) / static_cast<double>(n), ms,
                  ratio, plain.alphaRatio, plain.meanDifference, 100.0 * plain.differing);
    }
  }
  return 0;
}
