// The texture decoders as render/src/textures.cpp calls them: render::decodeImage
// (stb_image for PNG, JPEG and GIF, dimensions capped at 16384).
#include "fuzz_support.hpp"
#include "render/image.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors([&] {
    int components = 0;
    (void)gs::render::decodeImage(gs::fuzz::view(data, size), "fuzz.png", &components);
  });
  return 0;
}
