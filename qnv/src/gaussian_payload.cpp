// The compact payload of Gaussian streams (StreamKind::gaussian): docs/splats.md,
// "QNV Gaussian streams". Planes as the vector's compact payload, then the further words
// byte by byte, most significant first, so that each plane holds one field's byte.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <zstd.h>

#include "compact_payload.hpp"
#include "morton.hpp"
#include "qnv/record.hpp"
#include "qnv/stream.hpp"

namespace gs::qnv {

float gaussianImportance(std::uint64_t first, std::uint64_t second, const StreamHeader& h) {
  const float step = (h.valueMax - h.valueMin) / 255.0f;
  const float lnArea = 2.0f * h.valueMin +
                       step * static_cast<float>(((second >> 32) & 255u) + ((second >> 24) & 255u));
  const float value =
      static_cast<float>(first & 255u) / 255.0f * std::numbers::pi_v<float> * std::exp(lnArea);
  return std::isfinite(value) ? value : 0.0f;
}

}  // namespace gs::qnv

namespace gs::qnv::detail {

namespace {

constexpr int kGaussianZstdLevel = 19;
constexpr std::size_t kTryOneBlockBelow = 512;  // splats in a packet

// The SH words (record 2 on) hold coefficients from the top bit down: 9 of 5 bits (SH
// degree 1), then 4 bits each (15 of degree 2, 21 of degree 3). Each becomes a plane.
int shPlanes(std::uint32_t words) {
  constexpr int kCoefficients[] = {0, 0, 0, 9, 24, 45};  // by words: SH degree + 2
  return words <= 5 ? kCoefficients[words] : 45;
}
// The A code of the quantized splat's importance; `quantize` is made once per packet from
// the stream's magnitude range (two logarithms a splat saved).
std::uint32_t predictedCode(std::uint64_t first, std::uint64_t second, const StreamHeader& h,
                            const MagnitudeQuantizer& quantize) {
  return quantize(gaussianImportance(first, second, h));
}

}  // namespace

void appendGaussianCompactPayload(std::string& out, std::span<const std::uint64_t> records,
                                  std::uint32_t words, const StreamHeader& header) {
  const std::size_t n = records.size() / words;
  std::vector<std::pair<std::uint32_t, std::size_t>> sorted;
  sorted.reserve(n);
  for (std::size_t i = 0; i < n; ++i) sorted.emplace_back(recordMorton(records[i * words]), i);
  std::sort(sorted.begin(), sorted.end());
  std::string planes;
  planes.reserve(n * (5 + 8 * words));
  std::uint32_t previous = 0;
  for (const auto& [code, i] : sorted) {
    appendVarint(planes, code - previous);
    previous = code;
  }
  // zstd blocks: one per field, so that each gets its own literal table (a zstd frame's
  // blocks decode as one; the splitting is the encoder's alone).
  std::vector<std::size_t> blockStarts;
  auto appendPlane = [&](auto field, bool delta = false, bool newBlock = true) {
    if (newBlock) blockStarts.push_back(planes.size());
    unsigned char last = 0;
    for (const auto& entry : sorted) {
      const auto b = static_cast<unsigned char>(field(entry.second) & 0xffu);
      planes.push_back(static_cast<char>(delta ? static_cast<unsigned char>(b - last) : b));
      last = b;
    }
  };
  appendPlane([&](std::size_t i) { return directionCell(records[i * words]) >> 8; });
  appendPlane([&](std::size_t i) { return directionCell(records[i * words]); });
  // A as its difference from the importance of the quantized splat (0 as our encoder
  // writes it), so that it costs nearly nothing.
  const MagnitudeQuantizer quantize(header.mapping, header.magnitudeMin, header.magnitudeMax);
  std::vector<std::uint16_t> residual(n);
  for (std::size_t i = 0; i < n; ++i)
    residual[i] = static_cast<std::uint16_t>(
        magnitudeCode(records[i * words]) -
        predictedCode(records[i * words], records[i * words + 1], header, quantize));
  appendPlane([&](std::size_t i) { return residual[i] >> 8u; });
  appendPlane([&](std::size_t i) { return residual[i]; }, false, false);
  appendPlane([&](std::size_t i) { return static_cast<std::uint32_t>(records[i * words]); });
  for (int shift = 56; shift >= 0; shift -= 8)
    appendPlane(
        [&](std::size_t i) { return static_cast<std::uint32_t>(records[i * words + 1] >> shift); },
        shift >= 16,  // colour and scales: as their Morton neighbours'
        shift != 48 && shift != 40 && shift != 24);  // blocks: colour, major and middle scale
  const int sh = shPlanes(words);
  for (int c = 0, at = 0; c < sh; at += gaussianShBits(c), ++c)
    appendPlane(
        [&](std::size_t i) { return readWordBits(&records[i * words + 2], at, gaussianShBits(c)); },
        false, c == 0 || c == 9 || c == 24);  // a block per SH degree
  // The blocks' literal tables cost more than they save in a small packet (a stream's last
  // one, or a small --packet-bytes: 8-64 splats took 2-16% more bytes): below
  // kTryOneBlockBelow splats one block is tried too, and the smaller kept.
  appendZstdSmaller(out, planes, kGaussianZstdLevel, blockStarts, n < kTryOneBlockBelow);
}

bool decodeGaussianCompactPayload(std::string_view payload, std::size_t count, std::uint32_t words,
                                  const StreamHeader& header, std::uint64_t* out) {
  if (words < 2 || count == 0 || count % words != 0) return false;
  const std::size_t n = count / words;
  const MagnitudeQuantizer quantize(header.mapping, header.magnitudeMin, header.magnitudeMax);
  const int sh = shPlanes(words);
  const std::size_t fixedPlanes = 5 + 8 + static_cast<std::size_t>(sh);
  std::vector<unsigned char> planes(n * (5 + fixedPlanes));  // varints at most 5 bytes
  const std::size_t got =
      ZSTD_decompress(planes.data(), planes.size(), payload.data(), payload.size());
  if (ZSTD_isError(got) || got < n * (1 + fixedPlanes)) return false;
  std::size_t pos = 0;
  std::vector<std::uint32_t> morton(n);
  if (!readMortonGaps(planes.data(), got, pos, n, morton.data())) return false;
  if (got - pos != n * fixedPlanes) return false;
  const unsigned char* plane = planes.data() + pos;
  unsigned char last[6] = {};
  for (std::size_t i = 0; i < n; ++i) {
    RecordFields f;
    if (!planeFields(morton[i], plane, n, i, f)) return false;
    std::uint64_t word = 0;
    for (int b = 0; b < 8; ++b) {
      unsigned char v = plane[(5 + b) * n + i];
      if (b < 6) {  // colour and scales: differences from the previous splat's
        last[b] = static_cast<unsigned char>(last[b] + v);
        v = last[b];
      }
      word = (word << 8) | v;
    }
    f.a = 0;
    const std::uint32_t a = (predictedCode(packRecord(f), word, header, quantize) +
                             ((std::uint32_t{plane[2 * n + i]} << 8) | plane[3 * n + i])) &
                            0xffffu;
    if (a >= kMagnitudeSteps) return false;
    f.a = static_cast<std::uint16_t>(a);
    out[i * words] = packRecord(f);
    out[i * words + 1] = word;
    std::fill(out + i * words + 2, out + (i + 1) * words, std::uint64_t{0});
    for (int c = 0, at = 0; c < sh; at += gaussianShBits(c), ++c) {
      const std::uint32_t v = plane[(13 + c) * n + i];
      if (v >> gaussianShBits(c)) return false;
      writeWordBits(out + i * words + 2, at, v, gaussianShBits(c));
    }
  }
  return true;
}

}  // namespace gs::qnv::detail
