// The level-of-detail tree of merged Gaussians (splats/lod_tree.hpp, docs/splats-lod.md):
// the moment matching, the eigen-decomposition, the tree's invariants and the cut.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "lod_views.hpp"
#include "splats/lod_tree.hpp"

using namespace gs::splats;

namespace {

using TestView = gs::test::LodTestView;
using gs::test::projectedCoverage;
using gs::test::randomRotation;

/// n weak splats (anisotropic, about the mean spacing in size) filling the cube
/// [-0.5, 0.5]^3: a haze. Each splat's opacity is `opacity` x 0.5..1.5 / cbrt(n), so that
/// the haze's optical depth does not depend on n (about 0.3 across the cube at 0.1).
GaussianCloud hazeCloud(std::size_t n, std::uint32_t seed, int shDegree = 0, float opacity = 0.1f) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f), unit(0.0f, 1.0f);
  GaussianCloud cloud;
  cloud.shDegree = shDegree;
  cloud.resize(n);
  const float spacing = std::cbrt(1.0f / static_cast<float>(n));
  for (std::size_t i = 0; i < n; ++i) {
    cloud.positions[i] = {u(rng), u(rng), u(rng)};
    cloud.scales[i] = spacing * glm::vec3(0.3f + 0.7f * unit(rng), 0.3f + 0.7f * unit(rng),
                                          0.3f + 0.7f * unit(rng));
    cloud.rotations[i] = randomRotation(rng);
    cloud.opacities[i] = opacity * (0.5f + unit(rng)) / std::cbrt(static_cast<float>(n));
    cloud.shDc[i] = {u(rng), u(rng), u(rng)};
  }
  for (auto& c : cloud.shRest) c = {u(rng), u(rng), u(rng)};
  return cloud;
}

/// A scene like a capture: `surface` of the splats flat, nearly opaque discs tangent to the
/// sphere of radius 0.5, the rest a haze inside the cube [-0.5, 0.5]^3.
GaussianCloud sceneCloud(std::size_t n, std::uint32_t seed, double surface = 0.5) {
  GaussianCloud cloud = hazeCloud(n, seed);
  std::mt19937 rng(seed + 1);
  std::normal_distribution<float> g;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::size_t shell = static_cast<std::size_t>(surface * static_cast<double>(n));
  const float discSize = std::sqrt(std::numbers::pi_v<float> / static_cast<float>(shell));
  for (std::size_t i = 0; i < shell; ++i) {
    const glm::vec3 normal = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    cloud.positions[i] = 0.5f * normal;
    // The rotation taking +z to the normal: the disc's flat axis is z.
    cloud.rotations[i] = normal.z > -0.9999f
                             ? glm::normalize(glm::quat(1.0f + normal.z, -normal.y, normal.x, 0.0f))
                             : glm::quat(0.0f, 1.0f, 0.0f, 0.0f);
    cloud.scales[i] = discSize * glm::vec3(0.5f + 0.5f * unit(rng), 0.5f + 0.5f * unit(rng), 0.0f);
    cloud.opacities[i] = 0.9f;
  }
  return cloud;
}

TestView viewAt(double distance, int pixels = 512, float fovY = glm::radians(60.0f),
                float threshold = 1.0f, glm::vec3 direction = {0.3f, 0.4f, 0.866f}) {
  return gs::test::lodViewAt(distance, pixels, fovY, threshold, direction);
}

double maxAbs(const glm::dmat3& m) {
  double out = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) out = std::max(out, std::abs(m[c][r]));
  return out;
}

double maxAbsDifference(const glm::dmat3& a, const glm::dmat3& b) {
  return maxAbs(a - b);
}

