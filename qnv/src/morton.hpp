// Private to qnv/: Morton (Z-order) interleaving of three 10-bit coordinates, shared by
// the compact and entropy packet codings (docs/qnv-format.md).
#pragma once

#include <cstdint>

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

}  // namespace gs::qnv::detail
