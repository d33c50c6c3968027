// formats::readDicom on any bytes: the element walk that bounds GDCM's allocations, then
// GDCM's ImageReader on a stream over the bytes (every transfer syntax it decodes).
#include "formats/dicom_reader.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::expectingErrors(
      [&] { (void)gs::formats::readDicom(gs::fuzz::view(data, size), "fuzz.dcm"); });
  return 0;
}
