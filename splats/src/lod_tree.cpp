// The level-of-detail tree of merged Gaussians and its cut (splats/lod_tree.hpp,
// docs/splats-lod.md).
#include "splats/lod_tree.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

namespace gs::splats {

// ---------------------------------------------------------------------------------------
// The merge

double meanProjectedArea(const glm::vec3& scale) {
  const double p = kThomsenExponent;
  const double ap = std::pow(std::abs(static_cast<double>(scale.x)), p);
  const double bp = std::pow(std::abs(static_cast<double>(scale.y)), p);
  const double cp = std::pow(std::abs(static_cast<double>(scale.z)), p);
  const double mean = (ap * bp + ap * cp + bp * cp) / 3.0;
  if (!(mean > 0.0)) return 0.0;  // also NaN
  return std::numbers::pi * std::pow(mean, 1.0 / p);
}

double splatCoverage(const glm::vec3& scale, float opacity) {
  if (!(opacity > 0.0f)) return 0.0;  // also NaN
  return static_cast<double>(std::min(opacity, 1.0f)) * meanProjectedArea(scale);
}

GaussianMoments splatMoments(const glm::vec3& position, const glm::vec3& scale,
                             const glm::quat& rotation, float opacity) {
  GaussianMoments m;
  m.weight = splatCoverage(scale, opacity);
  m.count = 1.0;
  m.mean = glm::dvec3(position);
  glm::dquat q(rotation.w, rotation.x, rotation.y, rotation.z);
  const double length = glm::length(q);
  q = length > 0.0 && std::isfinite(length) ? q / length : glm::dquat(1.0, 0.0, 0.0, 0.0);
  const glm::dmat3 r = glm::mat3_cast(q);
  glm::dmat3 rs;
  for (int c = 0; c < 3; ++c) rs[c] = r[c] * std::abs(static_cast<double>(scale[c]));
  m.covariance = rs * glm::transpose(rs);
  return m;
}

GaussianMoments splatMoments(const GaussianCloud& cloud, std::size_t i) {
  return splatMoments(cloud.positions[i], cloud.scales[i], cloud.rotations[i], cloud.opacities[i]);
}

namespace {

/// The factor of each part in a merge (weight or, when all weights are 0, count, over the
/// total); false when both totals are 0.
bool mergeFactors(std::span<const GaussianMoments> parts, double* factors) {
  double weight = 0.0, count = 0.0;
  for (const GaussianMoments& part : parts) {
    weight += part.weight;
    count += part.count;
  }
  const bool byWeight = weight > 0.0;
  const double total = byWeight ? weight : count;
  if (!(total > 0.0)) return false;
  for (std::size_t k = 0; k < parts.size(); ++k)
    factors[k] = (byWeight ? parts[k].weight : parts[k].count) / total;
  return true;
}

/// mergeMoments with the factors already known.
GaussianMoments mergeWithFactors(std::span<const GaussianMoments> parts, const double* factors) {
  GaussianMoments out;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    out.weight += parts[k].weight;
    out.count += parts[k].count;
    out.mean += factors[k] * parts[k].mean;
  }
  for (std::size_t k = 0; k < parts.size(); ++k) {
    if (factors[k] == 0.0) continue;
    const glm::dvec3 d = parts[k].mean - out.mean;
    out.covariance += factors[k] * (parts[k].covariance + glm::outerProduct(d, d));
  }
  return out;
}

}  // namespace

GaussianMoments mergeMoments(std::span<const GaussianMoments> parts) {
  std::vector<double> factors(parts.size());
  if (!mergeFactors(parts, factors.data())) {
    GaussianMoments out;
    for (const GaussianMoments& part : parts) {
      out.weight += part.weight;
      out.count += part.count;
    }
    return out;
  }
  return mergeWithFactors(parts, factors.data());
}

