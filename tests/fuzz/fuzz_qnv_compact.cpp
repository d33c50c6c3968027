// The compact packet payload (zstd, varint Morton deltas, byte planes) decoded alone: the
// first two bytes give the record count (1..8191), the rest is the payload.
#include <memory>
#include <vector>

#include "compact_payload.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::size_t count = 1 + ((data[0] | (data[1] << 8)) % 8191);
  std::vector<std::uint64_t> out(count);
  gs::qnv::detail::decodeCompactPayload(gs::fuzz::view(data + 2, size - 2), count, out.data());
  return 0;
}
