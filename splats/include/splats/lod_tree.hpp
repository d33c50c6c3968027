// A level-of-detail tree of merged Gaussians (docs/splats-lod.md): a bounding-volume
// hierarchy over a cloud's splats whose every node with more than one splat below holds
// ONE Gaussian moment-matched from them (Kerbl et al. 2024, "A Hierarchical 3D Gaussian
// Representation for Real-Time Rendering of Very Large Datasets", section 4.2), and the
// cut of that tree for one view: the coarsest nodes whose screen-space size is within a
// pixel threshold, under a budget of splats.
//
// Pure computation: no OpenGL, no files. Units: scene units (metres) for positions and
// sizes, pixels on screen, radians for angles.
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "splats/gaussian.hpp"

namespace gs::splats {

// ---------------------------------------------------------------------------------------
// The merge (moment matching)

/// The exponent of Knud Thomsen's approximation of an ellipsoid's surface area
/// S ~ 4 pi ((a^p b^p + a^p c^p + b^p c^p) / 3)^(1/p), relative error at most 1.061%
/// (exact for spheres; 1% high for flat discs).
inline constexpr double kThomsenExponent = 1.6075;

/// The area a Gaussian of standard deviations `scale` (scene units, >= 0) shows on
/// average over all view directions: the mean orthographic projected area of its 1-sigma
/// ellipsoid, which is a quarter of that ellipsoid's surface (Cauchy's formula), from
/// Thomsen's approximation. pi s^2 for a sphere of radius s, ~ pi a b / 2 for a flat
/// disc (scale (a, b, 0)), 0 when two scales are 0. Scene units squared.
double meanProjectedArea(const glm::vec3& scale);

/// A splat's coverage: opacity (0..1) times meanProjectedArea(scale). The integral of
/// its 2D footprint's opacity over an orthographic image plane is 2 pi alpha
/// sqrt(det Sigma'), whose mean over view directions is 2 x coverage; the merge keeps
/// the sum of its members' coverage (see mergedOpacity). Scene units squared, >= 0.
double splatCoverage(const glm::vec3& scale, float opacity);

/// The first two moments of a Gaussian or of a weighted mixture of Gaussians, in double.
struct GaussianMoments {
  /// The mixture weight: the summed coverage (splatCoverage) of the splats it stands
  /// for, scene units squared, >= 0.
  double weight = 0.0;
  /// Splats it stands for (1 for one splat). Weights the merge instead of `weight` when
  /// every member's weight is 0 (all transparent or all point-like).
  double count = 0.0;
  /// Mean, scene units.
  glm::dvec3 mean{0.0};
  /// Covariance (symmetric, positive semi-definite), scene units squared.
  glm::dmat3 covariance{0.0};
};

/// The moments of one splat: weight = splatCoverage, count = 1, mean = position,
/// covariance = R S S^T R^T (the rotation normalised first).
GaussianMoments splatMoments(const glm::vec3& position, const glm::vec3& scale,
                             const glm::quat& rotation, float opacity);
/// Same, for splat `i` of `cloud` (i < cloud.size()).
GaussianMoments splatMoments(const GaussianCloud& cloud, std::size_t i);

/// Moment matching of a mixture (Kerbl et al. 2024, eq. 6-7; the law of total variance):
/// with w_i = parts[i].weight and W = sum w_i,
///   mean       mu    = sum w_i mu_i / W
///   covariance Sigma = sum w_i (Sigma_i + d_i d_i^T) / W,  d_i = mu_i - mu,
/// weight = W and count = sum of counts. When W is 0 the counts weight the mean and
/// covariance instead (W stays 0). Associative: merging merged parts equals merging all
/// their splats at once. An empty span gives all zeros.
GaussianMoments mergeMoments(std::span<const GaussianMoments> parts);

/// The eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations, robust to
/// repeated and zero eigenvalues: `values` in descending order, `vectors` the matching
/// unit eigenvectors as columns, a proper rotation (determinant +1). m = V diag(values) V^T
/// to within ~1e-15 relative to m's largest entry. Non-finite input gives non-finite output.
struct SymmetricEigen {
  glm::dvec3 values{0.0};
  glm::dmat3 vectors{1.0};
};
SymmetricEigen symmetricEigen(const glm::dmat3& m);

/// A covariance (symmetric, positive semi-definite; scene units squared) as the model's
/// scale + rotation: scale = sqrt of the eigenvalues (descending, negative rounding noise
/// clamped to 0, so a flat covariance gives a 0 scale) and rotation = the eigenvectors'
/// proper rotation, so that covariance(scale, rotation) reproduces it.
void covarianceToScaleRotation(const glm::dmat3& covariance, glm::vec3& scale, glm::quat& rotation);

/// The opacity of a merged Gaussian of standard deviations `scale` standing for summed
/// coverage `weight`: min(1, weight / meanProjectedArea(scale)), so that its own coverage
/// equals its members' (mass-conserving, as Kerbl et al. 2024's ClusterMerger and
/// splat-transform's --decimate; the clamp to 1 is splat-transform's). 0 when weight is 0.
/// Many weak splats merge into one wide, faint Gaussian of the same coverage: the haze keeps
/// its integrated opacity.
float mergedOpacity(double weight, const glm::vec3& scale);

// ---------------------------------------------------------------------------------------
// The tree

/// How buildLodTree shapes the tree.
struct LodTreeOptions {
  /// Children of an interior node: 2, 4 or 8 (1, 2 or 3 levels of median splits per node;
  /// fewer where a part already fits in a leaf).
  int branching = 4;
  /// The most splats a leaf holds, 1..64.
  int leafSize = 4;
  /// When not null: read every 4,096 nodes, and once true the build stops by throwing
  /// LodTreeCancelled (a session closed while its stream's tree was building).
  const std::atomic<bool>* cancel = nullptr;
};

/// What buildLodTree throws when LodTreeOptions::cancel became true.
struct LodTreeCancelled : std::runtime_error {
  LodTreeCancelled() : std::runtime_error("buildLodTree: cancelled") {}
};

/// One node of a LodTree (40 bytes).
struct LodNode {
  /// Means "no merged Gaussian": a leaf with one splat, which stands for itself.
  static constexpr std::uint32_t kNone = 0xffffffffu;
  /// The axis-aligned box of the 3-sigma ellipsoids of every splat below, cloud coordinates.
  glm::vec3 boundsMin{0.0f};
  glm::vec3 boundsMax{0.0f};
  /// The node's granularity for the screen-space error: the diameter of its merged
  /// Gaussian's 1-sigma ellipsoid along its longest axis (2 x its largest scale), which
  /// holds both the members' own extent and their spread; scene units. 0 for a leaf of one
  /// splat (nothing to refine). Drawn at projected size <= 1 pixel, a merged Gaussian's
  /// standard deviation is <= 0.5 pixel, below the 0.55 pixel of the rasterizer's own
  /// low-pass filter (0.3 pixel^2): a point on screen, as its members are.
  float size = 0.0f;
  /// Interior: index of the first child in LodTree::nodes (children are consecutive).
  /// Leaf: index of the first splat in LodTree::leafSplats (its splats are consecutive).
  std::uint32_t first = 0;
  /// Index of the node's merged Gaussian in LodTree::merged, or kNone.
  std::uint32_t gaussian = kNone;
  /// Interior: children (2..branching). Leaf: splats (1..leafSize).
  std::uint16_t count = 0;
  /// 1 for a leaf, 0 for an interior node.
  std::uint8_t leaf = 0;
  std::uint8_t reserved = 0;