SymmetricEigen symmetricEigen(const glm::dmat3& m) {
  // a[i][j] is row i, column j of the symmetrised matrix (glm indexes [column][row]).
  double a[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) a[i][j] = 0.5 * (m[j][i] + m[i][j]);
  double v[3][3] = {{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}};
  constexpr int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  // Cyclic Jacobi (Golub and Van Loan, "Matrix Computations", 8.5.2; the update of
  // Numerical Recipes' jacobi): each rotation zeroes a[p][q]; convergence is quadratic, a
  // handful of sweeps reach rounding level.
  for (int sweep = 0; sweep < 50; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-36 * diagonal)) break;  // also off == 0 and NaN
    for (const auto& pair : kPairs) {
      const int p = pair[0], q = pair[1];
      const double apq = a[p][q];
      if (apq == 0.0) continue;
      const double theta = (a[q][q] - a[p][p]) / (2.0 * apq);
      const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::hypot(1.0, theta));
      const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
      a[p][p] -= t * apq;
      a[q][q] += t * apq;
      a[p][q] = a[q][p] = 0.0;
      const int r = 3 - p - q;
      const double arp = a[r][p], arq = a[r][q];
      a[r][p] = a[p][r] = c * arp - s * arq;
      a[r][q] = a[q][r] = s * arp + c * arq;
      for (int k = 0; k < 3; ++k) {
        const double vkp = v[k][p], vkq = v[k][q];
        v[k][p] = c * vkp - s * vkq;
        v[k][q] = s * vkp + c * vkq;
      }
    }
  }
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int x, int y) { return a[x][x] > a[y][y]; });
  SymmetricEigen out;
  for (int c = 0; c < 3; ++c) {
    out.values[c] = a[order[c]][order[c]];
    for (int k = 0; k < 3; ++k) out.vectors[c][k] = v[k][order[c]];
  }
  if (glm::determinant(out.vectors) < 0.0) out.vectors[2] = -out.vectors[2];
  return out;
}

void covarianceToScaleRotation(const glm::dmat3& covariance, glm::vec3& scale,
                               glm::quat& rotation) {
  const SymmetricEigen eigen = symmetricEigen(covariance);
  for (int c = 0; c < 3; ++c)
    scale[c] = static_cast<float>(std::sqrt(std::max(eigen.values[c], 0.0)));
  glm::dquat q = glm::quat_cast(eigen.vectors);
  const double length = glm::length(q);
  q = length > 0.0 && std::isfinite(length) ? q / length : glm::dquat(1.0, 0.0, 0.0, 0.0);
  rotation = glm::quat(static_cast<float>(q.w), static_cast<float>(q.x), static_cast<float>(q.y),
                       static_cast<float>(q.z));
}

float mergedOpacity(double weight, const glm::vec3& scale) {
  if (!(weight > 0.0)) return 0.0f;
  const double area = meanProjectedArea(scale);
  if (!(area > 0.0)) return 1.0f;  // coverage without area: only from rounding
  return static_cast<float>(std::min(1.0, weight / area));
}

// ---------------------------------------------------------------------------------------
// The tree

static_assert(sizeof(LodNode) == 40, "LodNode is documented as 40 bytes");

std::size_t LodTree::memoryBytes() const {
  return nodes.capacity() * sizeof(LodNode) + leafSplats.capacity() * sizeof(std::uint32_t) +
         merged.positions.capacity() * sizeof(glm::vec3) +
         merged.scales.capacity() * sizeof(glm::vec3) +
         merged.rotations.capacity() * sizeof(glm::quat) +
         merged.opacities.capacity() * sizeof(float) + merged.shDc.capacity() * sizeof(glm::vec3) +
         merged.shRest.capacity() * sizeof(glm::vec3) + mergedCoverage.capacity() * sizeof(float);
}

namespace {

struct Item {
  glm::vec3 position;
  std::uint32_t index;
};

struct Range {
  std::uint32_t begin, end;
  std::uint32_t size() const { return end - begin; }
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finiteSplat(const GaussianCloud& cloud, std::size_t i) {
  const glm::quat& q = cloud.rotations[i];
  return finite(cloud.positions[i]) && finite(cloud.scales[i]) && std::isfinite(q.w) &&
         std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z) &&
         std::isfinite(cloud.opacities[i]);
}

/// Splits items[range] (more than leafSize of them) by the centres along the longest axis
/// of their box, at the median rounded to whole leaves (the left part a multiple of
/// leafSize, so that leaves are full); returns the split.
std::uint32_t medianSplit(std::vector<Item>& items, Range range, std::uint32_t leafSize) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::uint32_t k = range.begin; k < range.end; ++k) {
    lo = glm::min(lo, items[k].position);
    hi = glm::max(hi, items[k].position);
  }
  const glm::vec3 extent = hi - lo;
  const int axis =
      extent.x >= extent.y ? (extent.x >= extent.z ? 0 : 2) : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t leaves = (range.size() + leafSize - 1) / leafSize;  // >= 2
  const std::uint32_t middle = range.begin + leaves / 2 * leafSize;
  std::nth_element(
      items.begin() + range.begin, items.begin() + middle, items.begin() + range.end,
      [axis](const Item& x, const Item& y) { return x.position[axis] < y.position[axis]; });
  return middle;
}

