// The .qnv stream: a versioned header, then packets that each decode on their own
// (Nagasawa, "Beyond VRML", section 3.6: records are packed into independent network
// cells so a lost cell costs only its own vectors). Byte layout in docs/qnv-format.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/mesh.hpp"
#include "qnv/record.hpp"

namespace gs::qnv {

/// What the vectors sample (paper section 2.1).
enum class StreamKind : std::uint8_t {
  surface = 1,  // one vector per triangle: A = triangle area
  volume = 2,   // one vector per voxel: A = gradient magnitude
  /// One anisotropic 3D Gaussian per splat (docs/splats.md, "QNV Gaussian streams"):
  /// wordsPerSplat() consecutive records, the first a figure-6 record (position, the
  /// normal of the thinnest axis, A = importance, C = opacity), then scales, rotation,
  /// colour and SH. A = opacity times the largest cross-section's area.
  gaussian = 3,
};

/// Records (64-bit words) per splat of a Gaussian stream of SH degree `shDegree` (0..3):
/// 2, 3, 4 or 5 (docs/splats.md, "QNV Gaussian streams").
constexpr std::uint32_t gaussianWordsPerSplat(int shDegree) {
  return 2u + static_cast<std::uint32_t>(shDegree);
}

/// The SH words of a Gaussian splat (its records 2 on) hold the coefficients beyond DC, R G
/// B of each coefficient in turn, from the top bit of record 2 down: value `k` (0-based)
/// takes 5 bits when it belongs to degree 1 (k < 9), 4 bits above (docs/splats.md).
constexpr int gaussianShBits(int k) {
  return k < 9 ? 5 : 4;
}

/// `bits` (1..32) bits of `words` from bit `at` on, counted from the top bit of words[0]
/// down (a field may span two words).
inline std::uint32_t readWordBits(const std::uint64_t* words, int at, int bits) {
  const int offset = at & 63;
  const std::uint64_t* w = words + (at >> 6);
  const std::uint64_t mask = (std::uint64_t{1} << bits) - 1;
  if (offset + bits <= 64) return static_cast<std::uint32_t>((w[0] >> (64 - offset - bits)) & mask);
  const int low = offset + bits - 64;  // bits in w[1]
  return static_cast<std::uint32_t>(((w[0] << low) | (w[1] >> (64 - low))) & mask);
}

/// ORs the low `bits` (1..32) bits of `value` into `words` at bit `at` (as readWordBits
/// reads them); the bits there must be 0.
inline void writeWordBits(std::uint64_t* words, int at, std::uint32_t value, int bits) {
  const int offset = at & 63;
  std::uint64_t* w = words + (at >> 6);
  const std::uint64_t v = value & ((std::uint64_t{1} << bits) - 1);
  if (offset + bits <= 64) {
    w[0] |= v << (64 - offset - bits);
    return;
  }
  const int low = offset + bits - 64;
  w[0] |= v >> low;
  w[1] |= v << (64 - low);
}

/// The importance of a Gaussian stream's splat from its quantized fields (docs/splats.md,
/// "QNV Gaussian streams"): opacity C / 255 times pi times the two largest scales, each
/// exp(valueMin + q (valueMax - valueMin) / 255) for its 8-bit code q in the second word.
/// Square metres. The encoder sets A to its code, so compact packets need not store A.
struct StreamHeader;
float gaussianImportance(std::uint64_t first, std::uint64_t second, const StreamHeader& header);

/// How a packet's records are stored.
enum class PacketEncoding : std::uint8_t {
  plain = 0,    // count little-endian 64-bit records, in stream order
  compact = 1,  // the same records, spatially sorted, delta-coded and zstd-compressed
  entropy = 2,  // the same records, spatially sorted, coded with per-packet rANS models
};

/// The Gaussian opacity profile alpha(u, x_k) ~ exp(-|u - x_k|^2 / A) of section 3.1, as
/// the renderer applies it: sigma is the Gaussian's standard deviation in units of the
/// splat radius (0 < sigma <= 4); opacityScale multiplies the peak opacity (0 < s <= 64).
struct OpacityProfile {
  float sigma = 0.5f;
  float opacityScale = 1.0f;
};

/// 8-byte file signature: 0x89 "QNV" CR LF 0x1A LF (catches text-mode transfers, as PNG).
inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'Q', 'N', 'V', '\r', '\n', 0x1a, '\n'};
/// The only version this build writes and reads.
inline constexpr std::uint16_t kFormatVersion = 1;
/// Bytes of the version-1 header, palette and header CRC included. A stream with a
/// stream model (docs/qnv-format.md, "Stream model") has a longer header:
/// StreamHeader::headerBytes.
inline constexpr std::size_t kHeaderBytes = 1132;
/// Largest stream model block: its bytes after the 4-byte length, CRC excluded.
inline constexpr std::size_t kMaxModelBytes = std::size_t{1} << 20;
/// Bytes of each packet's own header: sync "QP", count, sequence, payload bytes,
/// encoding, reserved, CRC-32.
inline constexpr std::size_t kPacketHeaderBytes = 16;
/// Record payload capacity of a packet (plain encoding): a multiple of 8 in this range.
/// 48 is the paper's ATM cell (6 records); the default 1376 (172 records) makes
/// 1392-byte packets that fit a 1400-byte datagram.
inline constexpr std::uint32_t kMinPacketBytes = 8;
inline constexpr std::uint32_t kMaxPacketBytes = 65528;
inline constexpr std::uint32_t kDefaultPacketBytes = 1376;
/// Streams claiming more vectors than this (2^36) are rejected as impossible.
inline constexpr std::uint64_t kMaxVectorCount = std::uint64_t{1} << 36;