/// The splats each merged Gaussian stands for: splatsOf[g] for merged Gaussian g.
std::vector<std::vector<std::uint32_t>> splatsOfMerged(const LodTree& tree) {
  std::vector<std::vector<std::uint32_t>> out(tree.merged.size());
  // Leaf ranges of each node by walking bottom up: a node's splats are a contiguous range
  // of leafSplats (breadth-first children are consecutive, their ranges adjacent).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> range(tree.nodes.size());
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    const LodNode& node = tree.nodes[i];
    if (node.isLeaf())
      range[i] = {node.first, node.first + node.count};
    else
      range[i] = {range[node.first].first, range[node.first + node.count - 1].second};
    if (node.gaussian != LodNode::kNone)
      out[node.gaussian].assign(tree.leafSplats.begin() + range[i].first,
                                tree.leafSplats.begin() + range[i].second);
  }
  return out;
}

/// Whether `cut` represents every splat of the tree exactly once.
bool coversOnce(const LodTree& tree, const LodCut& cut,
                const std::vector<std::vector<std::uint32_t>>& splatsOf) {
  std::vector<int> seen(tree.splatCount, 0);
  for (const std::uint32_t i : cut.originals) ++seen[i];
  for (const std::uint32_t g : cut.merged)
    for (const std::uint32_t i : splatsOf[g]) ++seen[i];
  return std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; });
}

}  // namespace

TEST_CASE("meanProjectedArea is Cauchy's mean projection of the 1-sigma ellipsoid",
          "[splats][lod]") {
  CHECK(meanProjectedArea({2.0f, 2.0f, 2.0f}) == Approx(std::numbers::pi * 4.0).epsilon(1e-12));
  // A flat disc seen from all directions shows pi a b |cos| on average: pi a b / 2
  // (Thomsen's approximation is 1% high there).
  CHECK(meanProjectedArea({3.0f, 1.0f, 0.0f}) == Approx(std::numbers::pi * 1.5).epsilon(0.011));
  CHECK(meanProjectedArea({3.0f, 0.0f, 0.0f}) == 0.0);
  CHECK(splatCoverage({1.0f, 1.0f, 1.0f}, 0.25f) == Approx(0.25 * std::numbers::pi));
  CHECK(splatCoverage({1.0f, 1.0f, 1.0f}, std::nanf("")) == 0.0);
}