void checkCloud(const GaussianCloud& cloud) {
  const std::size_t n = cloud.size();
  if (cloud.shDegree < 0 || cloud.shDegree > kMaxShDegree)
    throw std::invalid_argument("buildLodTree: SH degree " + std::to_string(cloud.shDegree) +
                                " is not 0..3");
  if (cloud.scales.size() != n || cloud.rotations.size() != n || cloud.opacities.size() != n ||
      cloud.shDc.size() != n ||
      cloud.shRest.size() != n * static_cast<std::size_t>(cloud.shRestPerSplat()))
    throw std::invalid_argument("buildLodTree: the cloud's arrays disagree in size");
  if (n >= std::size_t{LodNode::kNone})
    throw std::length_error("buildLodTree: " + std::to_string(n) +
                            " splats; at most 2^32 - 2 are supported");
}

/// Adds factor x the SH coefficients of splat `i` of `from` to Gaussian `g` of `to`.
void accumulateSh(GaussianCloud& to, std::size_t g, const GaussianCloud& from, std::size_t i,
                  float factor) {
  to.shDc[g] += factor * from.shDc[i];
  const std::size_t rest = static_cast<std::size_t>(to.shRestPerSplat());
  for (std::size_t k = 0; k < rest; ++k)
    to.shRest[g * rest + k] += factor * from.shRest[i * rest + k];
}

}  // namespace

