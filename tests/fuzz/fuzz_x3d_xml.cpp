// The X3D XML encoding (encodings/src/x3d_xml.cpp: expat, the translation into Classic VRML
// text, the diagnostics moved back onto the XML) on any bytes, whole and streamed in two
// pieces (fuzz_x3d.hpp); every input starts '<'.
#include "fuzz_x3d.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::parseX3dEncoding(data, size, '<', "fuzz.x3d");
  return 0;
}
