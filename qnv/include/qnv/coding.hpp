// Where the bits of the entropy packet coding go, for benchmarks and reports
// (docs/qnv-format.md, "Compact coding").
#pragma once

#include <cstdint>

#include "qnv/stream.hpp"

namespace gs::qnv {

/// Bits of a stream written with PacketEncoding::entropy, split by field, summed over
/// all packets. rANS-coded fields count at their model cost (the entropy under the
/// packet's normalized table); framing is the rest: 16-byte packet headers, the 6-byte
/// payload preamble, the 4-byte rANS state and padding to whole bytes. The stream
/// header (1132 bytes) is not counted; its model section, when there is one, is.
struct CodingBits {
  double position = 0;   // Morton gap tokens and their extra bits
  double direction = 0;  // theta and phi deltas
  double magnitude = 0;  // A offsets from the packet's smallest A
  double color = 0;      // palette indices
  double tables = 0;     // the per-packet models
  double framing = 0;
  double model = 0;  // the stream model section of the header (length, block, CRC)
  std::uint64_t vectors = 0;
  std::uint64_t blockPackets = 0;  // packets that code positions among the model's blocks
  double total() const {
    return position + direction + magnitude + color + tables + framing + model;
  }
};

/// Codes `vectors` with the entropy packet encoding at `packetBytes` (as writeStream,
/// with a stream model block when `streamModel` and it pays) and reports where the bits
/// went; `fastEntropy` for the fast layout (WriteOptions::fastEntropy). Throws InputError on a
/// packetBytes out of range.
CodingBits entropyCodingBits(const EncodedVectors& vectors, std::uint32_t packetBytes,
                             bool streamModel = false, bool fastEntropy = false);

}  // namespace gs::qnv
