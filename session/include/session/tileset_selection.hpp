// Which bricks of a QNV tileset to draw, and how much of each, from the view alone (issue
// 13 part 1; docs/tilesets.md "Viewing a tileset"). Pure computation, no GL, no network.
//
// The rule (a screen-space error against a pixel budget, as 3D Tiles' geometric error and
// Potree's point budget do it):
// - A brick's box (its index bounds, placed by `model`) is culled when it lies wholly
//   outside the view frustum (left, right, bottom, top, near planes).
// - Its projected size s (pixels) is the diameter of its bounding sphere over the distance
//   from the eye to the sphere's near side (at least the near distance), times the
//   viewport height over 2 tan(fov / 2): an overestimate, as is usual for conservative
//   refinement. Its screen area is s^2 pixels.
// - A brick drawn alone gives s^2 / vectorCount pixels per vector. It is refined (its
//   visible children are considered too) while that exceeds `pixelsPerVector` (default 1:
//   about one vector per pixel of the brick's footprint). A Gaussian tileset (template
//   of kind gaussian) counts splats, each recordsPerElement() records: records and
//   budgets stay in records.
// - A brick's own prefix is min(vectorCount, ceil(s^2 / pixelsPerVector)) records, rounded
//   up to whole packets, so a small far brick sends only its largest vectors.
// - Opacity (volume tilesets, issue 22 item 3; Gaussian tilesets, whose A is a splat's
//   coverage, opacity times area, so a band's optical depth is its count times the band's
//   centre A over the brick's mean projected area): the prefix is at least all but the
//   brick's weakest vectors whose optical depth, averaged over the brick's mean projected
//   area, stays within `maxLostOpticalDepth`, and a brick is also refined while its
//   descendants add more than that; this optical depth does not depend on the view, so
//   the haze of many weak vectors (equation 1) is kept at any distance.
// - Order: a priority queue from the root, larger priority first, priority = s * (1 + m)
//   where m in [0, 1] is the brick's mean magnitude band (its histogram) over 15: nearer,
//   larger and stronger bricks first. A child enters the queue only when its parent was
//   taken, so ancestors (an even, magnitude-first sample of their region) come before
//   their children.
// - Budget: when the choice holds more records than min(vectorBudget, memoryBudget),
//   every brick keeps only its vectors above one global magnitude threshold, read from
//   the histograms (a band cut in part counts in proportion), the threshold found by
//   bisection so the choice fits: the vectors kept are those the single stream's prefix
//   of that size keeps (the largest of the whole data), restricted to the view. The walk
//   at that threshold then stops at the budget (whole packets: the total may pass it by
//   less than one packet).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "qnv/tileset.hpp"

namespace gs::session {

/// The view a selection is made for (world coordinates, metres, radians).
struct TilesetView {
  glm::vec3 position{0.0f, 0.0f, 10.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};  // unit
  glm::vec3 up{0.0f, 1.0f, 0.0f};        // unit, orthogonal to forward
  float verticalFov = 0.785398f;         // radians, (0, pi)
  float aspect = 1.0f;                   // width / height
  int heightPixels = 512;                // viewport height
  float nearClip = 0.0f;                 // metres; 0: no near plane
  glm::mat4 model{1.0f};                 // tileset coordinates to world
};

struct TilesetBudget {
  /// Vectors drawn at most (the viewport's level of detail times the tileset's count).
  std::uint64_t vectors = UINT64_MAX;
  /// Vectors held decoded at most (--tileset-memory MB / sizeof(qnv::DecodedVector), 32
  /// bytes per vector).
  std::uint64_t memoryVectors = UINT64_MAX;
  /// Screen-space error threshold: pixels per vector above which a brick is refined.
  double pixelsPerVector = 1.0;
  /// Volume tilesets: the optical depth a brick's dropped vectors may take from its
  /// pixels, on average (the opacity-aware part of the rule; 0 turns it off).
  double maxLostOpticalDepth = 0.02;
};

/// One brick chosen: its index in TilesetIndex::bricks and the prefix to fetch and draw.
struct BrickChoice {
  std::size_t brick = 0;
  std::uint64_t records = 0;  // whole packets (or the brick's count)
  std::uint64_t bytes = 0;    // qnv::brickPrefixBytes for `records`
  double priority = 0.0;      // s * (1 + m), larger first
  double pixels = 0.0;        // projected size s
};

/// The bricks to draw for `view`, in priority order (ancestors before descendants).
/// `skip` (empty, or one entry per brick): bricks with a non-zero entry are never chosen
/// (they lie in a region drawn by its merged brick, chooseMerged).
std::vector<BrickChoice> selectBricks(const qnv::TilesetIndex& index, const TilesetView& view,
                                      const TilesetBudget& budget,
                                      std::span<const std::uint8_t> skip = {});

/// Projected cell size (pixels) at or below which an interior node is drawn by its merged
/// brick: the node's projected diameter (as above) over its cells per axis.
inline constexpr double kMergedPixels = 2.0;

/// Which interior nodes the views draw by their merged bricks (docs/tilesets.md, "Merged
/// levels"; an index with mergedCellsLog2 > 0). For each view, from the root: a visible
/// interior brick whose projected diameter over 2^mergedCellsLog2 is at most
/// `mergedPixels` is merged and nothing below it is visited; a larger one is refined
/// (its children visited); leaves are never merged. Over several views a node is merged
/// when some view merges it and none refines it.
struct MergedChoice {
  /// Bricks drawn by their merged brick (index order), none inside another.
  std::vector<std::size_t> merged;
  /// Per brick (all of the index, or empty when nothing is merged): 1 for a merged brick,
  /// every brick below one, and every refined brick whose children are all merged or out
  /// of view (nothing of its own is left to draw), which selectBricks must not choose.
  std::vector<std::uint8_t> skip;
};
/// `unavailable` (empty, or one entry per brick): bricks whose merged brick could not be
/// read; they are refined instead, so a missing merged brick costs vectors, not the region.
MergedChoice chooseMerged(const qnv::TilesetIndex& index, const std::vector<TilesetView>& views,
                          double mergedPixels = kMergedPixels,
                          std::span<const std::uint8_t> unavailable = {});

/// Merges the choices of several views: per brick the largest prefix, ordered by the
/// largest priority any view gave it.
std::vector<BrickChoice> mergeChoices(const std::vector<std::vector<BrickChoice>>& views);

/// Bytes of all the prefixes of `choices` (what fetching them costs, headers included).
std::uint64_t totalBytes(const std::vector<BrickChoice>& choices);

}  // namespace gs::session
