// qnv::StreamDecoder: header, packets (plain and compact), CRCs, resynchronisation, fed
// in chunks whose sizes come from the input's first bytes.
#include <fuzzer/FuzzedDataProvider.h>

#include "fuzz_support.hpp"
#include "qnv/decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const std::size_t chunk = in.ConsumeIntegralInRange<std::size_t>(1, 70000);
  const std::string bytes = in.ConsumeRemainingBytesAsString();
  gs::qnv::StreamDecoder decoder("fuzz.qnv");
  std::uint64_t vectors = 0;
  const auto sink = [&](std::uint64_t, std::span<const gs::qnv::DecodedVector> v) {
    vectors += v.size();
  };
  for (std::size_t at = 0; at < bytes.size(); at += chunk)
    if (!decoder.feed(std::string_view(bytes).substr(at, chunk), sink)) break;
  decoder.finish(sink);
  return 0;
}
