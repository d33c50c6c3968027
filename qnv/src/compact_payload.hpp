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

namespace gs::qnv {
struct StreamHeader;
}

namespace gs::qnv::detail {

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