TEST_CASE("moment matching two Gaussians gives the analytic mean and covariance", "[splats][lod]") {
  // Equal coverage: mean halfway, variance along x = sigma^2 + 1 (the law of total variance).
  // (b is rotated: a sphere's covariance does not depend on its rotation.)
  std::mt19937 rng(3);
  const GaussianMoments a =
      splatMoments({-1.0f, 0.0f, 0.0f}, glm::vec3(0.5f), glm::quat(1, 0, 0, 0), 0.2f);
  const GaussianMoments b =
      splatMoments({1.0f, 0.0f, 0.0f}, glm::vec3(0.5f), randomRotation(rng), 0.2f);
  const GaussianMoments pair[] = {a, b};
  const GaussianMoments m = mergeMoments(pair);
  CHECK(m.weight == Approx(2.0 * 0.2 * std::numbers::pi * 0.25));
  CHECK(m.count == 2.0);
  CHECK(glm::length(m.mean) < 1e-12);
  const glm::dmat3 expected(glm::dvec3(1.25, 0.0, 0.0), glm::dvec3(0.0, 0.25, 0.0),
                            glm::dvec3(0.0, 0.0, 0.25));
  CHECK(maxAbsDifference(m.covariance, expected) < 1e-7);

  // Coverage 3 : 1 (opacity 0.9 and 0.3): mean = 0.75 (-1) + 0.25 (1) = -0.5, variance
  // along x = 0.25 + 0.75 x 0.5^2 + 0.25 x 1.5^2 = 1.
  const GaussianMoments c =
      splatMoments({-1.0f, 0.0f, 0.0f}, glm::vec3(0.5f), glm::quat(1, 0, 0, 0), 0.9f);
  const GaussianMoments d =
      splatMoments({1.0f, 0.0f, 0.0f}, glm::vec3(0.5f), glm::quat(1, 0, 0, 0), 0.3f);
  const GaussianMoments pair2[] = {c, d};
  const GaussianMoments m2 = mergeMoments(pair2);
  CHECK(m2.mean.x == Approx(-0.5).epsilon(1e-6));  // 0.9f / 0.3f is not exactly 3
  const glm::dmat3 expected2(glm::dvec3(1.0, 0.0, 0.0), glm::dvec3(0.0, 0.25, 0.0),
                             glm::dvec3(0.0, 0.0, 0.25));
  CHECK(maxAbsDifference(m2.covariance, expected2) < 1e-7);

  // The tree of the two gives the same merged Gaussian, its opacity keeping the coverage.
  GaussianCloud cloud;
  cloud.resize(2);
  cloud.positions = {{-1.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}};
  cloud.scales = {glm::vec3(0.5f), glm::vec3(0.5f)};
  cloud.opacities = {0.9f, 0.3f};
  cloud.shDc = {glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
  const LodTree tree = buildLodTree(cloud, {.branching = 4, .leafSize = 2});
  REQUIRE(tree.nodes.size() == 1);
  REQUIRE(tree.merged.size() == 1);
  CHECK(tree.merged.positions[0].x == Approx(-0.5f).margin(1e-6));
  const glm::dmat3 sigma(covariance(tree.merged.scales[0], tree.merged.rotations[0]));
  CHECK(maxAbsDifference(sigma, expected2) < 1e-6);
  CHECK(tree.merged.scales[0].x == Approx(1.0f).epsilon(1e-6));
  const double area = meanProjectedArea(tree.merged.scales[0]);
  CHECK(tree.merged.opacities[0] * area == Approx(m2.weight).epsilon(1e-5));
  CHECK(tree.merged.opacities[0] < 0.9f);
  CHECK(tree.merged.shDc[0].x == Approx(0.75f).epsilon(1e-6));  // coverage-weighted colour
  CHECK(tree.merged.shDc[0].y == Approx(0.25f).epsilon(1e-6));
}

TEST_CASE("merging is associative and keeps the coverage", "[splats][lod]") {
  const GaussianCloud cloud = hazeCloud(20000, 11);
  const LodTree tree = buildLodTree(cloud);
  // The root's coverage is the sum of every splat's.
  double total = 0.0;
  for (std::size_t i = 0; i < cloud.size(); ++i)
    total += splatCoverage(cloud.scales[i], cloud.opacities[i]);
  REQUIRE(!tree.merged.empty());
  CHECK(tree.mergedCoverage[0] == Approx(total).epsilon(1e-5));
  // And its moments are those of all splats merged at once (associativity).
  std::vector<GaussianMoments> all(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i) all[i] = splatMoments(cloud, i);
  const GaussianMoments direct = mergeMoments(all);
  CHECK(glm::length(glm::dvec3(tree.merged.positions[0]) - direct.mean) < 1e-6);
  const glm::dmat3 rootSigma(covariance(tree.merged.scales[0], tree.merged.rotations[0]));
  CHECK(maxAbsDifference(rootSigma, direct.covariance) < 1e-5 * maxAbs(direct.covariance));
  // Each merged Gaussian's opacity x mean projected area is its coverage (no clamp in a
  // haze), and each coverage is its children's sum.
  int checked = 0;
  for (const LodNode& node : tree.nodes) {
    if (node.gaussian == LodNode::kNone) continue;
    const std::size_t g = node.gaussian;
    const double own = tree.merged.opacities[g] * meanProjectedArea(tree.merged.scales[g]);
    if (tree.merged.opacities[g] < 1.0f)
      CHECK(own == Approx(tree.mergedCoverage[g]).epsilon(1e-4));
    else
      CHECK(own <= tree.mergedCoverage[g] * (1.0 + 1e-6));
    double parts = 0.0;
    for (std::uint32_t k = 0; k < node.count; ++k) {
      if (node.isLeaf()) {
        const std::uint32_t s = tree.leafSplats[node.first + k];
        parts += splatCoverage(cloud.scales[s], cloud.opacities[s]);
      } else {
        const LodNode& child = tree.nodes[node.first + k];
        parts += child.gaussian != LodNode::kNone
                     ? tree.mergedCoverage[child.gaussian]
                     : splatCoverage(cloud.scales[tree.leafSplats[child.first]],
                                     cloud.opacities[tree.leafSplats[child.first]]);
      }
    }
    CHECK(tree.mergedCoverage[g] == Approx(parts).epsilon(1e-4));
    ++checked;
  }
  CHECK(checked == static_cast<int>(tree.merged.size()));
  // Many weak splats become one wide Gaussian: the root spans the cube (sigma of a uniform
  // unit interval: 0.29), its opacity unclamped (the haze's optical depth is below 1).
  CHECK(tree.merged.scales[0].z > 0.25f);
  CHECK(tree.merged.opacities[0] > 0.0f);
  CHECK(tree.merged.opacities[0] < 1.0f);
}

TEST_CASE("the eigen-decomposition reconstructs covariances, flat ones included", "[splats][lod]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  std::vector<glm::vec3> scales = {{1.0f, 0.5f, 0.0f},      {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f},
                                   {1.0f, 1.0f, 1.0f},      {1.0f, 1.0f, 0.3f}, {0.3f, 1.0f, 1.0f},
                                   {1e-4f, 1.0f, 1e3f},     {1.0f, 1.0f, 0.0f}, {0.0f, 3.0f, 0.0f},
                                   {1e-10f, 1e-10f, 1e-10f}};
  for (int k = 0; k < 500; ++k) {
    glm::vec3 s(u(rng), u(rng), u(rng));
    if (k % 3 == 0) s[k % 3 + (k / 3) % 2] = 0.0f;  // flat
    if (k % 7 == 0) s.y = s.x;                      // repeated
    scales.push_back(s);
  }
  int flat = 0;
  for (std::size_t k = 0; k < scales.size(); ++k) {
    const glm::quat q = k % 5 == 0 ? glm::quat(1.0f, 0.0f, 0.0f, 0.0f) : randomRotation(rng);
    const glm::dmat3 sigma = splatMoments(glm::vec3(0.0f), scales[k], q, 1.0f).covariance;
    const double norm = maxAbs(sigma);
    // The double decomposition: V diag V^T, V a proper rotation, values descending.
    const SymmetricEigen e = symmetricEigen(sigma);
    glm::dmat3 d(0.0);
    for (int c = 0; c < 3; ++c) d[c][c] = e.values[c];
    CHECK(maxAbsDifference(e.vectors * d * glm::transpose(e.vectors), sigma) <= 1e-12 * norm);
    CHECK(glm::determinant(e.vectors) == Approx(1.0).epsilon(1e-12));
    CHECK(maxAbsDifference(glm::transpose(e.vectors) * e.vectors, glm::dmat3(1.0)) < 1e-12);
    CHECK(e.values[0] >= e.values[1]);
    CHECK(e.values[1] >= e.values[2]);
    // Through the model's float scale + rotation.
    glm::vec3 scale;
    glm::quat rotation;
    covarianceToScaleRotation(sigma, scale, rotation);
    const glm::dmat3 back(covariance(scale, rotation));
    CHECK(maxAbsDifference(back, sigma) <= 1e-5 * norm);
    CHECK(scale.x >= scale.y);
    CHECK(scale.y >= scale.z);
    if (scales[k].x == 0.0f || scales[k].y == 0.0f || scales[k].z == 0.0f) {
      ++flat;
      CHECK(scale.z <= 1e-3f * std::max(scale.x, 1e-30f));
    }
  }
  CHECK(flat > 100);
}

