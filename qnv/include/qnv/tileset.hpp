// STUB (branch tsv): the QNV tileset index API as pinned in the lead's design (issue 13
// part 1); the writer branch (tsw) owns the real header and implementation, which replace
// this file and qnv/src/tileset_stub.cpp when merged.
//
// A tileset is static files: OUT/index.qnvt (this index) and OUT/bricks/L/X_Y_Z.qnv, each
// brick an ordinary QNV stream sorted by A code, largest first (docs/qnv-format.md).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "qnv/stream.hpp"

namespace gs::qnv {

/// One brick: an octree node with at least one vector.
struct TilesetBrick {
  std::uint8_t level = 0;
  std::uint32_t x = 0, y = 0, z = 0;
  glm::vec3 boundsMin{0}, boundsMax{0};
  std::uint64_t vectorCount = 0;
  /// Vectors per A-code band (band b = codes [2048 b, 2048 b + 2047]).
  std::array<std::uint32_t, 16> histogram{};
  std::vector<std::uint64_t> packetEnds;  // byte offset past each packet
  std::uint64_t fileBytes = 0;
  /// "bricks/L/X_Y_Z.qnv"
  std::string path() const;
};

struct TilesetIndex {
  std::uint8_t depth = 0;
  StreamHeader header;               // the template
  std::vector<TilesetBrick> bricks;  // sorted by (level, z, y, x)
};

std::string serializeTilesetIndex(const TilesetIndex&);
std::optional<TilesetIndex> parseTilesetIndex(std::string_view bytes, const std::string& name,
                                              std::string& error);
/// Records of the first `records` vectors of a brick = bytes [0, end) of its file.
std::uint64_t brickPrefixBytes(const TilesetBrick&, const StreamHeader& header,
                               std::uint64_t records);

}  // namespace gs::qnv
