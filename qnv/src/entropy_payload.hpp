// The entropy packet encoding (PacketEncoding::entropy), private to qnv/src; the bytes
// are pinned in docs/qnv-format.md ("Compact coding"). A packet's records are sorted by
// the Morton code of their positions (on the volume's voxel grid when the header has
// one), the Morton gaps, direction deltas and colours are coded with small per-packet
// static rANS models, the magnitude codes as fixed-width offsets from the packet's
// smallest. Each packet decodes alone given the stream header; records come back in
// Morton order, not stream order.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "entropy_fields.hpp"

namespace gs::qnv {
struct StreamHeader;
struct DecodedVector;
class Dequantizer;
}  // namespace gs::qnv

namespace gs::qnv::detail {

/// The lattice positions lie on per axis: for a volume of at most 1024 samples along an
/// axis, voxel i sits in cell floor(i * 1024 / (dims - 1)) (clamped to 1023), so a
/// position needs only log2(dims) bits there; otherwise all 1024 cells. With a stream
/// model (docs/qnv-format.md, "Stream model"), also the occupied blocks of that index
/// space. Built in position_model.cpp.
struct PositionGrid {
  std::array<std::vector<std::uint16_t>, 3> cellOf;  // index -> cell (0..1023)
  std::array<std::vector<std::int16_t>, 3> indexOf;  // cell -> index, or -1
  /// index (0..1023) -> cell, or 0x8000 past the axis's indices: lookups without clamps.
  std::array<std::vector<std::uint16_t>, 3> cellOrOutside;
  bool active = false;  // some axis is coarser than 1024
  /// Stream model: blocks of 2^blockShift indices per axis (1..7, at most 2^21 blocks in
  /// the index space), 0 without a model.
  int blockShift = 0;
  /// Morton codes of the occupied blocks' coordinates, strictly increasing (at most 2^21).
  std::vector<std::uint32_t> blocks;
  /// For the decoders, per occupied block: its first index as X << 20 | Y << 10 | Z in the
  /// low 32 bits, its direction (blockDirections, or 0) in bits 32..43, and in bit 63
  /// whether some index of the block lies past axisSize on an axis: one load.
  std::vector<std::uint64_t> blockOrigins;
  /// The model's shared tables (docs/qnv-format.md, "Shared tables"), none without.
  SharedTables shared;
  /// Model kind 2 only (else empty): each occupied block's direction cell, theta << 6 | phi
  /// (theta < 32), in the order of `blocks`; packets with flag bit 3 predict from it.
  std::vector<std::uint16_t> blockDirections;
  /// False when the header's model block does not decode (the stream is then refused).
  bool modelValid = true;

  /// The grid of a stream: from volumeDims for volumes, none for surfaces; the occupied
  /// blocks from header.model.
  static PositionGrid forHeader(const StreamHeader& header);
  /// Index-space size along axis a (the sample count on the grid, else 1024).
  std::uint32_t axisSize(int a) const {
    return active ? static_cast<std::uint32_t>(cellOf[a].size()) : 1024u;
  }
  /// Rank of the block with Morton code `block` among the occupied ones, or -1.
  std::int64_t blockRank(std::uint32_t block) const;
};

/// Stream model blocks worth writing `records` (stream order) under `header` with, for the
/// writer to try in turn: first the occupied blocks (kind 1) at the block size whose
/// estimated saving is largest, then the occupied blocks with their mean directions
/// (kind 2) at that size and the sizes either side. Empty when no model saves bytes (or
/// a record is off the volume's grid).
std::vector<std::string> streamModelCandidates(const StreamHeader& header,
                                               std::span<const std::uint64_t> records);
/// `model` (a candidate above, or empty for none) with shared tables appended (kind bit 7;
/// docs/qnv-format.md, "Shared tables") when they save bits: one table set per group of
/// consecutive packets, the group size chosen by the estimated saving. Returns `model`
/// unchanged when no tables pay.
std::string withSharedTables(const StreamHeader& header, std::span<const std::uint64_t> records,
                             const std::string& model);

/// Where the bits of entropy payloads go (the rANS fields at their model cost).
struct EntropyFieldBits {
  double position = 0, direction = 0, magnitude = 0, color = 0, tables = 0, framing = 0;
  std::size_t blockPackets = 0;  // packets coding positions among the model's blocks
};

/// Appends the entropy payload of `records` (1..8191 records) to `out`; adds its bits
/// per field to `bits` when given. `fast` picks the fast layout (flag bit 2,
/// docs/qnv-format.md "Fast layout": the same symbols, decoded field by field with up to
/// 16 interleaved rANS states) over the original one.
void appendEntropyPayload(std::string& out, std::span<const std::uint64_t> records,
                          const PositionGrid& grid, EntropyFieldBits* bits = nullptr,
                          bool fast = false);

/// Decodes an entropy payload holding exactly `count` records into `out[0..count)`.
/// Returns false on any inconsistency (unknown flags, a table that does not sum up, a
/// field out of range, bytes missing or left over); never writes more than `count`
/// records and allocates only the fixed-size model tables.
bool decodeEntropyPayload(std::string_view payload, std::size_t count, const PositionGrid& grid,
                          std::uint64_t* out);

/// What a decoder needs to write DecodedVectors straight from a packet's fields, without
/// 64-bit records between (the fast layout's decoder): the coordinate of each position
/// index on each axis, for packets on the voxel grid (1024 entries, those past the grid's
/// samples unused) and for packets of cells, and copies of the Dequantizer's direction (theta * 64
/// + phi, 2048 unit normals), magnitude (32768) and RGBA8 colour (256) tables.
struct VectorTables {
  std::array<std::array<float, 1024>, 3> gridAxis{};  // voxel index -> coordinate
  std::array<std::array<float, 1024>, 3> cellAxis{};  // cell -> coordinate
  std::array<glm::vec3, 2048> direction{};
  std::vector<float> magnitude;
  std::array<std::uint32_t, 256> color{};

  VectorTables(const Dequantizer& dequantizer, const PositionGrid& grid);
};

/// True when an entropy payload is in the fast layout (flag bit 2 of its first byte).
inline bool isFastLayout(std::string_view payload) {
  return !payload.empty() && (static_cast<unsigned char>(payload[0]) & 4u) != 0;
}

/// Decodes a fast-layout entropy payload of exactly `count` records straight into
/// DecodedVectors `out[0..count)` (the records' Morton order), with the checks of
/// decodeEntropyPayload: false on any inconsistency (out may then hold garbage).
bool decodeFastVectors(std::string_view payload, std::size_t count, const PositionGrid& grid,
                       const VectorTables& tables, DecodedVector* out);

}  // namespace gs::qnv::detail
