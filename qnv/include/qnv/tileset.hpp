// The QNV tileset index (index.qnvt): an octree of bricks, each an ordinary .qnv stream
// sorted largest first, described by one small file so a viewer picks from the view alone
// which bricks to fetch and how much of each (issue 13 part 1; a bricked extension of
// Nagasawa, "Beyond VRML", sections 2 and 3.6). Byte layout in docs/qnv-format.md,
// section "Tilesets".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/stream.hpp"

namespace gs::qnv {

/// 8-byte signature of index.qnvt: 0x89 "QNT" CR LF 0x1A LF.
inline constexpr std::array<std::uint8_t, 8> kTilesetMagic = {0x89, 'Q',  'N',  'T',
                                                              '\r', '\n', 0x1a, '\n'};
/// The only index version this build writes and reads.
inline constexpr std::uint16_t kTilesetVersion = 1;
/// Deepest octree level an index may declare (levels 0 .. 12).
inline constexpr std::uint8_t kTilesetMaxDepth = 12;
/// Most bricks an index may declare (2^22).
inline constexpr std::uint32_t kTilesetMaxBricks = std::uint32_t{1} << 22;
/// Magnitude histogram bands per brick: band b counts A codes [2048 b, 2048 b + 2047].
inline constexpr std::size_t kTilesetBands = 16;
/// Bytes before the first brick record: signature, version, depth, reserved, brick count
/// (16) and the template stream header (kHeaderBytes).
inline constexpr std::size_t kTilesetPreambleBytes = 16 + kHeaderBytes;
/// Largest log2 of the merged cells per axis an index may declare (128 cells).
inline constexpr std::uint8_t kTilesetMaxMergedLog2 = 7;
/// The deepest level with merged bricks for cells per axis 2^cellsLog2: the levels whose
/// nodes hold at most 2^18 cells in all (8^L R^3 <= 2^18), at least the root. With the
/// default R = 16: levels 0, 1 and 2. This bounds what an encode sums in memory (about
/// 300 bytes a cell with vectors) however large the data.
constexpr int deepestMergedLevel(std::uint8_t cellsLog2) {
  const int level = (18 - 3 * static_cast<int>(cellsLog2)) / 3;
  return level > 0 ? level : 0;
}

/// Byte 11's flag (bit 7) saying that every interior level has merged bricks, not only
/// those down to deepestMergedLevel: Gaussian tilesets since the thirty-first session,
/// whose merged sums are built node by node (splats/merged_levels.hpp,
/// GaussianMergedLevels), so their memory does not grow with the levels.
inline constexpr std::uint8_t kTilesetMergedEveryLevel = 0x80;

/// Bytes of one brick record (without its packet offsets).
inline constexpr std::size_t kTilesetBrickRecordBytes = 124;

/// The histogram band of A code `code` (0 .. 32767): code / 2048.
constexpr std::size_t tilesetBand(std::uint32_t code) {
  return (code >> 11) & 15u;
}

/// One brick: the vectors of octree node (level, x, y, z) in their own .qnv stream.
struct TilesetBrick {
  std::uint8_t level = 0;                                // 0 = root .. depth
  std::uint32_t x = 0, y = 0, z = 0;                     // cell at that level, each < 2^level
  glm::vec3 boundsMin{0}, boundsMax{0};                  // the brick header's quantization box
  std::uint64_t vectorCount = 0;                         // records in the brick (>= 1)
  std::array<std::uint32_t, kTilesetBands> histogram{};  // vectors per A-code band
  std::vector<std::uint64_t> packetEnds;                 // byte offset past each packet
  std::uint64_t fileBytes = 0;                           // whole brick file size

  /// The brick file's path relative to the tileset folder: "bricks/L/X_Y_Z.qnv".
  std::string path() const;
  /// The path of the node's merged brick (a Gaussian stream of its region's merged
  /// splats, docs/tilesets.md "Merged levels"): "merged/L/X_Y_Z.qnv". Only interior
  /// nodes (level < depth, and level <= deepestMergedLevel unless the index says every
  /// level) of an index with mergedCellsLog2 > 0 have one (TilesetIndex::hasMerged).
  std::string mergedPath() const;
};

/// The whole index.
struct TilesetIndex {
  std::uint8_t depth = 0;  // the leaves' level, 0 .. kTilesetMaxDepth
  /// Byte 11, bits 0-6: 0, or log2 of the cells per axis (1 .. kTilesetMaxMergedLog2) of
  /// the merged bricks (splats/merged_levels.hpp; docs/tilesets.md, "Merged levels").
  std::uint8_t mergedCellsLog2 = 0;
  /// Byte 11, bit 7 (kTilesetMergedEveryLevel): every interior node has a merged brick;
  /// without it, those of levels 0 .. deepestMergedLevel(mergedCellsLog2). Only with
  /// mergedCellsLog2 > 0.
  bool mergedEveryLevel = false;
  StreamHeader header;               // the template: whole box, total vectorCount, mapping
  std::vector<TilesetBrick> bricks;  // sorted by (level, z, y, x), no duplicates
  /// Whether a brick of `level` has a merged brick.
  bool hasMerged(std::uint8_t level) const {
    return mergedCellsLog2 > 0 && level < depth &&
           (mergedEveryLevel || level <= deepestMergedLevel(mergedCellsLog2));
  }
};

/// The bytes of index.qnvt for `index` (little-endian, CRC-32 last). The caller keeps
/// the invariants parseTilesetIndex checks; this function does not check them.
std::string serializeTilesetIndex(const TilesetIndex& index);

/// Parses and checks index.qnvt bytes; safe for untrusted input (every count is checked
/// against the bytes before anything is allocated). Returns nullopt and sets `error` to a
/// sentence naming `name` on: a wrong signature or version, merged cells (byte 11 without
/// its bit 7) above kTilesetMaxMergedLog2, bit 7 without merged cells or in a tileset
/// not of Gaussians, a CRC mismatch, a damaged
/// template header (qnv::parseHeader's sentences), counts that do not fit the bytes or
/// trailing bytes, more than kTilesetMaxBricks bricks, a level above the depth, a cell
/// coordinate >= 2^level, bricks out of order or duplicated, bounds that are non-finite,
/// inverted or outside the template's box, a histogram whose sum is not the brick's
/// vectorCount, an empty brick, brick vector counts not summing to the template's,
/// a packetCount other than ceil(vectorCount / recordsPerPacket), packet ends not
/// increasing or the last not equal to fileBytes, or a packet span outside
/// (16, 16 + packetBytes] bytes (the first span starts at kHeaderBytes).
std::optional<TilesetIndex> parseTilesetIndex(std::string_view bytes, const std::string& name,
                                              std::string& error);

/// Bytes [0, end) of a brick's file hold its header and first `records` records: end is
/// kHeaderBytes for 0 records, else the end of packet ceil(records / recordsPerPacket)
/// (`header` is the index's template: all bricks share its packetBytes); records beyond
/// the brick's vectorCount give fileBytes.
std::uint64_t brickPrefixBytes(const TilesetBrick& brick, const StreamHeader& header,
                               std::uint64_t records);

}  // namespace gs::qnv
