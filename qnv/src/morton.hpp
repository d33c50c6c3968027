// Private to qnv/: Morton (Z-order) interleaving of three 10-bit coordinates, shared by
// the compact and entropy packet codings (docs/qnv-format.md).
#pragma once

#include <array>
#include <cstdint>

#include "qnv/record.hpp"

namespace gs::qnv::detail {

/// Spreads the low 10 bits of v to every third bit (bit i goes to bit 3i).
inline std::uint32_t spread3(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

/// The inverse of spread3: gathers every third bit of v into the low 10 bits.
inline std::uint32_t compact3(std::uint32_t v) {
  v &= 0x09249249u;
  v = (v | (v >> 2)) & 0x030c30c3u;
  v = (v | (v >> 4)) & 0x0300f00fu;
  v = (v | (v >> 8)) & 0x030000ffu;
  v = (v | (v >> 16)) & 0x3ffu;
  return v;
}

/// The 30-bit Morton code of a packed record's (X, Y, Z): X at bit 0, Y at 1, Z at 2.
inline std::uint32_t recordMorton(std::uint64_t r) {
  const RecordFields f = unpackRecord(r);
  return spread3(f.x) | (spread3(f.y) << 1) | (spread3(f.z) << 2);
}

// A 12-bit piece of a Morton code (4 bits of each axis) spread back to X at bits 20..23,
// Y at 10..13, Z at 0..3; pieces 1 and 2 shifted left by 4 and 8 complete the axes.
struct MortonPieces {
  std::array<std::uint32_t, 4096> xyz{};
  constexpr MortonPieces() {
    for (std::uint32_t c = 0; c < 4096; ++c)
      for (int b = 0; b < 4; ++b)
        xyz[c] |= (((c >> (3 * b)) & 1u) << (20 + b)) | (((c >> (3 * b + 1)) & 1u) << (10 + b)) |
                  (((c >> (3 * b + 2)) & 1u) << b);
  }
};
inline constexpr MortonPieces kMortonPieces;

/// X << 20 | Y << 10 | Z of a 30-bit Morton code (bits over 30 ignored): three lookups.
inline std::uint32_t mortonToXyz(std::uint32_t m) {
  return kMortonPieces.xyz[m & 4095u] | (kMortonPieces.xyz[(m >> 12) & 4095u] << 4) |
         (kMortonPieces.xyz[(m >> 24) & 63u] << 8);
}

}  // namespace gs::qnv::detail
