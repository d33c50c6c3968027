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

namespace gs::qnv::detail {

/// Appends the compact payload of `records` (1..8191 records) to `out`.
void appendCompactPayload(std::string& out, std::span<const std::uint64_t> records);

/// Decodes a compact payload holding exactly `count` records into `out[0..count)`.
/// Returns false on any inconsistency (zstd error, size mismatch, bad varint); never
/// writes more than `count` records and never allocates more than 8 * count + 64 bytes.
bool decodeCompactPayload(std::string_view payload, std::size_t count, std::uint64_t* out);

}  // namespace gs::qnv::detail
