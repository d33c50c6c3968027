// PROTO and EXTERNPROTO expansion: the input is a world and, after the first NUL byte,
// the text every EXTERNPROTO URL loads (so EXTERNPROTO files naming others, cycles and
// depth limits are reached). Both get a VRML header unless they start with '#'.
#include "encodings/parser.hpp"
#include "fuzz_support.hpp"

namespace {
std::string withHeader(std::string_view s) {
  if (!s.empty() && s[0] == '#') return std::string(s);
  return "#VRML V2.0 utf8\n" + std::string(s);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all = gs::fuzz::view(data, size);
  const std::size_t nul = all.find('\0');
  const std::string world = withHeader(all.substr(0, nul));
  const std::string library =
      nul == std::string_view::npos ? world : withHeader(all.substr(nul + 1));
  gs::vrml::ParseOptions options;
  options.limits.maxNodes = 200'000;
  gs::base::CallbackFetcher served(
      [&library](const std::string&, const std::string&, gs::base::FetchMode) {
        return gs::base::fetchReady(library);
      });
  options.fetcher = &served;
  const gs::vrml::Scene scene = gs::vrml::parseVrml(world, "http://fuzz.example/w.wrl", options);
  (void)scene;
  return 0;
}
