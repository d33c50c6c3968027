// Decoding QNV records into GPU-ready vectors, and the streaming decoder that turns bytes
// arriving in chunks of any size into vectors packet by packet (paper section 3.6).
//
// Safe for untrusted input: every field is checked before use, memory stays bounded by
// one packet (at most 65,552 bytes) plus the chunk being fed, nothing read from the
// stream sizes an allocation, and no input makes it throw, crash or loop.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/stream.hpp"

namespace gs::qnv {

namespace detail {
struct PositionGrid;
struct VectorTables;
}  // namespace detail

/// One decoded vector, 32 bytes, laid out for a GPU vertex buffer: position (world
/// units, the cell centre), magnitude A (area in square units for surfaces, gradient
/// magnitude in value units per unit length for volumes), unit normal, and the palette
/// colour as RGBA8 packed little-endian (R in the low byte).
struct DecodedVector {
  glm::vec3 position;
  float magnitude;
  glm::vec3 normal;
  std::uint32_t rgba;
};
static_assert(sizeof(DecodedVector) == 32);

/// Lookup tables built once per stream header: decoding a record is six table lookups
/// and some shifts (about 1 ns per vector on one core; see bench_qnv).
class Dequantizer {
 public:
  explicit Dequantizer(const StreamHeader& header);
  /// Decodes `count` records (host-order 64-bit words) into `out[0..count)`.
  void decode(const std::uint64_t* records, std::size_t count, DecodedVector* out) const;
  /// Decodes `count` little-endian records straight from stream bytes (8 * count bytes).
  void decodeBytes(const char* bytes, std::size_t count, DecodedVector* out) const;
  DecodedVector decodeOne(std::uint64_t record) const;

  /// The tables themselves, for decoders that write DecodedVectors without records:
  /// the coordinate of each cell along axis `a` (0..2; 1024 entries, world units).
  const std::array<float, kPositionSteps>& axis(int a) const { return axis_[a]; }
  /// The unit normal of each direction cell, theta * 64 + phi (2048 entries).
  const glm::vec3* directions() const { return direction_.data(); }
  /// The magnitude of each A code (32768 entries).
  const float* magnitudes() const { return magnitude_.data(); }
  /// The RGBA8 colour of each palette index, R in the low byte (256 entries).
  const std::uint32_t* colors() const { return color_.data(); }

 private:
  std::array<std::array<float, kPositionSteps>, 3> axis_{};
  std::array<glm::vec3, kDirectionCells> direction_{};
  std::vector<float> magnitude_;  // kMagnitudeSteps entries
  std::array<std::uint32_t, kPaletteSize> color_{};
};

/// Counters of a streaming decode, all monotonic.
struct DecoderStats {
  std::uint64_t bytesFed = 0;
  std::uint64_t packetsDecoded = 0;
  std::uint64_t vectorsDecoded = 0;
  /// Damaged packets: a CRC mismatch or an impossible packet header, each counted once
  /// (the bytes up to the next good packet are skipped).
  std::uint64_t packetsCorrupt = 0;
  /// Sequence numbers below the highest one seen that never arrived (lost or damaged).
  std::uint64_t packetsMissing = 0;
  std::uint64_t bytesSkipped = 0;  // bytes not belonging to any good packet
};

/// Feeds bytes, yields vectors. Typical use:
///   StreamDecoder d("head.qnv");
///   while (chunk) d.feed(chunk, [&](std::uint64_t first, std::span<const DecodedVector> v) {...});
///   d.finish();
class StreamDecoder {
 public:
  /// Receives each good packet's vectors as soon as it completes. `firstIndex` is the
  /// stream position of the packet's first record (sequence * recordsPerPacket), so
  /// vectors with a lower index are larger. Compact and entropy packets yield their
  /// records in spatial (Morton) order. The span is valid only during the call.
  using Sink = std::function<void(std::uint64_t firstIndex, std::span<const DecodedVector>)>;

  /// Receives each good packet of a Gaussian stream (StreamKind::gaussian, whose packets
  /// give the vectors' Sink nothing): its records (host-order 64-bit words), whole splats
  /// of header()->recordsPerElement() records (in Morton order in compact packets), and
  /// the stream index of its first record. Streams of other kinds never call it.
  using RecordSink = std::function<void(std::uint64_t firstIndex, std::span<const std::uint64_t>)>;

  /// `name` (a path or URL) prefixes every message.
  explicit StreamDecoder(std::string name);

  /// Sets the record sink (Gaussian streams).
  void setRecordSink(RecordSink sink) { recordSink_ = std::move(sink); }

  /// Consumes `chunk` (any size, including 0). Returns false once the stream is unusable:
  /// the header was rejected (wrong signature, unknown version, damaged or impossible
  /// header; see error()). Damaged packets are skipped and counted, not fatal.
  bool feed(std::string_view chunk, const Sink& sink);

  /// Declares the end of input; packets found behind a damaged stretch that was still
  /// waiting for bytes go to `sink`. Returns true when every vector of the header arrived.
  /// Otherwise sets a message: "name: stream ends after 12 of 40 packets
  /// (3 damaged, 1 missing)" or "name: no QNV header (N bytes)".
  bool finish(const Sink& sink = {});

  /// The header once the first kHeaderBytes arrived and were accepted.
  const std::optional<StreamHeader>& header() const { return header_; }
  const DecoderStats& stats() const { return stats_; }
  /// Fatal error (header rejected), or empty.
  const std::string& error() const { return error_; }
  /// Non-fatal problems in order (damaged packets with their byte offset, trailing
  /// garbage, truncation), at most 100 kept.
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// True when packets 0..packetCount()-1 all arrived (duplicates aside).
  bool complete() const;

 private:
  void warn(std::string message);
  bool parsePackets(const Sink& sink);
  void compactBuffer();

  std::string name_;
  std::string buffer_;            // bytes kept between feeds (an unfinished packet)
  std::string_view view_;         // what parsePackets reads: buffer_, or a chunk in place
  std::size_t offset_ = 0;        // first unconsumed byte of buffer_
  std::uint64_t bufferBase_ = 0;  // stream offset of buffer_[0]
  std::optional<StreamHeader> header_;
  std::optional<Dequantizer> dequantizer_;
  std::shared_ptr<const detail::PositionGrid> grid_;          // entropy packets' voxel grid
  std::shared_ptr<const detail::VectorTables> vectorTables_;  // fast entropy packets
  DecoderStats stats_;
  std::string error_;
  std::vector<std::string> warnings_;
  std::vector<DecodedVector> scratch_;
  std::vector<std::uint64_t> records_;
  RecordSink recordSink_;
  bool resyncing_ = false;
  std::uint64_t packetsReceived_ = 0;
  std::uint64_t highestSequence_ = 0;
  bool anyPacket_ = false;
  bool finished_ = false;
};

}  // namespace gs::qnv
