// vrml::StreamingParser fed the input in chunks of sizes the fuzzer chooses (the first
// bytes of the input pick them), then finish(). Its documented promise is checked: the
// result is the Scene parseVrml() gives for the whole text (same root nodes, same number
// of errors).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>

#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"
#include "fuzz_no_files.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  std::vector<std::size_t> chunks;
  for (int i = 0; i < 16 && in.remaining_bytes() > 0; ++i)
    chunks.push_back(in.ConsumeIntegralInRange<std::size_t>(1, 4096));
  const std::string text = in.ConsumeRemainingBytesAsString();
  gs::vrml::ParseOptions options;
  options.limits.maxNodes = 200'000;
  options.fetcher = gs::fuzz::noFiles();
  gs::vrml::StreamingParser parser("fuzz.wrl", options);
  std::size_t at = 0;
  for (std::size_t i = 0; at < text.size(); ++i) {
    const std::size_t n = chunks.empty() ? text.size() : chunks[i % chunks.size()];
    parser.feed(std::string_view(text).substr(at, n));
    at += n;
  }
  parser.finish();
  const gs::vrml::Scene streamed = parser.takeScene();
  const gs::vrml::Scene whole = gs::vrml::parseVrml(text, "fuzz.wrl", options);
  if (streamed.rootNodes.size() != whole.rootNodes.size() ||
      streamed.diagnostics.errorCount() != whole.diagnostics.errorCount()) {
    std::fprintf(stderr, "streamed: %zu nodes, %zu errors; whole: %zu nodes, %zu errors\n",
                 streamed.rootNodes.size(), streamed.diagnostics.errorCount(),
                 whole.rootNodes.size(), whole.diagnostics.errorCount());
    for (const auto& d : streamed.diagnostics.items)
      std::fprintf(stderr, "S %s\n", d.format().c_str());
    for (const auto& d : whole.diagnostics.items)
      std::fprintf(stderr, "W %s\n", d.format().c_str());
    std::abort();
  }
  return 0;
}