TEST_CASE("the tree's shape: a permutation of the splats, nested boxes, bounded fan-out",
          "[splats][lod]") {
  const GaussianCloud cloud = sceneCloud(5000, 21);
  for (const int branching : {2, 4, 8}) {
    for (const int leafSize : {1, 4, 16}) {
      CAPTURE(branching, leafSize);
      const LodTree tree = buildLodTree(cloud, {.branching = branching, .leafSize = leafSize});
      REQUIRE(tree.splatCount == cloud.size());
      std::vector<std::uint32_t> sorted = tree.leafSplats;
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::uint32_t> identity(cloud.size());
      std::iota(identity.begin(), identity.end(), 0u);
      CHECK(sorted == identity);
      std::size_t merged = 0;
      bool fanOut = true, nested = true, inside = true, sized = true;
      for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
        const LodNode& node = tree.nodes[i];
        sized = sized && node.size == (node.gaussian == LodNode::kNone
                                           ? 0.0f
                                           : 2.0f * tree.merged.scales[node.gaussian].x);
        if (node.gaussian != LodNode::kNone) {
          ++merged;
          const glm::vec3 p = tree.merged.positions[node.gaussian];
          inside = inside && glm::all(glm::greaterThanEqual(p, node.boundsMin - 1e-5f)) &&
                   glm::all(glm::lessThanEqual(p, node.boundsMax + 1e-5f));
        }
        if (node.isLeaf()) {
          fanOut = fanOut && node.count >= 1 && node.count <= leafSize &&
                   (node.count == 1) == (node.gaussian == LodNode::kNone);
          continue;
        }
        fanOut = fanOut && node.count >= 2 && node.count <= branching && node.first > i;
        for (std::uint32_t k = 0; k < node.count; ++k) {
          const LodNode& child = tree.nodes[node.first + k];
          nested = nested && glm::all(glm::greaterThanEqual(child.boundsMin, node.boundsMin)) &&
                   glm::all(glm::lessThanEqual(child.boundsMax, node.boundsMax));
        }
      }
      CHECK(fanOut);
      CHECK(nested);
      CHECK(inside);
      CHECK(sized);
      CHECK(merged == tree.merged.size());
      CHECK(tree.mergedCoverage.size() == merged);
      CHECK(tree.depth > 0);
    }
  }
}

