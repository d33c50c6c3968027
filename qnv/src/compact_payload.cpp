#include "compact_payload.hpp"
#include "morton.hpp"

#include <algorithm>
#include <vector>

#include <zstd.h>

#include "qnv/record.hpp"

namespace gs::qnv::detail {

namespace {

constexpr int kZstdLevel = 9;

// Appends `planes` compressed with zstd at `level` as one frame (its content size set),
// ending a zstd block before each offset of `blockStarts` (ascending byte offsets into
// `planes`), so that each run of similar planes gets its own literal table; any zstd
// decoder reads the frame as one. Appends nothing on a zstd failure.
void appendZstd(std::string& out, const std::string& planes, int level,
                std::span<const std::size_t> blockStarts) {
  // Room for every block's 3-byte header on top of zstd's own bound, and a little slack.
  const std::size_t bound = ZSTD_compressBound(planes.size()) + 3 * (blockStarts.size() + 1) + 16;
  const std::size_t start = out.size();
  out.resize(start + bound);
  ZSTD_CCtx* context = ZSTD_createCCtx();
  bool ok = context != nullptr &&
            !ZSTD_isError(ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, level)) &&
            !ZSTD_isError(ZSTD_CCtx_setPledgedSrcSize(context, planes.size()));
  ZSTD_outBuffer to{out.data() + start, bound, 0};
  std::size_t from = 0;
  for (std::size_t b = 0; ok && b <= blockStarts.size(); ++b) {
    const bool last = b == blockStarts.size();
    const std::size_t end = last ? planes.size() : std::clamp(blockStarts[b], from, planes.size());
    if (!last && end == from) continue;  // no bytes since the last block
    ZSTD_inBuffer in{planes.data() + from, end - from, 0};
    const ZSTD_EndDirective mode = last ? ZSTD_e_end : ZSTD_e_flush;
    for (;;) {  // until this block's bytes are in and out
      const std::size_t left = ZSTD_compressStream2(context, &to, &in, mode);
      ok = !ZSTD_isError(left) && (left == 0 || to.pos < to.size);
      if (!ok || (left == 0 && in.pos == in.size)) break;
    }
    from = end;
  }
  ZSTD_freeCCtx(context);
  out.resize(ok ? start + to.pos : start);
}

}  // namespace

void appendZstdSmaller(std::string& out, const std::string& planes, int level,
                       std::span<const std::size_t> blockStarts, bool tryOneBlock) {
  std::string split, whole;
  appendZstd(split, planes, level, blockStarts);
  if (tryOneBlock) appendZstd(whole, planes, level, {});
  // The smaller of those made; nothing when zstd failed both (the caller writes it plain).
  if (whole.empty() || (!split.empty() && split.size() <= whole.size()))
    out += split;
  else
    out += whole;
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
  std::vector<std::size_t> blockStarts;
  auto appendPlane = [&](auto field) {
    blockStarts.push_back(planes.size());  // a zstd block per plane
    for (const auto& entry : sorted)
      planes.push_back(static_cast<char>(field(entry.second) & 0xffu));
  };
  appendPlane([](std::uint64_t r) { return directionCell(r) >> 8; });
  appendPlane([](std::uint64_t r) { return directionCell(r); });
  appendPlane([](std::uint64_t r) { return magnitudeCode(r) >> 8; });
  appendPlane([](std::uint64_t r) { return magnitudeCode(r); });
  appendPlane([](std::uint64_t r) { return static_cast<std::uint32_t>(r); });
  // A zstd block per plane pays for its own literal table: more than it saves in the
  // smallest packets (KiCad's, at 1376 bytes), so the smaller of the two is kept.
  appendZstdSmaller(out, planes, kZstdLevel, blockStarts, true);
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
