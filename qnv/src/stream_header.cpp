#include <cmath>
#include <cstring>

#include <libdeflate.h>

#include "base/byte_order.hpp"
#include "qnv/stream.hpp"

namespace gs::qnv {

using base::appendFloatLe;
using base::appendLe;
using base::loadFloatLe;
using base::loadLe;

namespace {

constexpr std::size_t kPaletteOffset = 104;
constexpr std::size_t kCrcOffset = kPaletteOffset + 4 * kPaletteSize;  // 1128
static_assert(kCrcOffset + 4 == kHeaderBytes);

bool finite3(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

std::uint32_t crc32(std::string_view bytes, std::uint32_t crc) {
  return libdeflate_crc32(crc, bytes.data(), bytes.size());
}

std::uint64_t StreamHeader::packetCount() const {
  const std::uint64_t per = recordsPerPacket();
  return per == 0 ? 0 : (vectorCount + per - 1) / per;
}

std::string serializeHeader(const StreamHeader& h) {
  std::string out(reinterpret_cast<const char*>(kMagic.data()), kMagic.size());
  appendLe<std::uint16_t>(out, kFormatVersion);
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(h.kind));
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(h.encoding));
  appendLe<std::uint32_t>(out, h.packetBytes);
  appendLe<std::uint64_t>(out, h.vectorCount);
  for (int i = 0; i < 3; ++i) appendFloatLe(out, h.boundsMin[i]);
  for (int i = 0; i < 3; ++i) appendFloatLe(out, h.boundsMax[i]);
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(h.mapping));
  appendLe<std::uint8_t>(out, 1);  // opacity profile kind: 1 = Gaussian
  appendLe<std::uint8_t>(out, h.kind == StreamKind::gaussian ? h.shDegree : 0);
  appendLe<std::uint8_t>(out, h.kind == StreamKind::gaussian && h.linearColor ? 1 : 0);
  appendFloatLe(out, h.magnitudeMin);
  appendFloatLe(out, h.magnitudeMax);
  appendFloatLe(out, h.profile.sigma);
  appendFloatLe(out, h.profile.opacityScale);
  for (int i = 0; i < 3; ++i) appendFloatLe(out, h.voxelSpacing[i]);
  for (int i = 0; i < 3; ++i) appendLe<std::uint32_t>(out, h.volumeDims[i]);
  appendFloatLe(out, h.valueMin);
  appendFloatLe(out, h.valueMax);
  const std::size_t modelSection = h.model.empty() ? 0 : 8 + h.model.size();
  appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(kHeaderBytes + modelSection));
  for (const Rgba8& c : h.palette)
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>(c[i]));
  appendLe<std::uint32_t>(out, crc32(out));
  if (!h.model.empty()) {  // the model section: length, bytes, CRC of both
    const std::size_t start = out.size();
    appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(h.model.size()));
    out += h.model;
    appendLe<std::uint32_t>(out, crc32(std::string_view(out).substr(start)));
  }
  return out;
}