TEST_CASE("a far cut is small, a near one with an unbounded budget is every original splat",
          "[splats][lod]") {
  // Surfaces: at 12 box diagonals (512 pixels, 60 degrees) at most 5% of the splats.
  const GaussianCloud cloud = sceneCloud(100000, 7, 1.0);
  const LodTree tree = buildLodTree(cloud);
  const auto splatsOf = splatsOfMerged(tree);

  const LodCut far = selectCut(tree, viewAt(12.0).cut, cloud.size());
  CHECK(far.size() > 0);
  CHECK(far.size() <= cloud.size() / 20);
  CHECK(coversOnce(tree, far, splatsOf));

  // A volume of haze merges in depth too, so it needs about twice the distance for as few
  // (docs/splats-lod.md): at 24 diagonals at most 5%.
  const GaussianCloud haze = hazeCloud(100000, 17);
  const LodTree hazeTree = buildLodTree(haze);
  CHECK(selectCut(hazeTree, viewAt(24.0).cut, haze.size()).size() <= haze.size() / 20);
  CHECK(selectCut(hazeTree, viewAt(12.0).cut, haze.size()).size() <= haze.size() / 2);

  const LodCut middle = selectCut(tree, viewAt(2.0).cut, cloud.size());
  CHECK(middle.size() > far.size());
  CHECK(coversOnce(tree, middle, splatsOf));

  // Near (the whole box in a 90-degree view from one diagonal), fine threshold: every
  // node is refined down to the original splats.
  const LodCut near = selectCut(tree, viewAt(1.0, 4096, glm::radians(90.0f), 0.5f).cut,
                                std::numeric_limits<std::size_t>::max());
  CHECK(near.merged.empty());
  std::vector<std::uint32_t> sorted = near.originals;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::uint32_t> identity(cloud.size());
  std::iota(identity.begin(), identity.end(), 0u);
  CHECK(sorted == identity);

  // A negative threshold without culling refines everything, wherever the camera is.
  CutView all = viewAt(50.0).cut;
  all.planeCount = 0;
  all.pixelThreshold = -1.0f;
  const LodCut every = selectCut(tree, all, cloud.size());
  CHECK(every.merged.empty());
  CHECK(every.originals.size() == cloud.size());
}

