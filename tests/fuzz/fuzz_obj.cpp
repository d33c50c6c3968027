// formats::readObj on any bytes.
#include "formats/mesh_readers.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors(
      [&] { (void)gs::formats::readObj(gs::fuzz::view(data, size), "fuzz.obj"); });
  return 0;
}
