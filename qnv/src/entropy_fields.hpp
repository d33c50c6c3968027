// Private to qnv/src: what the two layouts of the entropy packet encoding share
// (docs/qnv-format.md, "Compact coding" and "Fast layout"): the four modelled fields, their
// per-packet tables, and a packet sorted and turned into symbols by the encoder.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rans.hpp"

namespace gs::qnv::detail {

struct PositionGrid;

// The four modelled fields and their alphabets.
enum Field { kGap = 0, kTheta = 1, kPhi = 2, kColor = 3, kFields = 4 };
inline constexpr std::array<int, kFields> kAlphabetBits = {5, 6, 6, 8};
// Table modes: 0 constant symbol, 1..12 rANS with 2^mode total frequency, 13 raw bits,
// 14 one of the stream model's shared tables (docs/qnv-format.md, "Shared tables").
inline constexpr int kModeConstant = 0;
inline constexpr int kModeRaw = 13;
inline constexpr int kModeShared = 14;
inline constexpr std::uint8_t kFlagGrid = 1;
inline constexpr std::uint8_t kFlagBlocks = 2;  // positions are ranks among the model's blocks
inline constexpr std::uint8_t kFlagFast = 4;    // the fast layout (entropy_fast.cpp)
/// Theta and phi are coded from the direction of the record's block (model kind 2), not
/// from the previous record; only with kFlagBlocks.
inline constexpr std::uint8_t kFlagBlockDirections = 8;
/// Fast layout only: the rANS states start from values that carry the first magnitude
/// offset bits (docs/qnv-format.md, "States that carry bits"), not from 2^16.
inline constexpr std::uint8_t kFlagStateBits = 16;

/// The packet's magnitude byte holds the offsets' width (bits 0..3) and the trailing zero
/// bits they share (bits 4..7; docs/qnv-format.md, "Shared low bits"): valid when the two
/// fit the 15-bit code, and with no shift when there is no width (one encoding).
constexpr bool validMagnitudeWidth(int aBits, int aShift) {
  return aBits + aShift <= 15 && (aBits > 0 || aShift == 0);
}

/// How one field of a packet is coded.
struct FieldCoder {
  int mode = kModeRaw;
  unsigned constant = 0;
  RansModel model;
  /// Encoder only: the index of the stream model's shared table set this coder is taken
  /// from (writeTable then writes mode 14 and the index in `sharedIndexBits` bits), or -1.
  int sharedSet = -1;
  int sharedIndexBits = 0;
  bool coded() const { return mode != kModeRaw && mode != kModeConstant; }
};

/// The stream model's shared tables (docs/qnv-format.md, "Shared tables"): sets of one
/// table per field, built once per stream; a packet's field may name one set's table
/// instead of carrying its own.
struct SharedTables {
  static constexpr std::size_t kMaxSets = 256;  // at most 256 * 4 * 16 KiB of slots
  std::vector<std::array<FieldCoder, kFields>> sets;
  /// Bits of a set index in a packet: ceil(log2(sets)), 0 for one set.
  int indexBits() const {
    return sets.size() <= 1 ? 0 : 32 - __builtin_clz(static_cast<unsigned>(sets.size() - 1));
  }
};

/// Writes a field's table (4-bit mode, then the constant or the frequencies; or mode 14 and
/// the set index when coder.sharedSet >= 0).
void writeTable(BitWriter& bits, const FieldCoder& coder, int alphabetBits);
/// Reads a field's own table (modes 0..13) into `coder`; false on an invalid table.
bool readTable(BitReader& bits, FieldCoder& coder, int alphabetBits);
/// Reads field `field`'s table of a packet: its own (into `own`) or, with mode 14, a set of
/// `shared`. Returns the table to decode with, or nullptr when invalid (mode 15, a set index
/// past the sets, a bad own table).
const FieldCoder* readPacketTable(BitReader& bits, FieldCoder& own, int field,
                                  const SharedTables& shared);

/// The cheapest table for a field with these symbol counts over n records (constant, raw,
/// or rANS at the best total frequency, table bits counted); its bits, table included,
/// in `bitsOut` when given.
FieldCoder planField(const std::vector<std::uint32_t>& counts, std::size_t n, int alphabetBits,
                     double* bitsOut = nullptr);

/// Bits of a field with these counts over n records under shared table `coder`, its
/// reference (mode and a set index of `indexBits`) included; 1e300 when the table cannot
/// code a symbol that occurs.
double sharedTableBits(const FieldCoder& coder, const std::vector<std::uint32_t>& counts,
                       std::size_t n, int alphabetBits, int indexBits);

/// The symbol counts per field (indexed by symbol) of the entropy packet `records` would
/// make under `grid` (for building the shared tables).
std::array<std::vector<std::uint32_t>, kFields> packetSymbolCounts(
    std::span<const std::uint64_t> records, const PositionGrid& grid);

/// A packet as the encoder sees it once sorted: per record in Morton order its (coded)
/// Morton code and record, its four symbols, and the chosen coders.
struct PacketSymbols {
  std::span<const std::pair<std::uint32_t, std::uint64_t>> sorted;
  std::span<const std::array<std::uint32_t, kFields>> symbols;
  const std::array<FieldCoder, kFields>* coders = nullptr;
  std::uint32_t aMin = 0;
  int aBits = 0;           // the width of an offset (A - aMin) >> aShift, 0..15
  int aShift = 0;          // the trailing zero bits every offset shares, 0..15 - aBits
  std::uint8_t flags = 0;  // kFlagGrid, kFlagBlocks, kFlagBlockDirections
};

/// Appends the fast layout of a packet's payload (flag bit 2) to `out`.
void appendFastLayout(std::string& out, const PacketSymbols& packet);

/// Decodes a fast-layout payload (flag bit 2 set) of exactly `count` records, with the
/// contract of decodeEntropyPayload.
bool decodeFastLayout(std::string_view payload, std::size_t count, const PositionGrid& grid,
                      std::uint64_t* out);

}  // namespace gs::qnv::detail
