// The compact packet encoding (PacketEncoding::compact), private to qnv/src. A packet's
// records are sorted by the Morton code of (X, Y, Z), the codes delta-coded as LEB128
// varints, the direction (11 bits), A (15 bits) and C (8 bits) fields split into byte
// planes, and the whole zstd-compressed. Each packet compresses on its own, so packet
// independence is kept; records come back in Morton order, not stream order.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "morton.hpp"
#include "qnv/record.hpp"

namespace gs::qnv {
struct StreamHeader;
}

namespace gs::qnv::detail {

/// Appends `d` as an unsigned LEB128 varint (7 bits a byte, low first).
inline void appendVarint(std::string& out, std::uint32_t d) {
  while (d >= 0x80) {
    out.push_back(static_cast<char>((d & 0x7f) | 0x80));
    d >>= 7;
  }
  out.push_back(static_cast<char>(d));
}

/// Reads `count` LEB128 varints from data[pos..size) as the gaps between sorted Morton
/// codes and writes their running sums to out[0..count), advancing `pos`. False on a
/// varint that runs past `size` or beyond 32 bits.
template <typename T>
bool readMortonGaps(const unsigned char* data, std::size_t size, std::size_t& pos,
                    std::size_t count, T* out) {
  std::uint32_t code = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t d = 0;
    for (int shift = 0;; shift += 7) {
      if (pos >= size || shift > 28) return false;
      const unsigned char b = data[pos++];
      d |= static_cast<std::uint32_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) break;
    }
    code += d;
    out[i] = code;
  }
  return true;
}

/// The fields of record `i` that both compact layouts keep the same way: position from
/// its Morton code `m`, direction (planes 0 and 1: high and low byte of theta * 64 + phi)
/// and C (plane 4), each plane `n` bytes. A stays 0. False for a code or direction out of
/// range.
inline bool planeFields(std::uint32_t m, const unsigned char* plane, std::size_t n, std::size_t i,
                        RecordFields& f) {
  const std::uint32_t dir = (std::uint32_t{plane[i]} << 8) | plane[n + i];
  f.x = static_cast<std::uint16_t>(compact3(m));
  f.y = static_cast<std::uint16_t>(compact3(m >> 1));
  f.z = static_cast<std::uint16_t>(compact3(m >> 2));
  f.theta = static_cast<std::uint8_t>(dir >> 6);
  f.phi = static_cast<std::uint8_t>(dir & 63u);
  f.a = 0;
  f.c = plane[4 * n + i];
  return m < (1u << 30) && dir < kDirectionCells;
}

/// Appends `planes` compressed with zstd at `level` as one frame (its content size set),
/// ending a zstd block before each offset of `blockStarts` (ascending byte offsets into
/// `planes`), so that each run of similar planes gets its own literal table; any zstd
/// decoder reads the frame as one. With `tryOneBlock`, the frame is also made as one block
/// and the smaller kept. Appends nothing when zstd failed every time (the caller then
/// writes the packet plain).
void appendZstdSmaller(std::string& out, const std::string& planes, int level,
                       std::span<const std::size_t> blockStarts, bool tryOneBlock);

/// Appends the compact payload of `records` (1..8191 records) to `out`.
void appendCompactPayload(std::string& out, std::span<const std::uint64_t> records);

/// Decodes a compact payload holding exactly `count` records into `out[0..count)`.
/// Returns false on any inconsistency (zstd error, size mismatch, bad varint); never
/// writes more than `count` records and never allocates more than 8 * count + 64 bytes.
bool decodeCompactPayload(std::string_view payload, std::size_t count, std::uint64_t* out);

/// The compact payload of a Gaussian stream's packet (docs/splats.md, "QNV Gaussian
/// streams"): `records` holds whole splats of `words` records each (2..5); the splats are
/// sorted by the Morton code of their first record's (X, Y, Z), the codes delta-coded as
/// LEB128 varints, then byte planes (direction 2; A 2, as its difference from the code of
/// gaussianImportance; C 1; the 8 bytes of the second word, most significant first, its
/// colour and scale bytes as differences from the previous splat's; then one plane per SH
/// coefficient), zstd-compressed. `header`: the stream's (ranges of A and scales).
void appendGaussianCompactPayload(std::string& out, std::span<const std::uint64_t> records,
                                  std::uint32_t words, const StreamHeader& header);

/// Decodes a Gaussian compact payload of exactly `count` records (a multiple of `words`)
/// into `out[0..count)`, splats in Morton order. False on any inconsistency; allocates at
/// most 8 * count + 64 bytes.
bool decodeGaussianCompactPayload(std::string_view payload, std::size_t count, std::uint32_t words,
                                  const StreamHeader& header, std::uint64_t* out);

}  // namespace gs::qnv::detail
