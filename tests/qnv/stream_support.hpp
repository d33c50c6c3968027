// Test helpers for QNV streams: decoding a stream in chunks into its vectors grouped by
// packet, and walking and editing it packet by packet (docs/qnv-format.md, "Packets"): the
// payload size of a packet, the offsets of all packets of a well-formed stream, and
// resealing a packet (payload size and CRC) after its payload was edited.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <cmath>

#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "qnv/stream.hpp"
#include "qnv/volume.hpp"

namespace gs::qnv::packets {

/// What a stream decodes to: each packet's vectors (their 32 bytes, as a multiset: records
/// come back in Morton order inside a packet) by the packet's first stream index.
struct DecodedStream {
  std::map<std::uint64_t, std::multiset<std::string>> byFirst;
  std::size_t vectors = 0;
  bool finished = false;  // StreamDecoder::finish()
  std::string error;
  DecoderStats stats;
};

/// Decodes `bytes` fed to a StreamDecoder in chunks of `chunk` bytes (at least 1).
inline DecodedStream decodeStream(std::string_view bytes, std::size_t chunk = 1 << 16) {
  DecodedStream out;
  StreamDecoder d("test.qnv");
  auto sink = [&](std::uint64_t first, std::span<const DecodedVector> v) {
    for (const DecodedVector& x : v)
      out.byFirst[first].insert(std::string(reinterpret_cast<const char*>(&x), sizeof x));
    out.vectors += v.size();
  };
  for (std::size_t at = 0; at < bytes.size(); at += chunk) d.feed(bytes.substr(at, chunk), sink);
  out.finished = d.finish(sink);
  out.error = d.error();
  out.stats = d.stats();
  return out;
}

/// The stream of `e`'s records as plain packets of `bytes` record bytes, decoded: what any
/// other coding of the same records must decode to.
inline DecodedStream plainDecoded(const EncodedVectors& e, std::uint32_t bytes) {
  return decodeStream(writeStream(e, {bytes, PacketEncoding::plain}), 1 << 16);
}

/// A volume of `dims` voxels, spacing 1, 1, 2 (as CThead), whose sample at voxel (x, y, z)
/// is sample(x, y, z).
template <typename Sample>
Volume sampledVolume(glm::uvec3 dims, Sample&& sample) {
  Volume v;
  v.dims = dims;
  v.spacing = {1, 1, 2};
  v.samples.resize(v.voxelCount());
  std::size_t i = 0;
  for (std::uint32_t z = 0; z < v.dims.z; ++z)
    for (std::uint32_t y = 0; y < v.dims.y; ++y)
      for (std::uint32_t x = 0; x < v.dims.x; ++x) v.samples[i++] = sample(x, y, z);
  return v;
}

/// The vectors of a sphere shell in a volume of `dims` voxels (spacing 1, 1, 2): sample
/// values fall from 1000 to 0 across a sphere of `radius` around (cx, cy, cz) in voxel
/// units (z counted twice, its spacing), its radius rippled by `ripple` * sin(0.4 x); the
/// largest `fraction` of the gradients kept. Neighbouring voxels' gradients agree.
inline EncodedVectors sphereShellVectors(glm::uvec3 dims, float cx, float cy, float cz,
                                         float radius, float ripple, double fraction) {
  const Volume v = sampledVolume(dims, [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    const float dx = x - cx, dy = y - cy, dz = 2.0f * z - cz;
    const float r = std::sqrt(dx * dx + dy * dy + dz * dz) + std::sin(0.4f * x) * ripple;
    return 1000.0f / (1.0f + std::exp(2.0f * (r - radius)));
  });
  VolumeEncodeOptions options;
  options.selection.fraction = fraction;
  return encodeVolume(v, options);
}

/// Payload bytes of the packet starting at byte `at` of stream `s` (its u16 at offset 8).
inline std::size_t payloadBytes(const std::string& s, std::size_t at) {
  return static_cast<unsigned char>(s[at + 8]) + 256u * static_cast<unsigned char>(s[at + 9]);
}

/// Byte offsets of the packets of a well-formed stream whose header is `headerBytes` long.
inline std::vector<std::size_t> packetStarts(const std::string& s, std::size_t headerBytes) {
  std::vector<std::size_t> starts;
  for (std::size_t at = headerBytes; at + kPacketHeaderBytes <= s.size();
       at += kPacketHeaderBytes + payloadBytes(s, at))
    starts.push_back(at);
  return starts;
}

/// Rewrites the payload size and CRC of the packet at `at` for a payload of `payload` bytes.
inline void resealPacket(std::string& s, std::size_t at, std::size_t payload) {
  s[at + 8] = static_cast<char>(payload & 0xff);
  s[at + 9] = static_cast<char>(payload >> 8);
  const std::uint32_t crc = crc32(std::string_view(s).substr(at + kPacketHeaderBytes, payload),
                                  crc32(std::string_view(s).substr(at + 2, 10)));
  for (int i = 0; i < 4; ++i) s[at + 12 + i] = static_cast<char>(crc >> (8 * i));
}

}  // namespace gs::qnv::packets
