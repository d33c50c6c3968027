// The HTTP response head as net/ reads it (status line, Content-Length, Content-Encoding,
// Content-Range) and the body plan made from it: the input's first bytes choose whether a
// range was asked and from where, the rest are header lines.
#include <fuzzer/FuzzedDataProvider.h>

#include "fuzz_support.hpp"
#include "http_response.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const bool ranged = in.ConsumeBool();
  const std::uint64_t from = in.ConsumeIntegral<std::uint64_t>();
  const std::string text = in.ConsumeRemainingBytesAsString();
  gs::net::detail::ResponseHead head;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t eol = text.find('\n', at);
    if (eol == std::string::npos) eol = text.size();
    gs::net::detail::readHeaderLine(std::string_view(text).substr(at, eol + 1 - at), head);
    at = eol + 1;
  }
  const auto plan = gs::net::detail::planBody(head, head.code, ranged, from);
  if (plan.left < -1 || plan.resourceSize < -1) __builtin_trap();
  return 0;
}
