// formats::readGltf (tinygltf underneath) on JSON and GLB bytes; external buffers are
// refused (the loader answers nothing), so only data: URIs and the GLB BIN chunk count.
#include "formats/mesh_readers.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors([&] {
    (void)gs::formats::readGltf(gs::fuzz::view(data, size), "fuzz.gltf",
                                [](const std::string&) { return std::optional<std::string>(); });
  });
  return 0;
}
