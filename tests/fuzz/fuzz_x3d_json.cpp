// The X3D JSON encoding (vrml/src/x3d_json.cpp: the nesting scan, nlohmann-json, the
// translation into XML and Classic VRML text, the diagnostics moved back onto the JSON)
// on any bytes, whole and streamed in two pieces. The input is made to start with '{' so
// that every run takes the JSON path. EXTERNPROTO URLs are refused, so the fuzzer never
// reads the machine's files.
#include "fuzz_support.hpp"
#include "vrml/parser.hpp"
#include "vrml/streaming_parser.hpp"

#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::vrml::ParseOptions options;
  options.limits.maxNodes = 200'000;
  options.loader = [](const std::string&, std::string&, std::string& error) {
    error = "no files while fuzzing";
    return false;
  };
  std::string bytes(gs::fuzz::view(data, size));
  if (bytes.empty() || bytes[0] != '{') bytes.insert(0, "{");
  const gs::vrml::Scene whole = gs::vrml::parseVrml(bytes, "fuzz.x3dj", options);
  for (const auto& d : whole.diagnostics.items) (void)d.format();
  gs::vrml::StreamingParser stream("fuzz.x3dj", options);
  const std::size_t cut = size > 0 ? data[0] % (bytes.size() + 1) : 0;
  stream.feed(std::string_view(bytes).substr(0, cut));
  stream.feed(std::string_view(bytes).substr(cut));
  stream.finish();
  return 0;
}