std::optional<StreamHeader> parseHeader(std::string_view bytes, const std::string& name,
                                        std::string& error) {
  auto fail = [&](const std::string& why) -> std::optional<StreamHeader> {
    error = name + ": " + why;
    return std::nullopt;
  };
  const std::size_t sigBytes = std::min(bytes.size(), kMagic.size());
  if (std::memcmp(bytes.data(), kMagic.data(), sigBytes) != 0)
    return fail("not a QNV stream (wrong signature)");
  if (bytes.size() < kMagic.size() + 2)
    return fail("truncated QNV header (" + std::to_string(bytes.size()) + " bytes)");
  const char* p = bytes.data();
  const auto version = loadLe<std::uint16_t>(p + 8);
  if (version != kFormatVersion)
    return fail("QNV version " + std::to_string(version) + " is " +
                (version > kFormatVersion ? "newer than" : "not") +
                " the version this build reads (" + std::to_string(kFormatVersion) + ")");
  if (bytes.size() < kHeaderBytes)
    return fail("truncated QNV header (" + std::to_string(bytes.size()) + " of " +
                std::to_string(kHeaderBytes) + " bytes)");
  if (crc32(bytes.substr(0, kCrcOffset)) != loadLe<std::uint32_t>(p + kCrcOffset))
    return fail("QNV header is damaged (CRC mismatch)");

  StreamHeader h;
  const auto kind = loadLe<std::uint8_t>(p + 10);
  const auto encoding = loadLe<std::uint8_t>(p + 11);
  h.packetBytes = loadLe<std::uint32_t>(p + 12);
  h.vectorCount = loadLe<std::uint64_t>(p + 16);
  for (int i = 0; i < 3; ++i) h.boundsMin[i] = loadFloatLe(p + 24 + 4 * i);
  for (int i = 0; i < 3; ++i) h.boundsMax[i] = loadFloatLe(p + 36 + 4 * i);
  const auto mapping = loadLe<std::uint8_t>(p + 48);
  const auto profileKind = loadLe<std::uint8_t>(p + 49);
  const auto shDegree = loadLe<std::uint8_t>(p + 50);
  const auto colorSpace = loadLe<std::uint8_t>(p + 51);
  h.magnitudeMin = loadFloatLe(p + 52);
  h.magnitudeMax = loadFloatLe(p + 56);
  h.profile.sigma = loadFloatLe(p + 60);
  h.profile.opacityScale = loadFloatLe(p + 64);
  for (int i = 0; i < 3; ++i) h.voxelSpacing[i] = loadFloatLe(p + 68 + 4 * i);
  for (int i = 0; i < 3; ++i) h.volumeDims[i] = loadLe<std::uint32_t>(p + 80 + 4 * i);
  h.valueMin = loadFloatLe(p + 92);
  h.valueMax = loadFloatLe(p + 96);
  const auto headerBytes = loadLe<std::uint32_t>(p + 100);
  for (std::size_t i = 0; i < kPaletteSize; ++i)
    for (int c = 0; c < 4; ++c)
      h.palette[i][c] = static_cast<std::uint8_t>(p[kPaletteOffset + 4 * i + c]);

  if (kind < 1 || kind > 3) return fail("unknown stream kind " + std::to_string(kind));
  if (kind == 3 && (shDegree > 3 || encoding == 2))
    return fail(shDegree > 3 ? "impossible SH degree " + std::to_string(shDegree)
                             : std::string("a Gaussian stream cannot use the entropy encoding"));
  if (kind == 3 && colorSpace > 1)
    return fail("unknown colour space " + std::to_string(colorSpace));
  const std::uint32_t perElement = kind == 3 ? gaussianWordsPerSplat(shDegree) : 1u;
  if (encoding > 2) return fail("unknown packet encoding " + std::to_string(encoding));
  if (headerBytes != kHeaderBytes && (encoding != 2 || headerBytes < kHeaderBytes + 9 ||
                                      headerBytes > kHeaderBytes + 8 + kMaxModelBytes))
    return fail("header size " + std::to_string(headerBytes) + " is not " +
                std::to_string(kHeaderBytes) +
                (encoding == 2 ? " nor that of a stream model block" : ""));
  h.headerBytes = headerBytes;
  if (headerBytes > kHeaderBytes && bytes.size() >= headerBytes) {
    const std::string_view section = bytes.substr(kHeaderBytes, headerBytes - kHeaderBytes);
    const std::size_t modelBytes = section.size() - 8;
    if (loadLe<std::uint32_t>(section.data()) != modelBytes)
      return fail("stream model length does not match the header size");
    if (crc32(section.substr(0, 4 + modelBytes)) !=
        loadLe<std::uint32_t>(section.data() + 4 + modelBytes))
      return fail("QNV stream model is damaged (CRC mismatch)");
    h.model.assign(section.substr(4, modelBytes));
  }
  if (h.packetBytes < kMinPacketBytes || h.packetBytes > kMaxPacketBytes ||
      h.packetBytes % (8 * perElement))
    return fail("impossible packet size " + std::to_string(h.packetBytes) + " bytes");
  if (h.vectorCount % perElement)
    return fail("a Gaussian stream's record count " + std::to_string(h.vectorCount) +
                " is not a multiple of its " + std::to_string(perElement) + " words per splat");
  if (h.vectorCount > kMaxVectorCount)
    return fail("impossible vector count " + std::to_string(h.vectorCount) +
                " (more than the limit of " + std::to_string(kMaxVectorCount) +
                ", qnv::kMaxVectorCount)");
  if (!finite3(h.boundsMin) || !finite3(h.boundsMax) || h.boundsMin.x > h.boundsMax.x ||
      h.boundsMin.y > h.boundsMax.y || h.boundsMin.z > h.boundsMax.z)
    return fail("impossible bounding box");
  if (mapping != 1 && mapping != 2)
    return fail("unknown magnitude mapping " + std::to_string(mapping));
  h.mapping = static_cast<MagnitudeMapping>(mapping);
  if (!std::isfinite(h.magnitudeMin) || !std::isfinite(h.magnitudeMax) ||
      h.magnitudeMin > h.magnitudeMax ||
      (h.mapping == MagnitudeMapping::logarithmic && !(h.magnitudeMin > 0.0f)))
    return fail("impossible magnitude range");
  if (profileKind != 1) return fail("unknown opacity profile " + std::to_string(profileKind));
  if (!(h.profile.sigma > 0.0f && h.profile.sigma <= 4.0f) ||
      !(h.profile.opacityScale > 0.0f && h.profile.opacityScale <= 64.0f))
    return fail("impossible opacity profile");
  if (!finite3(h.voxelSpacing) || !std::isfinite(h.valueMin) || !std::isfinite(h.valueMax))
    return fail("impossible volume parameters");
  h.kind = static_cast<StreamKind>(kind);
  h.shDegree = kind == 3 ? shDegree : 0;
  h.linearColor = kind == 3 && colorSpace == 1;
  h.encoding = static_cast<PacketEncoding>(encoding);
  return h;
}

}  // namespace gs::qnv