TEST_CASE("a cut never exceeds its budget and always covers every splat once", "[splats][lod]") {
  const GaussianCloud cloud = sceneCloud(20000, 8);
  const LodTree tree = buildLodTree(cloud, {.branching = 8, .leafSize = 6});
  const auto splatsOf = splatsOfMerged(tree);
  CHECK(selectCut(tree, viewAt(1.0).cut, 0).size() == 0);
  for (const double distance : {0.3, 1.0, 4.0}) {
    std::size_t previous = 0;
    for (const std::size_t budget : {1u, 2u, 3u, 7u, 8u, 9u, 100u, 1000u, 4999u, 20000u}) {
      CAPTURE(distance, budget);
      const LodCut cut =
          selectCut(tree, viewAt(distance, 1024, glm::radians(60.0f), 0.5f).cut, budget);
      CHECK(cut.size() <= budget);
      CHECK(cut.size() >= previous);  // a best-first prefix grows with the budget
      CHECK(coversOnce(tree, cut, splatsOf));
      previous = cut.size();
    }
  }
}

TEST_CASE("a cut the budget does not bind is the same whichever way it is found", "[splats][lod]") {
  // The depth-first cut (budget not binding) against the best-first one: at a budget of
  // exactly its size, and at one less, where the best-first order must decide.
  const GaussianCloud cloud = sceneCloud(20000, 8);
  const LodTree tree = buildLodTree(cloud, {.branching = 8, .leafSize = 6});
  const auto splatsOf = splatsOfMerged(tree);
  const auto sortedCut = [](LodCut c) {
    std::sort(c.originals.begin(), c.originals.end());
    std::sort(c.merged.begin(), c.merged.end());
    return c;
  };
  // The reference: every node refined that is not one splat, not wholly outside a frustum
  // plane and over the threshold on screen, recursively.
  const auto reference = [&tree](const CutView& view) {
    LodCut c;
    const auto outside = [&view](const LodNode& n) {
      for (int k = 0; k < view.planeCount; ++k) {
        const glm::vec4& p = view.planes[static_cast<std::size_t>(k)];
        const glm::vec3 corner(p.x >= 0.0f ? n.boundsMax.x : n.boundsMin.x,
                               p.y >= 0.0f ? n.boundsMax.y : n.boundsMin.y,
                               p.z >= 0.0f ? n.boundsMax.z : n.boundsMin.z);
        if (glm::dot(glm::vec3(p), corner) + p.w < 0.0f) return true;
      }
      return false;
    };
    std::function<void(std::uint32_t)> visit = [&](std::uint32_t i) {
      const LodNode& n = tree.nodes[i];
      if ((n.isLeaf() && n.count <= 1) || outside(n) ||
          !(projectedSize(n, view) > view.pixelThreshold)) {
        if (n.gaussian != LodNode::kNone)
          c.merged.push_back(n.gaussian);
        else
          c.originals.push_back(tree.leafSplats[n.first]);
        return;
      }
      for (std::uint32_t k = 0; k < n.count; ++k) {
        if (n.isLeaf())
          c.originals.push_back(tree.leafSplats[n.first + k]);
        else
          visit(n.first + k);
      }
    };
    visit(0);
    return c;
  };
  for (const double distance : {0.3, 1.0, 4.0, 16.0}) {
    CAPTURE(distance);
    const CutView view = viewAt(distance, 1024, glm::radians(60.0f), 0.5f).cut;
    const LodCut all = sortedCut(selectCut(tree, view, cloud.size()));
    REQUIRE(all.size() > 1);
    const LodCut expected = sortedCut(reference(view));
    CHECK(all.originals == expected.originals);
    CHECK(all.merged == expected.merged);
    const LodCut exact = sortedCut(selectCut(tree, view, all.size()));
    CHECK(exact.originals == all.originals);
    CHECK(exact.merged == all.merged);
    CHECK(exact.nodes == all.nodes);
    const LodCut less = selectCut(tree, view, all.size() - 1);
    CHECK(less.size() <= all.size() - 1);
    CHECK(less.size() > 0);
    CHECK(coversOnce(tree, less, splatsOf));
  }
}