/// Everything a decoder needs before the first packet.
struct StreamHeader {
  StreamKind kind = StreamKind::surface;
  PacketEncoding encoding = PacketEncoding::plain;  // of the packets written after it
  std::uint32_t packetBytes = kDefaultPacketBytes;  // record bytes per full packet
  std::uint64_t vectorCount = 0;                    // records in the whole stream
  glm::vec3 boundsMin{0, 0, 0};                     // position quantization box (world units)
  glm::vec3 boundsMax{0, 0, 0};
  MagnitudeMapping mapping = MagnitudeMapping::logarithmic;
  float magnitudeMin = 1.0f;  // A code 0 .. 32767 spans [magnitudeMin, magnitudeMax]
  float magnitudeMax = 1.0f;
  OpacityProfile profile;
  glm::vec3 voxelSpacing{0, 0, 0};  // volumes: sample distance per axis; surfaces: 0
  glm::uvec3 volumeDims{0, 0, 0};   // volumes: samples per axis; surfaces: 0
  float valueMin = 0.0f;            // volumes: palette entry c holds values from
  float valueMax = 0.0f;            //   valueMin + c * (valueMax - valueMin) / 256 upwards
  std::array<Rgba8, kPaletteSize> palette{};
  /// Gaussian streams: the SH degree of every splat, 0..3 (header byte 50; 0 for the other
  /// kinds). Their valueMin, valueMax hold the natural-log range of the scales (metres).
  std::uint8_t shDegree = 0;
  /// Gaussian streams: whether their SH colours evaluate in linear Rec.709 and are shown
  /// through the sRGB transfer function (glTF KHR_gaussian_splatting's colorSpace
  /// "lin_rec709_display"; splats::ColorSpace::linear), header byte 51 = 1; false for
  /// sRGB display colours, as every other format stores them (byte 51 = 0). False for the
  /// other kinds.
  bool linearColor = false;
  /// Bytes of the whole header: kHeaderBytes, or kHeaderBytes + 8 + model.size() when the
  /// stream carries a model block (only with PacketEncoding::entropy).
  std::uint32_t headerBytes = static_cast<std::uint32_t>(kHeaderBytes);
  /// The stream model block (docs/qnv-format.md, "Stream model"): shared context the
  /// entropy packets may refer to; empty when none. serializeHeader writes it after the
  /// palette; parseHeader fills it when given all headerBytes.
  std::string model;

