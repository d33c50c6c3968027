// splats::readGaussians on any bytes: every splat scene reader (PLY, compressed PLY, SPZ,
// SOG bundles, glTF) by content, and .splat, which has no magic, by the name given here.
// Side files (SOG's WebP images beside a meta.json, a .gltf's buffers) are never found.
#include "fuzz_support.hpp"
#include "splats/readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gs::splats::SideFileReader noFiles = [](const std::string&, std::string&,
                                                std::string& error) {
    error = "no side files while fuzzing";
    return false;
  };
  gs::fuzz::expectingErrors(
      [&] { (void)gs::splats::readGaussians(gs::fuzz::view(data, size), "fuzz.splat", noFiles); });
  return 0;
}