TEST_CASE("nodes outside the frustum stay coarse", "[splats][lod]") {
  const GaussianCloud cloud = sceneCloud(20000, 9);
  const LodTree tree = buildLodTree(cloud);
  // The camera 3 diagonals away, looking away from the cloud: nothing to refine.
  TestView away = viewAt(3.0);
  const glm::vec3 eye = away.cut.eye;
  const glm::mat4 view = glm::lookAt(eye, 2.0f * eye, glm::vec3(0.0f, 1.0f, 0.0f));
  const CutView behind = cutViewFromViewProjection(
      glm::perspective(glm::radians(60.0f), 1.0f, 0.01f, 1000.0f) * view, eye, away.focal, 1.5f);
  CHECK(selectCut(tree, behind, cloud.size()).size() == 1);
  // Looking at it, the same camera refines.
  CHECK(selectCut(tree, away.cut, cloud.size()).size() > 100);
}

TEST_CASE("the far cut keeps the haze's opacity x projected area", "[splats][lod]") {
  const GaussianCloud cloud = hazeCloud(100000, 13, 1);
  const LodTree tree = buildLodTree(cloud);
  for (const auto& [far, fraction] : {std::pair{12.0, 0.5}, std::pair{24.0, 0.05}}) {
    const double distance = far;
    CAPTURE(distance);
    const TestView view = viewAt(distance);
    const LodCut cut = selectCut(tree, view.cut, cloud.size());
    GaussianCloud drawn;
    assembleCut(tree, cloud, cut, drawn);
    REQUIRE(drawn.size() == cut.size());
    CHECK(drawn.shDegree == 1);
    CHECK(drawn.shRest.size() == 3 * drawn.size());
    CHECK(static_cast<double>(cut.size()) < fraction * static_cast<double>(cloud.size()));
    const double full = projectedCoverage(cloud, view);
    const double merged = projectedCoverage(drawn, view);
    CHECK(merged / full > 0.8);
    CHECK(merged / full < 1.25);
  }
}

TEST_CASE("cut views from a ProjectionView and from a view-projection agree", "[splats][lod]") {
  const float fovY = glm::radians(50.0f);
  const int width = 640, height = 480;
  const glm::vec3 eye(3.0f, 1.0f, 4.0f);
  const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f), glm::vec3(0.0f, 1.0f, 0.0f));
  const float focal = 0.5f * static_cast<float>(height) / std::tan(0.5f * fovY);
  ProjectionView projection;
  projection.modelView = view;
  projection.fx = projection.fy = focal;
  projection.cx = 0.5f * static_cast<float>(width);
  projection.cy = 0.5f * static_cast<float>(height);
  projection.width = width;
  projection.height = height;
  projection.nearClip = 0.1f;
  projection.farClip = 100.0f;
  const CutView a = cutViewFromProjection(projection, 1.5f);
  const CutView b = cutViewFromViewProjection(
      glm::perspective(fovY, static_cast<float>(width) / static_cast<float>(height), 0.1f, 100.0f) *
          view,
      eye, focal, 1.5f);
  CHECK(glm::length(a.eye - eye) < 1e-5f);
  CHECK(a.planeCount == 6);
  CHECK(b.planeCount == 6);
  CHECK(a.focalPixels == Approx(focal));
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-8.0f, 8.0f);
  int agree = 0, inside = 0;
  const auto in = [](const CutView& v, const glm::vec3& p) {
    for (int k = 0; k < v.planeCount; ++k)
      if (glm::dot(glm::vec3(v.planes[static_cast<std::size_t>(k)]), p) +
              v.planes[static_cast<std::size_t>(k)].w <
          0.0f)
        return false;
    return true;
  };
  for (int k = 0; k < 20000; ++k) {
    const glm::vec3 p(u(rng), u(rng), u(rng));
    agree += in(a, p) == in(b, p);
    inside += in(a, p);
  }
  CHECK(agree >= 19990);  // only points within rounding of a plane may differ
  CHECK(inside > 500);
}

