// The entropy packet payload (either layout: flag bit 2 picks the fast one) decoded alone, under a
// stream model block read from the input (docs/qnv-format.md, "Compact coding" and "Stream model").
// Input: byte 0 picks the header (bit 0: a 48 x 44 x 24 volume, its voxel grid, else a surface);
// bytes 1-2 the record count - 1 (mod 8191); bytes 3-4 the model's length L (0: no model); then L
// model bytes (as far as the input goes), then the payload. A fast-layout payload is also decoded
// straight to vectors, which must agree with the records: the same verdict, the same vectors.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "entropy_payload.hpp"
#include "fuzz_support.hpp"
#include "qnv/decoder.hpp"
#include "qnv/stream.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  gs::qnv::StreamHeader header;
  if (data[0] & 1) {
    header.kind = gs::qnv::StreamKind::volume;
    header.volumeDims = {48, 44, 24};
  }
  const std::size_t count = 1 + ((data[1] | (data[2] << 8)) % 8191);
  const std::size_t modelBytes = std::min<std::size_t>(data[3] | (data[4] << 8), size - 5);
  header.model = std::string(gs::fuzz::view(data + 5, modelBytes));
  const auto grid = gs::qnv::detail::PositionGrid::forHeader(header);
  if (!grid.modelValid) return 0;
  std::vector<std::uint64_t> out(count);
  const std::string_view payload = gs::fuzz::view(data + 5 + modelBytes, size - 5 - modelBytes);
  const bool records = gs::qnv::detail::decodeEntropyPayload(payload, count, grid, out.data());
  if (gs::qnv::detail::isFastLayout(payload)) {
    const gs::qnv::Dequantizer dequantizer(header);
    const gs::qnv::detail::VectorTables tables(dequantizer, grid);
    std::vector<gs::qnv::DecodedVector> vectors(count), expected(count);
    const bool direct =
        gs::qnv::detail::decodeFastVectors(payload, count, grid, tables, vectors.data());
    if (direct != records) std::abort();
    dequantizer.decode(out.data(), count, expected.data());
    if (records && std::memcmp(vectors.data(), expected.data(), count * sizeof expected[0]) != 0)
      std::abort();
  }
  return 0;
}
