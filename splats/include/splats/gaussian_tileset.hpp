// A 3D Gaussian splatting scene as a QNV tileset (issue 40 items 3 and 4; docs/tilesets.md,
// "Gaussian tilesets"): the octree, assignment and index of a surface tileset
// (qnv/tileset_writer.hpp) over the splats' centres, each brick a QNV Gaussian stream
// (splats/qnv_gaussians.hpp) of its splats, importance first, and every interior node's
// merged brick moment-matched from the Gaussians of its region (splats/merged_levels.hpp).
// A viewer fetches, from the view alone, the bricks and the prefix of each it needs, so a
// scene far larger than memory or than one download streams by view, several viewports
// at their own level of detail. Pure computation on buffers: encode/src/gaussian_tileset.cpp
// writes the files.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "qnv/tileset.hpp"
#include "qnv/tileset_writer.hpp"
#include "splats/gaussian.hpp"
#include "splats/merged_levels.hpp"
#include "splats/qnv_gaussians.hpp"

namespace gs::splats {

/// A Gaussian tileset in memory: the whole of it, or one share's part.
struct GaussianTilesetFiles {
  /// The index: template of kind gaussian (the scene's box, log-scale and importance
  /// ranges, SH degree; vectorCount = records, recordsPerElement() per splat), bricks in
  /// index order, mergedCellsLog2 as asked and mergedEveryLevel set with it. A share's: its
  /// own bricks only (vectorCount theirs), the same merged fields.
  qnv::TilesetIndex index;
  std::vector<qnv::BrickFile> bricks;  // index order
  /// The merged brick (a whole Gaussian stream's bytes) of every brick of `index` that
  /// hasMerged, in index order; a node whose splats merge to nothing has an empty stream.
  std::vector<std::pair<qnv::TilesetCell, std::string>> merged;
  std::uint64_t splats = 0;  // splats kept (gaussianFrame), over all bricks
  /// The octree's depth, its leaves, and the share's range of them [first, end).
  std::uint8_t depth = 0;
  std::uint64_t leafCount = 1;
  std::pair<std::uint64_t, std::uint64_t> leaves{0, 1};
};

/// The tileset of `cloud`:
/// - the splats kept are gaussianFrame's (some opacity and size, finite);
/// - the octree is a surface tileset's over their centres (cut.brickVectors K counts
///   splats: depth D the smallest with 8^D K >= splats, at most 8);
/// - within each leaf the splats are ranked by quantized importance (descending, ties by
///   cloud index); the first q_0 go to the root, the next q_1 to the level-1 ancestor ...
///   (q_L = ceil(K / 8^(D - L))), the rest stay in the leaf: every node is an even,
///   importance-first sample of its region;
/// - each brick is encodeGaussianSplats of its splats in rank order, in the node's cell
///   box and the scene's scale and importance ranges, compact packets (plain when
///   cut.write.encoding is plain) of whole splats (K / 16 splats, 128 to 1,024 and at most
///   64 KiB);
/// - cut.mergedCellsLog2 > 0: every interior node has a merged brick (the index's
///   mergedEveryLevel; GaussianMergedLevels, R = 2^cellsLog2 cells per axis, fed the
///   leaves in Morton order, each leaf's splats in scene order).
/// `options` (SH bits) applies to every brick, shFullFraction to each brick's first
/// splats. cut.brickVoxels and cut.write.packetBytes are not used.
/// Share `share` of `shares` (--bricks I/N; 0 <= share < shares <= qnv::kMaxTilesetShares)
/// encodes only the leaf bricks of its leaves (TilesetLayout::shareLeaves), and share 0 the
/// interior and merged bricks too: every share reads the whole scene (the quantization
/// frame and the assignment are the scene's), and the shares' bricks together are the
/// unsplit run's, byte for byte (encode::mergeShares writes their index).
/// The bricks are encoded on `threads` threads (at least 1), and with more than one the
/// merged levels are summed and encoded on one more beside them: the same bytes whatever
/// the count. Throws qnv::InputError when K is 0, the share is out of range or no splat is
/// kept ("nothing to encode").
GaussianTilesetFiles buildGaussianTileset(const GaussianCloud& cloud,
                                          const qnv::TilesetOptions& cut,
                                          const GaussianStreamOptions& options = {},
                                          std::uint32_t share = 0, std::uint32_t shares = 1,
                                          unsigned threads = 1);

/// The merged levels' cells per axis a Gaussian tileset gets when the encode is not told
/// (`--merged-cells` not given), as log2: 5 (32^3 cells a node) when the root's 32^3 grid
/// over the kept splats' centres (gaussianFrame's box) holds at most one occupied cell per
/// 8 splats, else 4 (16^3, the default of volumes and meshes). A finer merged root stands
/// in for the scene from nearer, but only pays while it is far smaller than the splats it
/// stands for: CThead's capture (122,000 splats) gets 32^3, whose merged root (86 KB, 3.4%
/// of the tileset) draws its 30-unit view at 33.3 dB against the stream's picture (16^3:
/// 33 KB, 26.2 dB); bunny_small (3,000) keeps 16^3. 4 for a cloud with no splat kept.
std::uint8_t defaultGaussianMergedCellsLog2(const GaussianCloud& cloud);

/// The K (splats a node aims at) a Gaussian tileset gets when the encode is not told
/// (`--brick-vectors` not given), from the splats it keeps: 16384, but for 16,385 to
/// 131,072 kept splats the largest power of two K with 8 K < kept, so that the octree is 2
/// deep and its level-1 nodes have merged bricks. With depth 1 (the leaves at level 1) a
/// view that refines the merged root fetches the leaves' prefixes: CThead's capture
/// (122,000 splats) at 10 units read 1.84 MB of its 2.57 MB tileset (30.7 dB against the
/// stream's picture); with K = 8192 it reads 0.45 MB of 3.13 MB (35.1 dB), near views the
/// same bytes (2.49 MB).
std::uint64_t defaultGaussianBrickVectors(std::uint64_t kept);

/// The root cells a Gaussian scene's default merged cells are judged on, per axis.
inline constexpr std::uint32_t kGaussianRootCells = 32;
/// The cell (x + 32 (y + 32 z)) of the 32^3 grid over `frame`'s box (the kept splats'
/// centres, GaussianFrame::header) holding `position` (clamped into the grid).
std::uint32_t gaussianRootCell(const qnv::StreamHeader& frame, glm::vec3 position);
/// defaultGaussianMergedCellsLog2's rule from the count of distinct gaussianRootCell of
/// the `kept` splats: 5 when 8 occupiedCells <= kept (and kept > 0), else 4.
std::uint8_t gaussianMergedCellsLog2For(std::uint64_t occupiedCells, std::uint64_t kept);

/// The octree buildGaussianTileset builds over `kept` splats in the stream frame `frame`
/// (gaussianFrame's header): depth from `kept` and cut.brickVectors; packets of whole
/// splats (K / 16 of them, 128 to 1,024, at most 64 KiB), compact unless cut asks for plain.
/// Throws qnv::InputError when cut.brickVectors is 0.
qnv::TilesetLayout gaussianLayoutForSplats(const qnv::StreamHeader& frame, std::uint64_t kept,
                                           const qnv::TilesetOptions& cut);
/// Where the `count` splats of leaf `leaf`, ranked, go: (node, end) pairs, root first; the
/// splats [previous end, end) go to the node (q_0 to the root, q_1 to the level-1 ancestor
/// ..., the rest to the leaf itself). Fewer pairs when the splats run out.
std::vector<std::pair<qnv::TilesetCell, std::size_t>> splitGaussianLeaf(
    const qnv::TilesetLayout& layout, glm::uvec3 leaf, std::size_t count);
/// A merged brick's bytes: `merged` (a node's merged Gaussians) as a whole Gaussian
/// stream (encodeGaussianStream, compact packets).
std::string encodeMergedBrick(const GaussianCloud& merged);
/// The merged brick of every brick of `index` whose level hasMerged, in index order, from
/// the nodes' encoded merged bricks (encodeMergedBrick of GaussianMergedLevels' clouds);
/// an empty stream for a node without merged splats.
std::vector<std::pair<qnv::TilesetCell, std::string>> gaussianMergedBricks(
    const std::map<qnv::TilesetCell, std::string>& merged, const qnv::TilesetIndex& index);

/// The layout buildGaussianTileset builds its octree with, from the tileset's index
/// template `whole` (vectorCount = the splats' records) and the encode's `cut` (brickVectors
/// and mergedCellsLog2 as given; the packets' size and coding are the template's): for the
/// merge of shares. Throws qnv::InputError as TilesetLayout does.
qnv::TilesetLayout gaussianTilesetLayout(const qnv::StreamHeader& whole,
                                         const qnv::TilesetOptions& cut);

}  // namespace gs::splats
