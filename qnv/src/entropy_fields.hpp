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

#include "rans.hpp"

namespace gs::qnv::detail {

struct PositionGrid;

// The four modelled fields and their alphabets.
enum Field { kGap = 0, kTheta = 1, kPhi = 2, kColor = 3, kFields = 4 };
inline constexpr std::array<int, kFields> kAlphabetBits = {5, 6, 6, 8};
// Table modes: 0 constant symbol, 1..12 rANS with 2^mode total frequency, 13 raw bits.
inline constexpr int kModeConstant = 0;
inline constexpr int kModeRaw = 13;
inline constexpr std::uint8_t kFlagGrid = 1;
inline constexpr std::uint8_t kFlagBlocks = 2;  // positions are ranks among the model's blocks
inline constexpr std::uint8_t kFlagFast = 4;    // the fast layout (entropy_fast.cpp)
/// Theta and phi are coded from the direction of the record's block (model kind 2), not
/// from the previous record; only with kFlagBlocks.
inline constexpr std::uint8_t kFlagBlockDirections = 8;

/// How one field of a packet is coded.
struct FieldCoder {
  int mode = kModeRaw;
  unsigned constant = 0;
  RansModel model;
  bool coded() const { return mode != kModeRaw && mode != kModeConstant; }
};

/// Writes / reads a field's table (4-bit mode, then the constant or the frequencies).
/// readTable returns false on an invalid table.
void writeTable(BitWriter& bits, const FieldCoder& coder, int alphabetBits);
bool readTable(BitReader& bits, FieldCoder& coder, int alphabetBits);

/// A packet as the encoder sees it once sorted: per record in Morton order its (coded)
/// Morton code and record, its four symbols, and the chosen coders.
struct PacketSymbols {
  std::span<const std::pair<std::uint32_t, std::uint64_t>> sorted;
  std::span<const std::array<std::uint32_t, kFields>> symbols;
  const std::array<FieldCoder, kFields>* coders = nullptr;
  std::uint32_t aMin = 0;
  int aBits = 0;
  std::uint8_t flags = 0;  // kFlagGrid, kFlagBlocks, kFlagBlockDirections
};

/// Appends the fast layout of a packet's payload (flag bit 2) to `out`.
void appendFastLayout(std::string& out, const PacketSymbols& packet);

/// Decodes a fast-layout payload (flag bit 2 set) of exactly `count` records, with the
/// contract of decodeEntropyPayload.
bool decodeFastLayout(std::string_view payload, std::size_t count, const PositionGrid& grid,
                      std::uint64_t* out);

}  // namespace gs::qnv::detail
