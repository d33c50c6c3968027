// vrml::parseVrml (lexer, parser, node table, PROTO expansion, ROUTEs) on any bytes.
// EXTERNPROTO URLs are refused, so the fuzzer never reads the machine's files.
#include "encodings/parser.hpp"
#include "fuzz_no_files.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::vrml::ParseOptions options;
  options.limits.maxNodes = 200'000;
  options.fetcher = gs::fuzz::noFiles();
  const gs::vrml::Scene scene =
      gs::vrml::parseVrml(gs::fuzz::view(data, size), "fuzz.wrl", options);
  for (const auto& d : scene.diagnostics.items) (void)d.format();
  return 0;
}
