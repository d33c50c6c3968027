// NRRD: the header, then the attached data (line skip, byte skip, raw / ascii / gzip), as
// session/volume_input.cpp reads a .nrrd file. Detached data files are not opened.
#include "base/gzip.hpp"
#include "formats/volume_readers.hpp"
#include "fuzz_support.hpp"
#include "qnv/volume_slabs.hpp"

#include <algorithm>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = gs::fuzz::view(data, size);
  // The slab readers' parse (docs/out-of-core.md): multi-file forms, larger grids.
  gs::fuzz::expectingErrors([&] {
    gs::formats::NrrdParseOptions multi;
    multi.multiFile = true;
    multi.maxVoxels = gs::qnv::kMaxSlabVolumeVoxels;
    multi.maxDataFiles = 4096;
    (void)gs::formats::parseNrrdHeader(bytes, "fuzz.nrrd", multi);
  });
  gs::fuzz::expectingErrors([&] {
    const gs::formats::NrrdHeader h = gs::formats::parseNrrdHeader(bytes, "fuzz.nrrd");
    if (!h.dataFile.empty() || h.dataOffset > bytes.size()) return;
    std::string_view attached = bytes.substr(h.dataOffset);
    if (h.encoding != gs::formats::NrrdHeader::Encoding::gzip) {
      (void)gs::formats::decodeNrrdData(h, attached, "fuzz.nrrd");
      return;
    }
    // As session/src/volume_input.cpp: lines skipped in the compressed bytes.
    attached = gs::formats::skipNrrdLines(attached, h.lineSkip, "fuzz.nrrd");
    const std::size_t skip = h.byteSkip > 0 ? static_cast<std::size_t>(h.byteSkip) : 0;
    const std::size_t cap = std::min<std::size_t>(h.dataBytes() + skip + 64, 64u << 20);
    (void)gs::formats::decodeNrrdData(h, gs::base::gunzip(attached, cap), "fuzz.nrrd");
  });
  return 0;
}
