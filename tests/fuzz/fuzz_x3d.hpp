// The body shared by the X3D encoding targets (fuzz_x3d_xml, fuzz_x3d_json): the input,
// made to start with `lead` so every run takes that encoding's path, parsed whole and
// streamed in two pieces. EXTERNPROTO URLs are refused, so the fuzzer never reads the
// machine's files.
#pragma once

#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"
#include "fuzz_no_files.hpp"
#include "fuzz_support.hpp"

#include <string>

namespace gs::fuzz {

inline void parseX3dEncoding(const std::uint8_t* data, std::size_t size, char lead,
                             const char* url) {
  vrml::ParseOptions options;
  options.limits.maxNodes = 200'000;
  options.fetcher = noFiles();
  std::string bytes(view(data, size));
  if (bytes.empty() || bytes[0] != lead) bytes.insert(0, 1, lead);
  const vrml::Scene whole = vrml::parseVrml(bytes, url, options);
  for (const auto& d : whole.diagnostics.items) (void)d.format();
  vrml::StreamingParser stream(url, options);
  const std::size_t cut = size > 0 ? data[0] % (bytes.size() + 1) : 0;
  stream.feed(std::string_view(bytes).substr(0, cut));
  stream.feed(std::string_view(bytes).substr(cut));
  stream.finish();
}

}  // namespace gs::fuzz
