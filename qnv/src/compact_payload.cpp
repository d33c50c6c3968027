#include "compact_payload.hpp"
#include "morton.hpp"

#include <algorithm>
#include <vector>

#include <zstd.h>

#include "qnv/record.hpp"

namespace gs::qnv::detail {

namespace {

constexpr int kZstdLevel = 9;

}  // namespace

void appendZstd(std::string& out, const std::string& planes, int level) {
  const std::size_t bound = ZSTD_compressBound(planes.size());
  const std::size_t start = out.size();
  out.resize(start + bound);
  const std::size_t written =
      ZSTD_compress(out.data() + start, bound, planes.data(), planes.size(), level);
  out.resize(ZSTD_isError(written) ? start : start + written);
}

void appendCompactPayload(std::string& out, std::span<const std::uint64_t> records) {
  std::vector<std::pair<std::uint32_t, std::uint64_t>> sorted;
  sorted.reserve(records.size());
  for (std::uint64_t r : records) sorted.emplace_back(recordMorton(r), r);
  std::sort(sorted.begin(), sorted.end());

  const std::size_t n = sorted.size();
  std::string planes;
  planes.reserve(n * 9);
  std::uint32_t previous = 0;
  for (const auto& [code, r] : sorted) {  // Morton deltas, LEB128
    appendVarint(planes, code - previous);
    previous = code;
  }
  auto appendPlane = [&](auto field) {
    for (const auto& entry : sorted)
      planes.push_back(static_cast<char>(field(entry.second) & 0xffu));
  };
  appendPlane([](std::uint64_t r) { return directionCell(r) >> 8; });
  appendPlane([](std::uint64_t r) { return directionCell(r); });
  appendPlane([](std::uint64_t r) { return magnitudeCode(r) >> 8; });
  appendPlane([](std::uint64_t r) { return magnitudeCode(r); });
  appendPlane([](std::uint64_t r) { return static_cast<std::uint32_t>(r); });
  appendZstd(out, planes, kZstdLevel);
}

bool decodeCompactPayload(std::string_view payload, std::size_t count, std::uint64_t* out) {
  if (count == 0) return payload.empty();
  const std::size_t maxPlanes = count * 10;  // varints take at most 5 bytes, planes 5
  std::vector<unsigned char> planes(maxPlanes);
  const std::size_t got =
      ZSTD_decompress(planes.data(), planes.size(), payload.data(), payload.size());
  if (ZSTD_isError(got) || got < count * 6) return false;
  std::size_t pos = 0;  // Morton codes into out[] for now; the fields follow
  if (!readMortonGaps(planes.data(), got, pos, count, out)) return false;
  if (got - pos != count * 5) return false;
  const unsigned char* plane = planes.data() + pos;
  for (std::size_t i = 0; i < count; ++i) {
    RecordFields f;
    if (!planeFields(static_cast<std::uint32_t>(out[i]), plane, count, i, f)) return false;
    f.a = static_cast<std::uint16_t>((std::uint32_t{plane[2 * count + i]} << 8) |
                                     plane[3 * count + i]);
    if (f.a >= kMagnitudeSteps) return false;
    out[i] = packRecord(f);
  }
  return true;
}

}  // namespace gs::qnv::detail