  bool isLeaf() const { return leaf != 0; }
};

/// A level-of-detail tree over a GaussianCloud. It does not hold the cloud: the cut's
/// original splats index the cloud it was built from.
struct LodTree {
  /// The nodes, breadth first: nodes[0] is the root; a node's children come after it.
  /// Empty for an empty cloud.
  std::vector<LodNode> nodes;
  /// Indices of the original splats, leaf by leaf: a permutation of 0 .. splatCount - 1.
  std::vector<std::uint32_t> leafSplats;
  /// The merged Gaussians, one per node with more than one splat below (interior nodes
  /// and leaves of 2+ splats), in node order (merged[0] is the root's). Same shDegree,
  /// colorSpace and kernel as the source cloud.
  GaussianCloud merged;
  /// Each merged Gaussian's summed coverage (GaussianMoments::weight, scene units
  /// squared): its opacity times meanProjectedArea(scale), but for the clamp to 1.
  std::vector<float> mergedCoverage;
  /// The source cloud's size.
  std::size_t splatCount = 0;
  /// Levels below the root (0 when the root is a leaf).
  int depth = 0;

  /// Bytes held (capacities of every array).
  std::size_t memoryBytes() const;
};

/// Builds the tree: a bounding-volume hierarchy by median split of the splat centres on
/// the longest axis of their box (std::nth_element, O(n log n); the median rounded to whole
/// leaves, so that all leaves but about one per split are full), nodes breadth first; then
/// bottom-up, each node's moments from its children's (mergeMoments, exact for the whole
/// subtree), its merged Gaussian (covarianceToScaleRotation, mergedOpacity, SH as the
/// coverage-weighted mean of its members') and its box. One thread.
/// Throws std::invalid_argument for bad options or a cloud whose arrays disagree in size,
/// std::length_error past 2^32 - 2 splats, LodTreeCancelled when options.cancel became true.
LodTree buildLodTree(const GaussianCloud& cloud, const LodTreeOptions& options = {});

// ---------------------------------------------------------------------------------------
// The cut

/// One viewport's view of the tree, in the cloud's coordinates.
struct CutView {
  /// Camera centre, cloud coordinates.
  glm::vec3 eye{0.0f};
  /// Frustum planes (a, b, c, d): a point p is inside when a p.x + b p.y + c p.z + d >= 0
  /// for each of the first planeCount, (a, b, c) a unit normal. Only culling uses them.
  std::array<glm::vec4, 6> planes{};
  /// 0..6; 0 culls nothing.
  int planeCount = 0;
  /// Pixels per scene unit of lateral size at unit distance: viewport height /
  /// (2 tan(fovY / 2)) for a symmetric perspective. > 0.
  float focalPixels = 1.0f;
  /// A node is refined while its projected size exceeds this (pixels; 1 by default: see
  /// LodNode::size). A negative threshold refines every node in view.
  float pixelThreshold = 1.0f;
};

/// The view of a ProjectionView (modelView cloud -> eye, focal lengths and principal point
/// in pixels, viewport, near and far clip): the eye from the inverse of modelView, the
/// viewport's four side planes and the near and far planes (far dropped past 1e29),
/// focalPixels = max(fx, fy). modelView may scale uniformly (planes are renormalised;
/// projected sizes do not change with a uniform scale).
CutView cutViewFromProjection(const ProjectionView& view, float pixelThreshold = 1.0f);

/// The view of an OpenGL view-projection matrix (cloud -> clip, visible when -w <= x, y, z
/// <= w): planes by Gribb and Hartmann's method (a far plane at infinity is dropped), the
/// eye given (cloud coordinates) and focalPixels = viewport height / (2 tan(fovY / 2)),
/// i.e. 0.5 x height x projection[1][1].
CutView cutViewFromViewProjection(const glm::mat4& viewProjection, const glm::vec3& eye,
                                  float focalPixels, float pixelThreshold = 1.0f);

/// What a cut draws: originals index the cloud the tree was built from, merged index
/// LodTree::merged. Each splat of the cloud is represented exactly once: by itself or by
/// the merged Gaussian of one of its ancestors.
struct LodCut {
  std::vector<std::uint32_t> originals;
  std::vector<std::uint32_t> merged;
  /// Nodes the cut went through (the frontier): diagnostics.
  std::size_t nodes = 0;

