// formats::readNifti on any bytes (both byte orders, every datatype, scaling, forms).
#include "formats/volume_readers.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors(
      [&] { (void)gs::formats::readNifti(gs::fuzz::view(data, size), "fuzz.nii"); });
  return 0;
}