LodTree buildLodTree(const GaussianCloud& cloud, const LodTreeOptions& options) {
  if (options.branching != 2 && options.branching != 4 && options.branching != 8)
    throw std::invalid_argument("buildLodTree: branching " + std::to_string(options.branching) +
                                " is not 2, 4 or 8");
  if (options.leafSize < 1 || options.leafSize > 64)
    throw std::invalid_argument("buildLodTree: leaf size " + std::to_string(options.leafSize) +
                                " is not 1..64");
  checkCloud(cloud);
  LodTree tree;
  tree.splatCount = cloud.size();
  tree.merged.shDegree = cloud.shDegree;
  tree.merged.colorSpace = cloud.colorSpace;
  tree.merged.kernel = cloud.kernel;
  const std::uint32_t n = static_cast<std::uint32_t>(cloud.size());
  if (n == 0) return tree;

  // Topology: breadth first, each node's range of items split by up to log2(branching)
  // levels of median splits into its children.
  std::vector<Item> items(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    const glm::vec3& p = cloud.positions[i];
    items[i] = {finite(p) ? p : glm::vec3(0.0f), i};
  }
  const std::uint32_t leafSize = static_cast<std::uint32_t>(options.leafSize);
  const int splits = std::countr_zero(static_cast<unsigned>(options.branching));
  std::vector<Range> ranges;
  ranges.reserve(n / std::max<std::uint32_t>(1, leafSize / 2) + 16);
  tree.nodes.reserve(ranges.capacity());
  tree.nodes.emplace_back();
  ranges.push_back({0, n});
  std::size_t levelEnd = 1;
  const auto checkCancel = [&options](std::size_t node) {
    if (node % 4096 == 0 && options.cancel != nullptr &&
        options.cancel->load(std::memory_order_relaxed))
      throw LodTreeCancelled();
  };
  for (std::size_t i = 0; i < tree.nodes.size(); ++i) {
    checkCancel(i);
    if (i == levelEnd) {
      ++tree.depth;
      levelEnd = tree.nodes.size();
    }
    const Range range = ranges[i];
    if (range.size() <= leafSize) {
      tree.nodes[i].leaf = 1;
      tree.nodes[i].first = range.begin;
      tree.nodes[i].count = static_cast<std::uint16_t>(range.size());
      continue;
    }
    Range parts[8] = {range};
    int partCount = 1;
    for (int s = 0; s < splits; ++s) {
      Range next[8];
      int nextCount = 0;
      for (int k = 0; k < partCount; ++k) {
        if (parts[k].size() > leafSize) {
          const std::uint32_t middle = medianSplit(items, parts[k], leafSize);
          next[nextCount++] = {parts[k].begin, middle};
          next[nextCount++] = {middle, parts[k].end};
        } else {
          next[nextCount++] = parts[k];
        }
      }
      std::copy(next, next + nextCount, parts);
      partCount = nextCount;
    }
    tree.nodes[i].first = static_cast<std::uint32_t>(tree.nodes.size());
    tree.nodes[i].count = static_cast<std::uint16_t>(partCount);
    for (int k = 0; k < partCount; ++k) {
      tree.nodes.emplace_back();
      ranges.push_back(parts[k]);
    }
  }
  ranges = {};
  tree.nodes.shrink_to_fit();
  tree.leafSplats.resize(n);
  for (std::uint32_t k = 0; k < n; ++k) tree.leafSplats[k] = items[k].index;
  items = {};

  // Merged Gaussians in node order, for every node with more than one splat below.
  std::uint32_t mergedCount = 0;
  for (LodNode& node : tree.nodes)
    if (!node.isLeaf() || node.count > 1) node.gaussian = mergedCount++;
  tree.merged.resize(mergedCount);
  std::fill(tree.merged.shDc.begin(), tree.merged.shDc.end(), glm::vec3(0.0f));
  tree.mergedCoverage.resize(mergedCount);

  // Bottom up: moments, box and merged Gaussian of each node from its children's.
  std::vector<GaussianMoments> moments(tree.nodes.size());
  GaussianMoments leafParts[64];
  double factors[64];
  const glm::vec3 emptyLo(std::numeric_limits<float>::infinity());
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    checkCancel(i);
    LodNode& node = tree.nodes[i];
    glm::vec3 lo = emptyLo, hi = -emptyLo;
    std::span<const GaussianMoments> parts;
    if (node.isLeaf()) {
      for (std::uint32_t k = 0; k < node.count; ++k) {
        const std::uint32_t s = tree.leafSplats[node.first + k];
        if (!finiteSplat(cloud, s)) {
          leafParts[k] = GaussianMoments{};  // stands for nothing in its ancestors
          continue;
        }
        leafParts[k] = splatMoments(cloud, s);
        const glm::dmat3& c = leafParts[k].covariance;
        const glm::vec3 half(3.0 * glm::sqrt(glm::dvec3(c[0][0], c[1][1], c[2][2])));
        lo = glm::min(lo, cloud.positions[s] - half);
        hi = glm::max(hi, cloud.positions[s] + half);
      }
      parts = std::span<const GaussianMoments>(leafParts, node.count);
    } else {
      for (std::uint32_t k = 0; k < node.count; ++k) {
        const LodNode& child = tree.nodes[node.first + k];
        if (!(child.boundsMin.x <= child.boundsMax.x)) continue;  // empty
        lo = glm::min(lo, child.boundsMin);
        hi = glm::max(hi, child.boundsMax);
      }
      parts = std::span<const GaussianMoments>(moments.data() + node.first, node.count);
    }
    const bool merged = mergeFactors(parts, factors);
    if (merged) {
      moments[i] = mergeWithFactors(parts, factors);
    } else {
      moments[i] = GaussianMoments{};
      std::fill(factors, factors + parts.size(), 0.0);
    }
    if (lo.x <= hi.x) {
      node.boundsMin = lo;
      node.boundsMax = hi;
    } else {  // no finite splat below: a point box at its (zero) mean
      node.boundsMin = node.boundsMax = glm::vec3(moments[i].mean);
    }
    if (node.gaussian == LodNode::kNone) continue;  // a single splat: size 0

    const std::size_t g = node.gaussian;
    GaussianCloud& out = tree.merged;
    out.positions[g] = glm::vec3(moments[i].mean);
    covarianceToScaleRotation(moments[i].covariance, out.scales[g], out.rotations[g]);
    out.opacities[g] = mergedOpacity(moments[i].weight, out.scales[g]);
    node.size = 2.0f * out.scales[g].x;  // scales descend
    tree.mergedCoverage[g] = static_cast<float>(moments[i].weight);
    if (node.isLeaf()) {
      for (std::uint32_t k = 0; k < node.count; ++k)
        if (factors[k] != 0.0)
          accumulateSh(out, g, cloud, tree.leafSplats[node.first + k],
                       static_cast<float>(factors[k]));
    } else {
      for (std::uint32_t k = 0; k < node.count; ++k) {
        if (factors[k] == 0.0) continue;
        const LodNode& child = tree.nodes[node.first + k];
        if (child.gaussian != LodNode::kNone)
          accumulateSh(out, g, out, child.gaussian, static_cast<float>(factors[k]));
        else
          accumulateSh(out, g, cloud, tree.leafSplats[child.first], static_cast<float>(factors[k]));
      }
    }
  }
  return tree;
}

