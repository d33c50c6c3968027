// qnv::parseTilesetIndex (index.qnvt) and qnv::parseInteriorParts (a share's
// interior.qnvp): every count and range checked against the bytes; then
// brickPrefixBytes over every brick of an accepted index; scanInteriorParts (the merge's
// reading from disk) must accept exactly what parseInteriorParts accepts.
#include <cstring>

#include "fuzz_support.hpp"
#include "qnv/tileset.hpp"
#include "qnv/tileset_writer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  std::string error;
  if (const auto index = gs::qnv::parseTilesetIndex(bytes, "fuzz.qnvt", error))
    for (const gs::qnv::TilesetBrick& b : index->bricks)
      for (std::uint64_t n : {std::uint64_t{0}, std::uint64_t{1}, b.vectorCount / 2, b.vectorCount})
        (void)gs::qnv::brickPrefixBytes(b, index->header, n);
  gs::qnv::TilesetOptions cut;
  const bool parsed = gs::qnv::parseInteriorParts(bytes, "fuzz.qnvp", cut, error).has_value();
  // The merge's on-disk scan accepts exactly what the parser accepts.
  const gs::qnv::PartReader read = [&](std::uint64_t offset, std::size_t n, char* out) {
    if (offset > size || n > size - offset) __builtin_trap();
    std::memcpy(out, data + offset, n);
  };
  const auto spans = gs::qnv::scanInteriorParts(size, read, "fuzz.qnvp", cut, error);
  if (spans.has_value() != parsed) __builtin_trap();
  if (spans)
    for (const gs::qnv::InteriorPartSpan& span : *spans)
      (void)gs::qnv::loadInteriorEntries(span, read);
  return 0;
}
