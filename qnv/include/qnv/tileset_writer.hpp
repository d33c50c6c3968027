// Building a QNV tileset (issue 13 parts 1 and 2): the octree layout, the per-leaf quota
// assignment, per-brick quantization, and the share/merge split that lets many machines
// encode one tileset. Pure computation on buffers: the caller writes the files
// (encode/src/tileset.cpp). Rules in docs/qnv-format.md, section "Tilesets".
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/encoder.hpp"
#include "qnv/tileset.hpp"

namespace gs::qnv {

/// Most shares a tileset encode may be split into (2^20).
inline constexpr std::uint32_t kMaxTilesetShares = std::uint32_t{1} << 20;

/// How a tileset is cut and coded.
struct TilesetOptions {
  std::uint32_t brickVoxels = 64;      // volumes: leaf block side in voxels, >= 1
  std::uint64_t brickVectors = 16384;  // K: vectors a node aims at (surfaces: leaf size), >= 1
  WriteOptions write;                  // packet size and coding of every brick
  /// log2 of the cells per axis of the merged bricks the encode adds beside the interior
  /// bricks (splats/merged_levels.hpp; encode/tileset.hpp), 0: none. Not used by this
  /// module's own functions.
  std::uint8_t mergedCellsLog2 = 0;
};

/// An octree node: level (0 = root) and cell (each coordinate < 2^level).
struct TilesetCell {
  std::uint8_t level = 0;
  glm::uvec3 cell{0};
  /// (level, z, y, x), the order of bricks in the index.
  auto key() const { return std::make_tuple(level, cell.z, cell.y, cell.x); }
  bool operator<(const TilesetCell& o) const { return key() < o.key(); }
  bool operator==(const TilesetCell& o) const { return key() == o.key(); }
};

/// The octree of a tileset over `whole` (the single stream's header: kind, box, dims,
/// vectorCount = the kept vectors).
/// Volumes: leaves are blocks of B voxels per side, depth = the smallest D with
/// 2^D B >= max(dims); the leaf grid is ceil(dims / B) per axis.
/// Surfaces: depth = the smallest D with 8^D K >= vectorCount (at most 8); cells are
/// equal subdivisions of the box, the leaf grid is 2^D per axis.
class TilesetLayout {
 public:
  /// Throws InputError on a brickVoxels or brickVectors of 0.
  TilesetLayout(const StreamHeader& whole, const TilesetOptions& options);

  std::uint8_t depth() const { return depth_; }
  glm::uvec3 leafGrid() const { return leafGrid_; }
  std::uint64_t leafCount() const;
  /// The leaf holding `v`: its voxel's block, or the cell holding its position (clamped).
  glm::uvec3 leafOf(const SourceVector& v) const;
  /// Volumes: the voxel (x, y, z) of `v` from its source index.
  glm::uvec3 voxelOf(const SourceVector& v) const;
  /// Leaves are numbered in (z, y, x) order over leafGrid(): x + gx (y + gy z).
  std::uint64_t leafIndex(glm::uvec3 leaf) const;
  glm::uvec3 leafAt(std::uint64_t index) const;
  /// Share `share` of `shares` (0 <= share < shares <= kMaxTilesetShares) owns leaves
  /// [floor(share L / shares), floor((share + 1) L / shares)) of the L leaves.
  std::pair<std::uint64_t, std::uint64_t> shareLeaves(std::uint32_t share,
                                                      std::uint32_t shares) const;
  /// Per-leaf quota of level `level` < depth(): ceil(K / 8^(depth - level)).
  std::uint64_t quota(std::uint8_t level) const;
  /// The header of node `node`'s brick: the template with the node's box (volumes: the
  /// box of its voxel block's centres, volumeDims = the block's dims) and vectorCount.
  StreamHeader brickHeader(const TilesetCell& node, std::uint64_t vectorCount) const;
  /// Volumes: the first voxel of `node`'s block (for quantizeVector's grid index).
  glm::uvec3 blockStart(const TilesetCell& node) const;
  /// The whole template (packetBytes and encoding from the options; vectorCount as given).
  const StreamHeader& templateHeader() const { return whole_; }
  /// The cut and coding it was made with.
  const TilesetOptions& options() const { return options_; }

