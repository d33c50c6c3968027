// The DDS reader as ImageTexture3D and ImageCubeMapTexture call it (render/src/
// dds_images.hpp): any bytes give images or a std::runtime_error, within kMaxDdsTexels.
#include "dds_images.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors([&] {
    const gs::render::detail::DdsImages d =
        gs::render::detail::decodeDdsImages(gs::fuzz::view(data, size), "fuzz.dds");
    if (d.rgba.size() > 4 * gs::render::detail::kMaxDdsTexels) __builtin_trap();
  });
  return 0;
}
