// dis::decodeHeader and dis::decodeEntityState on any bytes (a datagram from the network).
#include "dis/pdu.hpp"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

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
  return 0;
}