 private:
  StreamHeader whole_;
  TilesetOptions options_;
  std::uint8_t depth_ = 0;
  glm::uvec3 leafGrid_{1};
};

/// A brick's file and its index record.
struct BrickFile {
  TilesetBrick brick;
  std::string bytes;
};

/// Writes one brick: `header` (from TilesetLayout::brickHeader), then the records in the
/// order given (largest A first) in packets of header.recordsPerPacket().
BrickFile writeBrick(const TilesetCell& node, const StreamHeader& header,
                     std::span<const std::uint64_t> records);

/// One vector an interior node receives from a leaf: its record (already quantized for
/// that node's brick) and the keys that order the node's brick: exact magnitude
/// descending, then source ascending.
struct InteriorEntry {
  float magnitude = 0;
  std::uint64_t source = 0;
  std::uint64_t record = 0;
};

/// What one share contributes to the interior nodes, by node.
using InteriorParts = std::map<TilesetCell, std::vector<InteriorEntry>>;

/// The bytes of a share's interior contributions (parts/I-of-N/interior.qnvp):
/// signature 0x89 "QNP" CR LF 0x1A LF, u32 brickVoxels, u64 brickVectors (the octree
/// cut, so the merge rebuilds the layout), u32 node count, then per node (in key order)
/// u8 level, u8[3] 0, u32 x, y, z, u64 entry count, then per entry f32 magnitude,
/// u64 source, u64 record; CRC-32 last. Little-endian.
std::string serializeInteriorParts(const InteriorParts& parts, const TilesetOptions& cut);
/// The same bytes in pieces, for parts too large to hold at once (out-of-core encodes
/// spill them): `nodes` in key order, entriesOf(i) gives node i's entries (in any order),
/// `sink` receives the bytes in order.
void writeInteriorParts(const std::vector<TilesetCell>& nodes,
                        const std::function<std::vector<InteriorEntry>(std::size_t)>& entriesOf,
                        const TilesetOptions& cut,
                        const std::function<void(std::string_view)>& sink);
/// Parses and checks those bytes (counts against bytes, levels <= 12, cells < 2^level,
/// node order, CRC) and sets cut's brickVoxels and brickVectors; nullopt and a sentence
/// naming `name` in `error` otherwise.
std::optional<InteriorParts> parseInteriorParts(std::string_view bytes, const std::string& name,
                                                TilesetOptions& cut, std::string& error);

/// Where one node's entries lie in an interior.qnvp file: `count` entries of 20 bytes
/// from byte `offset`.
struct InteriorPartSpan {
  TilesetCell node;
  std::uint64_t offset = 0;
  std::uint64_t count = 0;
};
/// Reads `bytes` bytes at `offset` of a part file into `out`; throws on a short read.
using PartReader = std::function<void(std::uint64_t offset, std::size_t bytes, char* out)>;
/// parseInteriorParts's checks on a file of `size` bytes read piece by piece through
/// `read` (1 MiB at a time for the CRC, then the node headers), never held whole: the
/// nodes' spans in key order, or nullopt and the same sentences in `error`. Safe for
/// untrusted input (every count is checked against the file size).
std::optional<std::vector<InteriorPartSpan>> scanInteriorParts(std::uint64_t size,
                                                               const PartReader& read,
                                                               const std::string& name,
                                                               TilesetOptions& cut,
                                                               std::string& error);
/// The entries of one span (scanInteriorParts's result for the same file).
std::vector<InteriorEntry> loadInteriorEntries(const InteriorPartSpan& span,
                                               const PartReader& read);
/// One interior node's brick from its entries of every share: sorted by (magnitude
/// descending, source ascending), so the result does not depend on the split.
BrickFile mergeInteriorNode(const TilesetCell& node, std::vector<InteriorEntry> entries,
                            const TilesetLayout& layout);

/// The interior bricks from every share's parts: a node's entries from all shares,
/// sorted by (magnitude descending, source ascending), so the result does not depend on
/// how the leaves were split. `layout` gives each node's brick header.
std::vector<BrickFile> mergeInteriorParts(const std::vector<InteriorParts>& shares,
                                          const TilesetLayout& layout);

/// The index over `bricks` (any order; sorted here by level, z, y, x): depth and template
/// from `layout`, template vectorCount = the bricks' sum.
TilesetIndex assembleTilesetIndex(const TilesetLayout& layout, std::vector<TilesetBrick> bricks);

/// A whole tileset in memory, as an unsplit run writes it (share 0 of 1, then the merge):
/// the bricks in index order and the index.
struct TilesetFiles {
  TilesetIndex index;
  std::vector<BrickFile> bricks;
};
TilesetFiles buildTileset(const SelectedVectors& selected, const TilesetOptions& options);

/// One share's encoder. Vectors arrive in any order through add(); a leaf whose vectors
/// have all arrived is closed with finishLeaf(), which returns its brick at once and
/// keeps only the leaf's interior quotas (at most sum of q_L vectors), so memory is the
/// open leaves plus the interior contributions.
class TilesetShareWriter {
 public:
  /// `layout` must outlive the writer. Throws InputError unless
  /// 0 <= share < shares <= kMaxTilesetShares.
  TilesetShareWriter(const TilesetLayout& layout, std::uint32_t share = 0,
                     std::uint32_t shares = 1);

  /// Buffers `v` in its leaf; false (and nothing kept) when the leaf is not this share's.
  bool add(const SourceVector& v);
  /// Ranks the leaf's vectors (magnitude descending, source ascending), gives the first
  /// q_0 to the root, the next q_1 to the level-1 ancestor, ..., and returns the rest as
  /// the leaf's brick (nullopt when none remain). Later add()s to it throw InputError.
  std::optional<BrickFile> finishLeaf(glm::uvec3 leaf);
  /// finishLeaf's work on vectors the caller gathered itself (all of `leaf`'s, in any
  /// order): the interior entries go to `interior` (not the writer's), the rest is the
  /// returned brick. Touches no state of the writer: safe from several threads at once
  /// (out-of-core encodes finish a row of leaves in parallel: encode/src/ooc_volume.cpp).
  std::optional<BrickFile> rankLeaf(glm::uvec3 leaf, std::vector<SourceVector> vectors,
                                    InteriorParts& interior) const;
  /// Moves `parts`' entries into the writer's interior contributions.
  void addInterior(InteriorParts&& parts);
  /// Hands out the interior contributions so far and forgets them (to spill them).
  InteriorParts takeInterior() { return std::exchange(interior_, {}); }
  /// Leaves holding buffered vectors, in (z, y, x) order.
  std::vector<glm::uvec3> openLeaves() const;
  /// The interior contributions so far.
  const InteriorParts& interior() const { return interior_; }
  std::pair<std::uint64_t, std::uint64_t> leafRange() const { return range_; }

 private:
  const TilesetLayout& layout_;
  std::pair<std::uint64_t, std::uint64_t> range_;
  std::map<std::uint64_t, std::vector<SourceVector>> open_;
  std::set<std::uint64_t> finished_;
  InteriorParts interior_;
};

}  // namespace gs::qnv