// ---------------------------------------------------------------------------------------
// The cut

namespace {

glm::vec4 normalisedPlane(const glm::vec4& plane) {
  const float length = glm::length(glm::vec3(plane));
  return plane / length;
}

/// Whether `plane` is usable: a finite, non-zero normal.
bool usablePlane(const glm::vec4& plane) {
  const float length = glm::length(glm::vec3(plane));
  return length > 0.0f && std::isfinite(length) && std::isfinite(plane.w);
}

bool outsideFrustum(const LodNode& node, const CutView& view) {
  for (int k = 0; k < view.planeCount; ++k) {
    const glm::vec4& plane = view.planes[static_cast<std::size_t>(k)];
    // The box corner farthest along the plane's normal.
    const glm::vec3 corner(plane.x >= 0.0f ? node.boundsMax.x : node.boundsMin.x,
                           plane.y >= 0.0f ? node.boundsMax.y : node.boundsMin.y,
                           plane.z >= 0.0f ? node.boundsMax.z : node.boundsMin.z);
    if (glm::dot(glm::vec3(plane), corner) + plane.w < 0.0f) return true;
  }
  return false;
}

}  // namespace

CutView cutViewFromProjection(const ProjectionView& view, float pixelThreshold) {
  CutView out;
  out.pixelThreshold = pixelThreshold;
  out.focalPixels = std::max(view.fx, view.fy);
  const glm::mat4 toCloud = glm::inverse(view.modelView);
  out.eye = glm::vec3(toCloud[3]) / toCloud[3][3];
  const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
  // Eye space (looking down -Z): pixel x = cx + fx x / -z, inside when 0 <= x <= width.
  const glm::vec4 eyePlanes[6] = {
      {view.fx, 0.0f, -view.cx, 0.0f},     {-view.fx, 0.0f, -(w - view.cx), 0.0f},
      {0.0f, view.fy, -view.cy, 0.0f},     {0.0f, -view.fy, -(h - view.cy), 0.0f},
      {0.0f, 0.0f, -1.0f, -view.nearClip}, {0.0f, 0.0f, 1.0f, view.farClip},
  };
  const glm::mat4 transposed = glm::transpose(view.modelView);
  for (int k = 0; k < 6; ++k) {
    if (k == 5 && !(view.farClip <= 1e29f)) continue;
    const glm::vec4 plane = transposed * eyePlanes[k];
    if (usablePlane(plane))
      out.planes[static_cast<std::size_t>(out.planeCount++)] = normalisedPlane(plane);
  }
  return out;
}

CutView cutViewFromViewProjection(const glm::mat4& viewProjection, const glm::vec3& eye,
                                  float focalPixels, float pixelThreshold) {
  CutView out;
  out.eye = eye;
  out.focalPixels = focalPixels;
  out.pixelThreshold = pixelThreshold;
  const glm::mat4 rows = glm::transpose(viewProjection);  // rows[i] is row i
  const glm::vec4 planes[6] = {rows[3] + rows[0], rows[3] - rows[0], rows[3] + rows[1],
                               rows[3] - rows[1], rows[3] + rows[2], rows[3] - rows[2]};
  for (const glm::vec4& plane : planes)
    if (usablePlane(plane))
      out.planes[static_cast<std::size_t>(out.planeCount++)] = normalisedPlane(plane);
  return out;
}

float projectedSize(const LodNode& node, const CutView& view) {
  const glm::vec3 gap =
      glm::max(glm::max(node.boundsMin - view.eye, view.eye - node.boundsMax), glm::vec3(0.0f));
  const float distance = glm::length(gap);
  if (distance == 0.0f) return std::numeric_limits<float>::infinity();
  return node.size * view.focalPixels / distance;  // NaN stays NaN
}

