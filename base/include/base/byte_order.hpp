// Little-endian load and store helpers for binary layouts: the .qnv stream and the
// binary formats the readers of formats/ take (PLY, GLB, NIfTI-1, raw volumes).
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

namespace gs::base {

/// `v` (an unsigned integer of 1, 2, 4 or 8 bytes) with its bytes in reverse order.
template <typename T>
T byteSwap(T v) {
  if constexpr (sizeof(T) == 1)
    return v;
  else if constexpr (sizeof(T) == 2)
    return static_cast<T>(__builtin_bswap16(v));
  else if constexpr (sizeof(T) == 4)
    return static_cast<T>(__builtin_bswap32(v));
  else
    return static_cast<T>(__builtin_bswap64(v));
}

/// The little-endian T stored at `p` (sizeof(T) bytes, any alignment).
template <typename T>
T loadLe(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (std::endian::native == std::endian::big) v = byteSwap(v);
  return v;
}

/// The little-endian IEEE 754 binary32 stored at `p`.
inline float loadFloatLe(const char* p) {
  return std::bit_cast<float>(loadLe<std::uint32_t>(p));
}

/// Appends `v` to `out` in little-endian order (sizeof(T) bytes).
template <typename T>
void appendLe(std::string& out, T v) {
  if constexpr (std::endian::native == std::endian::big) v = byteSwap(v);
  char b[sizeof v];
  std::memcpy(b, &v, sizeof v);
  out.append(b, sizeof v);
}

/// Appends `v` to `out` as a little-endian IEEE 754 binary32.
inline void appendFloatLe(std::string& out, float v) {
  appendLe(out, std::bit_cast<std::uint32_t>(v));
}

}  // namespace gs::base