  std::size_t size() const { return originals.size() + merged.size(); }
};

/// The projected size of `node` in pixels: node.size x focalPixels / the distance from
/// the eye to its box (nearest point), +infinity when the eye is inside the box.
float projectedSize(const LodNode& node, const CutView& view);

/// The cut of `tree` for `view` under `budget` splats: best first from the root (a priority
/// queue on projectedSize), a node is refined (interior: into its children; leaf: into its
/// original splats) while its projected size exceeds view.pixelThreshold and its box is
/// not wholly outside a frustum plane; a node outside stays coarse (drawn as its merged
/// Gaussian; the renderer culls it). Refinement stops at the first node whose refinement
/// would take the cut past `budget`, so the cut is a best-first prefix: cut.size() <=
/// budget for every budget >= 1, and a budget of 0 gives an empty cut. With an unbounded
/// budget and a threshold below every node's projected size, the cut is every original
/// splat. A cut that the budget does not bind is found depth first, in O(k) for k nodes
/// (the same nodes, in another order); else O(k log k) best first, after a depth-first try
/// of at most `budget` splats.
LodCut selectCut(const LodTree& tree, const CutView& view, std::size_t budget);

/// Fills `out` with the Gaussians of `cut`: first the originals (from `cloud`, the cloud the
/// tree was built from, or that cloud grown: a progressive stream's prefix tree), then the
/// merged ones, with cloud's shDegree, colorSpace and kernel. Reuses out's storage. Throws
/// std::invalid_argument when cloud.size() is below tree.splatCount.
void assembleCut(const LodTree& tree, const GaussianCloud& cloud, const LodCut& cut,
                 GaussianCloud& out);

}  // namespace gs::splats