namespace {

/// Whether selectCut refines `node`: not a single splat, not wholly outside the frustum,
/// and bigger than the threshold on screen (false for a NaN size).
bool refines(const LodNode& node, const CutView& view) {
  return (!node.isLeaf() || node.count > 1) && !outsideFrustum(node, view) &&
         projectedSize(node, view) > view.pixelThreshold;
}

/// Adds `node` to `cut` unrefined: its merged Gaussian, or a one-splat leaf's splat.
void addCoarse(const LodTree& tree, const LodNode& node, LodCut& cut) {
  ++cut.nodes;
  if (node.gaussian != LodNode::kNone)
    cut.merged.push_back(node.gaussian);
  else
    cut.originals.push_back(tree.leafSplats[node.first]);
}

/// Adds a refined leaf's original splats to `cut`.
void addLeafSplats(const LodTree& tree, const LodNode& leaf, LodCut& cut) {
  ++cut.nodes;
  cut.originals.insert(cut.originals.end(), tree.leafSplats.begin() + leaf.first,
                       tree.leafSplats.begin() + leaf.first + leaf.count);
}

/// selectCut's cut when the budget does not bind: every node above the threshold refined,
/// depth first with a stack (no priority queue: the order of refinement cannot change a
/// cut that refines all it may). False, with `cut` partial, as soon as the cut would pass
/// `budget`: then the best-first order decides and selectCut starts again.
bool unboundedCut(const LodTree& tree, const CutView& view, std::size_t budget, LodCut& cut) {
  std::vector<std::uint32_t> stack{0};
  std::size_t cost = 1;
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    const LodNode& node = tree.nodes[i];
    if (!refines(node, view)) {
      addCoarse(tree, node, cut);
      continue;
    }
    cost += static_cast<std::size_t>(node.count) - 1;
    if (cost > budget) return false;
    if (node.isLeaf()) {
      addLeafSplats(tree, node, cut);
    } else {
      for (std::uint32_t k = node.count; k-- > 0;) stack.push_back(node.first + k);
    }
  }
  return true;
}

}  // namespace

LodCut selectCut(const LodTree& tree, const CutView& view, std::size_t budget) {
  LodCut cut;
  if (tree.nodes.empty() || budget == 0) return cut;
  if (unboundedCut(tree, view, budget, cut)) return cut;
  cut = {};
  struct Entry {
    float error;
    std::uint32_t node;
    // Largest error first; on a tie the lower node index (the coarser, breadth first).
    bool operator<(const Entry& other) const {
      return error < other.error || (error == other.error && node > other.node);
    }
  };
  std::priority_queue<Entry> queue;
  const auto consider = [&](std::uint32_t i) {
    const LodNode& node = tree.nodes[i];
    if (refines(node, view))
      queue.push({projectedSize(node, view), i});
    else
      addCoarse(tree, node, cut);
  };
  std::size_t cost = 1;
  consider(0);
  while (!queue.empty()) {
    const LodNode& node = tree.nodes[queue.top().node];
    const std::size_t extra = static_cast<std::size_t>(node.count) - 1;
    if (cost + extra > budget) break;
    queue.pop();
    cost += extra;
    if (node.isLeaf()) {
      addLeafSplats(tree, node, cut);
    } else {
      for (std::uint32_t k = 0; k < node.count; ++k) consider(node.first + k);
    }
  }
  for (; !queue.empty(); queue.pop()) addCoarse(tree, tree.nodes[queue.top().node], cut);
  return cut;
}

void assembleCut(const LodTree& tree, const GaussianCloud& cloud, const LodCut& cut,
                 GaussianCloud& out) {
  if (cloud.size() < tree.splatCount)
    throw std::invalid_argument("assembleCut: the cloud has " + std::to_string(cloud.size()) +
                                " splats, the tree was built from " +
                                std::to_string(tree.splatCount));
  out.shDegree = cloud.shDegree;
  out.colorSpace = cloud.colorSpace;
  out.kernel = cloud.kernel;
  const std::size_t total = cut.size();
  const std::size_t rest = static_cast<std::size_t>(cloud.shRestPerSplat());
  out.positions.resize(total);
  out.scales.resize(total);
  out.rotations.resize(total);
  out.opacities.resize(total);
  out.shDc.resize(total);
  out.shRest.resize(total * rest);
  std::size_t k = 0;
  const auto copy = [&](const GaussianCloud& from, std::size_t i) {
    out.positions[k] = from.positions[i];
    out.scales[k] = from.scales[i];
    out.rotations[k] = from.rotations[i];
    out.opacities[k] = from.opacities[i];
    out.shDc[k] = from.shDc[i];
    std::copy_n(from.shRest.begin() + static_cast<std::ptrdiff_t>(i * rest), rest,
                out.shRest.begin() + static_cast<std::ptrdiff_t>(k * rest));
    ++k;
  };
  for (const std::uint32_t i : cut.originals) copy(cloud, i);
  for (const std::uint32_t i : cut.merged) copy(tree.merged, i);
}

}  // namespace gs::splats
