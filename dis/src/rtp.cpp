// RTP headers around DIS PDUs (dis/rtp.hpp; RFC 3550 clause 5.1).
#include "dis/rtp.hpp"

#include <cstddef>

namespace gs::dis {

namespace {
constexpr std::size_t kRtpFixedHeader = 12;
}  // namespace

bool startsWithRtpHeader(std::span<const std::uint8_t> datagram) {
  return !datagram.empty() && (datagram[0] & 0xC0u) == 0x80u;
}

std::span<const std::uint8_t> withoutRtpHeader(std::span<const std::uint8_t> datagram) {
  if (!startsWithRtpHeader(datagram)) return datagram;
  if (datagram.size() < kRtpFixedHeader) return {};
  const std::uint8_t first = datagram[0];
  std::size_t header = kRtpFixedHeader + 4u * (first & 0x0Fu);  // CSRC count
  if (datagram.size() < header) return {};
  if ((first & 0x10u) != 0) {  // X: a header extension, 4 bytes plus its length in words
    if (datagram.size() < header + 4) return {};
    const std::size_t words = (std::size_t{datagram[header + 2]} << 8) | datagram[header + 3];
    header += 4 + 4 * words;
    if (datagram.size() < header) return {};
  }
  std::size_t end = datagram.size();
  if ((first & 0x20u) != 0) {  // P: the last byte counts the padding bytes, itself included
    const std::size_t padding = datagram[end - 1];
    if (padding == 0 || end - header < padding) return {};
    end -= padding;
  }
  return datagram.subspan(header, end - header);
}

std::vector<std::uint8_t> rtpHeader(std::uint16_t sequence, std::uint32_t timestamp,
                                    std::uint32_t ssrc, std::uint8_t payloadType) {
  std::vector<std::uint8_t> h;
  h.reserve(kRtpFixedHeader);
  h.push_back(0x80);
  h.push_back(static_cast<std::uint8_t>(payloadType & 0x7Fu));
  h.push_back(static_cast<std::uint8_t>(sequence >> 8));
  h.push_back(static_cast<std::uint8_t>(sequence));
  for (const std::uint32_t v : {timestamp, ssrc})
    for (int shift = 24; shift >= 0; shift -= 8) h.push_back(static_cast<std::uint8_t>(v >> shift));
  return h;
}

}  // namespace gs::dis
