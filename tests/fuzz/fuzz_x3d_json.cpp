// The X3D JSON encoding (encodings/src/x3d_json.cpp: the nesting scan, nlohmann-json, the
// translation into XML and Classic VRML text, the diagnostics moved back onto the JSON)
// on any bytes, whole and streamed in two pieces (fuzz_x3d.hpp); every input starts '{'.
#include "fuzz_x3d.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  gs::fuzz::parseX3dEncoding(data, size, '{', "fuzz.x3dj");
  return 0;
}