TEST_CASE("edge cases: empty, one splat, bad input", "[splats][lod]") {
  GaussianCloud empty;
  const LodTree none = buildLodTree(empty);
  CHECK(none.nodes.empty());
  CHECK(selectCut(none, viewAt(1.0).cut, 100).size() == 0);

  GaussianCloud one;
  one.resize(1);
  const LodTree single = buildLodTree(one);
  REQUIRE(single.nodes.size() == 1);
  CHECK(single.merged.empty());
  const LodCut cut = selectCut(single, viewAt(1.0).cut, 100);
  CHECK(cut.originals == std::vector<std::uint32_t>{0});

  CHECK_THROWS_AS(buildLodTree(one, {.branching = 3, .leafSize = 4}), std::invalid_argument);
  CHECK_THROWS_AS(buildLodTree(one, {.branching = 4, .leafSize = 0}), std::invalid_argument);
  GaussianCloud broken = one;
  broken.opacities.clear();
  CHECK_THROWS_AS(buildLodTree(broken), std::invalid_argument);
  // A cloud grown past the tree's splats (a stream's prefix tree) gives the cut from its
  // prefix; a cloud smaller than the tree's is not its cloud.
  GaussianCloud other = hazeCloud(10, 1);
  GaussianCloud assembled;
  assembleCut(single, other, cut, assembled);
  REQUIRE(assembled.size() == 1);
  CHECK(assembled.positions[0] == other.positions[0]);
  const LodTree ten = buildLodTree(other);
  CHECK_THROWS_AS(assembleCut(ten, one, selectCut(ten, viewAt(1.0).cut, 100), assembled),
                  std::invalid_argument);

  // A non-finite splat does not poison its ancestors; it is still a leaf of its own.
  GaussianCloud haze = hazeCloud(1000, 4);
  haze.positions[17] = glm::vec3(std::nanf(""), 0.0f, 0.0f);
  haze.scales[40] = glm::vec3(std::numeric_limits<float>::infinity());
  const LodTree tree = buildLodTree(haze);
  for (std::size_t g = 0; g < tree.merged.size(); ++g) {
    CHECK(std::isfinite(tree.merged.positions[g].x));
    CHECK(std::isfinite(tree.merged.scales[g].x));
    CHECK(std::isfinite(tree.merged.opacities[g]));
  }
  CutView all = viewAt(1.0).cut;
  all.planeCount = 0;
  all.pixelThreshold = -1.0f;
  CHECK(selectCut(tree, all, 10000).originals.size() == 1000);
}

TEST_CASE("a tree's build stops when it is cancelled", "[splats][lod]") {
  // A session that closes while its stream's tree is building sets the flag
  // (session::StreamingSession's destructor); the build must not run on to its end.
  const GaussianCloud cloud = hazeCloud(20000, 5);
  std::atomic<bool> cancel{true};
  LodTreeOptions options;
  options.cancel = &cancel;
  CHECK_THROWS_AS(buildLodTree(cloud, options), LodTreeCancelled);
  cancel = false;
  const LodTree tree = buildLodTree(cloud, options);
  CHECK(tree.splatCount == cloud.size());
  CHECK(tree.merged.size() > 0);
}