  /// Records in one full packet (packetBytes / 8).
  std::uint32_t recordsPerPacket() const { return packetBytes / 8; }
  /// Records per element: 1, or gaussianWordsPerSplat(shDegree) for a Gaussian stream,
  /// whose packetBytes and vectorCount are multiples of it (a splat never spans packets).
  std::uint32_t recordsPerElement() const {
    return kind == StreamKind::gaussian ? gaussianWordsPerSplat(shDegree) : 1u;
  }
  /// Packets in the whole stream: ceil(vectorCount / recordsPerPacket()).
  std::uint64_t packetCount() const;
};

/// The header's bytes (little-endian, CRC-32 last): kHeaderBytes, then the model block
/// section when header.model is not empty (headerBytes is computed, not read).
std::string serializeHeader(const StreamHeader& header);

/// Parses and checks a header from the first kHeaderBytes of `bytes`. Returns nullopt
/// and sets `error` to a sentence naming `name` on: too few bytes, a wrong signature
/// ("not a QNV stream"), an unknown version ("QNV version 7 is newer than this build
/// reads (1)"), a header CRC mismatch, or an impossible value (kind, packet size,
/// vector count above kMaxVectorCount, non-finite or inverted bounds, magnitude range,
/// a header size that is neither kHeaderBytes nor a model block's, a damaged model).
/// Given fewer than headerBytes bytes of a stream with a model block, it returns the
/// header with headerBytes set and model empty: the caller waits for the rest.
std::optional<StreamHeader> parseHeader(std::string_view bytes, const std::string& name,
                                        std::string& error);

/// A set of records with the header that gives them meaning, as the encoders produce it.
/// records are in stream order: by A code, largest first.
struct EncodedVectors {
  StreamHeader header;
  std::vector<std::uint64_t> records;
};

/// How writeStream packs the records.
struct WriteOptions {
  std::uint32_t packetBytes = kDefaultPacketBytes;  // multiple of 8 in [8, 65528]
  PacketEncoding encoding = PacketEncoding::plain;
  /// Entropy encoding only: add a stream model block (the occupied blocks of space) to
  /// the header when it makes the stream smaller; packets then code positions among the
  /// occupied blocks only. Without it, a model in the given header (one shared by several
  /// streams of the same space) is kept when it decodes; other encodings drop it.
  bool streamModel = false;
  /// Entropy encoding only: write the fast layout of each packet (payload flag bit 2,
  /// docs/qnv-format.md "Fast layout": the same symbols, laid out field by field for a
  /// decoder several times faster, a few bytes larger per packet). `--coding entropy-fast`.
  bool fastEntropy = false;
};

/// The whole .qnv file: header (vectorCount, packetBytes and encoding set from the
/// arguments), then packets 0, 1, ... each holding the next recordsPerPacket() records
/// (the last one fewer). Throws InputError on a packetBytes outside the range, or (a
/// Gaussian stream) not a multiple of 8 * recordsPerElement(). A Gaussian stream asked for
/// the entropy coding gets the compact one (zstd over byte planes: its words are not
/// figure-6 records).
std::string writeStream(const EncodedVectors& vectors, const WriteOptions& options = {});

/// Appends one packet (header + payload) for `records` with sequence number `sequence`.
/// `records.size()` must be 1..packetBytes/8 of the stream it belongs to. `header`, when
/// given, is the stream's: entropy packets of a volume then code positions on its voxel
/// grid (smaller); without it they code all 1024 cells per axis (still valid).
/// `fastEntropy`: entropy packets in the fast layout (WriteOptions::fastEntropy).
void appendPacket(std::string& out, std::uint32_t sequence, std::span<const std::uint64_t> records,
                  PacketEncoding encoding, const StreamHeader* header = nullptr,
                  bool fastEntropy = false);

/// CRC-32 (ISO-HDLC, as zlib and PNG) of `bytes`, continuing from `crc` (0 to start);
/// computed by libdeflate (about 9 GB/s with PCLMUL).
std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0);

}  // namespace gs::qnv
