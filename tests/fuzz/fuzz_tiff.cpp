// formats::readTiff on any bytes: libtiff through memory client procedures (classic and
// BigTIFF, strips and tiles, its codecs), the OME-XML of the first page, every page.
#include "formats/tiff_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors(
      [&] { (void)gs::formats::readTiff(gs::fuzz::view(data, size), "fuzz.tif"); });
  return 0;
}
