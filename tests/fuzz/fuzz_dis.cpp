// dis::decodeHeader, dis::decodePdu and each PDU decoder (Entity State, Fire, Detonation,
// Collision, Remove Entity, Transmitter, Signal, Receiver) on any bytes (a datagram from
// the network), and dis::withoutRtpHeader before the dispatcher, as a reader takes them.
#include "dis/pdu.hpp"
#include "dis/rtp.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <variant>

namespace {

/// What decodes encodes again to a PDU that decodes to the same radio.
template <class P>
void roundTrip(const P& pdu, std::vector<std::uint8_t> (*encode)(const P&),
               std::optional<P> (*decode)(std::span<const std::uint8_t>, std::string*)) {
  const std::vector<std::uint8_t> again = encode(pdu);
  const std::optional<P> back = decode(again, nullptr);
  if (!back || !(back->radio == pdu.radio)) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  std::string error;
  (void)gs::dis::decodeHeader(bytes, &error);
  if (auto pdu = gs::dis::decodeEntityState(bytes, &error)) {
    // What decodes encodes again to a PDU that decodes to the same entity.
    const std::vector<std::uint8_t> again = gs::dis::encodeEntityState(*pdu);
    auto back = gs::dis::decodeEntityState(again, nullptr);
    if (!back || !(back->entityID == pdu->entityID)) __builtin_trap();
  }
  if (auto pdu = gs::dis::decodeTransmitter(bytes, &error)) {
    if (pdu->modulationParameters.size() + pdu->antennaPattern.size() > size) __builtin_trap();
    roundTrip(*pdu, &gs::dis::encodeTransmitter, &gs::dis::decodeTransmitter);
  }
  if (auto pdu = gs::dis::decodeSignal(bytes, &error)) {
    if (pdu->data.size() > size) __builtin_trap();
    roundTrip(*pdu, &gs::dis::encodeSignal, &gs::dis::decodeSignal);
  }
  if (auto pdu = gs::dis::decodeReceiver(bytes, &error))
    roundTrip(*pdu, &gs::dis::encodeReceiver, &gs::dis::decodeReceiver);
  if (auto pdu = gs::dis::decodeFire(bytes, &error)) {
    const auto back = gs::dis::decodeFire(gs::dis::encodeFire(*pdu), nullptr);
    if (!back || !(back->eventID == pdu->eventID)) __builtin_trap();
  }
  if (auto pdu = gs::dis::decodeDetonation(bytes, &error)) {
    if (16 * pdu->articulationParameters.size() > size) __builtin_trap();
    const auto back = gs::dis::decodeDetonation(gs::dis::encodeDetonation(*pdu), nullptr);
    if (!back || !(back->firingEntityID == pdu->firingEntityID)) __builtin_trap();
  }
  if (auto pdu = gs::dis::decodeCollision(bytes, &error)) {
    const auto back = gs::dis::decodeCollision(gs::dis::encodeCollision(*pdu), nullptr);
    if (!back || !(back->issuingEntityID == pdu->issuingEntityID)) __builtin_trap();
  }
  if (auto pdu = gs::dis::decodeRemoveEntity(bytes, &error)) {
    const auto back = gs::dis::decodeRemoveEntity(gs::dis::encodeRemoveEntity(*pdu), nullptr);
    if (!back || !(back->receivingID == pdu->receivingID) || back->requestID != pdu->requestID)
      __builtin_trap();
  }
  // An RTP header is taken off inside the datagram, or the datagram is left whole.
  const std::span<const std::uint8_t> payload = gs::dis::withoutRtpHeader(bytes);
  if (!payload.empty() && (payload.data() < data || payload.data() + payload.size() > data + size))
    __builtin_trap();
  if (gs::dis::startsWithRtpHeader(bytes) && !payload.empty())
    (void)gs::dis::decodePdu(payload, &error);
  // The dispatcher agrees with the decoder of the type it names.
  if (auto pdu = gs::dis::decodePdu(bytes, &error)) {
    const std::size_t index = pdu->index();
    const std::uint8_t type = bytes[2];
    const bool agrees = (type == 1 && index == 0) || (type == 25 && index == 1) ||
                        (type == 26 && index == 2) || (type == 27 && index == 3) ||
                        (type == 2 && index == 4) || (type == 3 && index == 5) ||
                        (type == 4 && index == 6) || (type == 12 && index == 7);
    if (!agrees) __builtin_trap();
  }
  return 0;
}
