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
    std::uint32_t d = code - previous;
    previous = code;
    while (d >= 0x80) {
      planes.push_back(static_cast<char>((d & 0x7f) | 0x80));
      d >>= 7;
    }
    planes.push_back(static_cast<char>(d));
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
  const std::size_t bound = ZSTD_compressBound(planes.size());
  const std::size_t start = out.size();
  out.resize(start + bound);
  const std::size_t written =
      ZSTD_compress(out.data() + start, bound, planes.data(), planes.size(), kZstdLevel);
  out.resize(ZSTD_isError(written) ? start : start + written);
}

bool decodeCompactPayload(std::string_view payload, std::size_t count, std::uint64_t* out) {
  if (count == 0) return payload.empty();
  const std::size_t maxPlanes = count * 10;  // varints take at most 5 bytes, planes 5
  std::vector<unsigned char> planes(maxPlanes);
  const std::size_t got =
      ZSTD_decompress(planes.data(), planes.size(), payload.data(), payload.size());
  if (ZSTD_isError(got) || got < count * 6) return false;
  std::size_t pos = 0;
  std::uint32_t code = 0;
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t d = 0;
    for (int shift = 0;; shift += 7) {
      if (pos >= got || shift > 28) return false;
      const unsigned char b = planes[pos++];
      d |= static_cast<std::uint32_t>(b & 0x7f) << shift;
      if (!(b & 0x80)) break;
    }
    code += d;
    out[i] = code;  // Morton code for now; the fields follow
  }
  if (got - pos != count * 5) return false;
  const unsigned char* plane = planes.data() + pos;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t m = static_cast<std::uint32_t>(out[i]);
    RecordFields f;
    f.x = static_cast<std::uint16_t>(compact3(m));
    f.y = static_cast<std::uint16_t>(compact3(m >> 1));
    f.z = static_cast<std::uint16_t>(compact3(m >> 2));
    const std::uint32_t dir = (std::uint32_t{plane[i]} << 8) | plane[count + i];
    f.theta = static_cast<std::uint8_t>(dir >> 6);
    f.phi = static_cast<std::uint8_t>(dir & 63u);
    f.a = static_cast<std::uint16_t>((std::uint32_t{plane[2 * count + i]} << 8) |
                                     plane[3 * count + i]);
    f.c = plane[4 * count + i];
    if (m >= (1u << 30) || dir >= kDirectionCells || f.a >= kMagnitudeSteps) return false;
    out[i] = packRecord(f);
  }
  return true;
}

}  // namespace gs::qnv::detail
