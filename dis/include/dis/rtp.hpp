// RTP headers around DIS PDUs (X3D 4.0 clause 28.4.3, `rtpHeaderExpected`; the RTP fixed
// header of RFC 3550 clause 5.1, 12 bytes plus 4 per CSRC and an optional extension).
// A DIS PDU's first byte is its protocol version (1 to 7), an RTP header's is 0x80 to
// 0xBF (version 2), so a reader tells the two apart by that byte alone.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace gs::dis {

/// Whether `datagram` starts with an RTP version 2 header (its first byte's top two bits
/// are 10): a DIS PDU never does.
bool startsWithRtpHeader(std::span<const std::uint8_t> datagram);

/// The payload of `datagram` after its RTP header (RFC 3550 clause 5.1: 12 bytes, 4 per
/// CSRC, the header extension when the X bit is set, and the padding the P bit announces
/// cut from the end); `datagram` itself when it has no RTP header; an empty span when the
/// header, its CSRCs, extension or padding run past the datagram. Never reads outside it.
std::span<const std::uint8_t> withoutRtpHeader(std::span<const std::uint8_t> datagram);

/// A 12-byte RTP header (RFC 3550 clause 5.1): version 2, no padding, extension or CSRC,
/// marker 0, payload type `payloadType` (0..127; DIS has no assigned one, 96 is the first
/// dynamic type), then `sequence`, `timestamp` and `ssrc`, big-endian.
std::vector<std::uint8_t> rtpHeader(std::uint16_t sequence, std::uint32_t timestamp,
                                    std::uint32_t ssrc, std::uint8_t payloadType = 96);

}  // namespace gs::dis
