// `ghostspace info FILE.qnv`.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "qnv/decoder.hpp"
#include "qnv/record.hpp"

namespace gs::app {

namespace {

constexpr int kHistogramBins = 10;

const char* kindName(qnv::StreamKind kind) {
  return kind == qnv::StreamKind::volume     ? "volume"
         : kind == qnv::StreamKind::gaussian ? "Gaussian splat"
                                             : "surface";
}

}  // namespace

int runQnvInfo(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "ghostspace: cannot open '%s'\n", path.c_str());
    return 1;
  }
  qnv::StreamDecoder decoder(path);
  std::array<std::uint64_t, kHistogramBins> histogram{};
  auto bin = [&](float magnitude) {
    const qnv::StreamHeader& h = *decoder.header();
    double t = 0.0;
    if (h.magnitudeMax > h.magnitudeMin) {
      t = h.mapping == qnv::MagnitudeMapping::logarithmic
              ? std::log(magnitude / h.magnitudeMin) / std::log(h.magnitudeMax / h.magnitudeMin)
              : (magnitude - h.magnitudeMin) / (h.magnitudeMax - h.magnitudeMin);
    }
    return std::clamp(static_cast<int>(t * kHistogramBins), 0, kHistogramBins - 1);
  };
  // The fewest bits every magnitude code fits (`encode --magnitude-bits`): codes come back
  // from the decoded magnitudes, which are their cells' centres.
  int magnitudeBits = 1;
  std::optional<qnv::MagnitudeQuantizer> quantizeA;
  std::vector<bool> codeSeen(qnv::kMagnitudeSteps);
  std::uint64_t distinctCodes = 0;
  const auto sink = [&](std::uint64_t, std::span<const qnv::DecodedVector> vectors) {
    const qnv::StreamHeader& h = *decoder.header();
    if (!quantizeA) quantizeA.emplace(h.mapping, h.magnitudeMin, h.magnitudeMax);
    for (const qnv::DecodedVector& v : vectors) {
      ++histogram[static_cast<std::size_t>(bin(v.magnitude))];
      const std::uint32_t code = (*quantizeA)(v.magnitude);
      if (!codeSeen[code]) ++distinctCodes;
      codeSeen[code] = true;
      while (magnitudeBits < qnv::kMagnitudeBits &&
             qnv::roundMagnitudeCode(code, magnitudeBits) != code)
        ++magnitudeBits;
    }
  };
  // A Gaussian stream's importance is the A of each splat's first record.
  decoder.setRecordSink([&](std::uint64_t, std::span<const std::uint64_t> records) {
    const qnv::StreamHeader& h = *decoder.header();
    std::vector<qnv::DecodedVector> firsts;
    for (std::size_t i = 0; i < records.size(); i += h.recordsPerElement()) {
      qnv::DecodedVector v{};
      v.magnitude = qnv::reconstructMagnitude(qnv::magnitudeCode(records[i]), h.mapping,
                                              h.magnitudeMin, h.magnitudeMax);
      firsts.push_back(v);
    }
    sink(0, firsts);
  });
  std::string chunk(1 << 20, '\0');
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    if (!decoder.feed(std::string_view(chunk.data(), static_cast<std::size_t>(in.gcount())), sink))
      break;
  }
  decoder.finish(sink);
  if (!decoder.header()) {
    std::fprintf(stderr, "ghostspace: %s\n", decoder.error().c_str());
    return 1;
  }
  const qnv::StreamHeader& h = *decoder.header();
  const qnv::DecoderStats& st = decoder.stats();
  std::printf("%s: QNV version %u, %s stream\n", path.c_str(), qnv::kFormatVersion,
              kindName(h.kind));
  std::printf("  vectors     %llu in %llu packets of up to %u records (%s)\n",
              static_cast<unsigned long long>(h.vectorCount),
              static_cast<unsigned long long>(h.packetCount()), h.recordsPerPacket(),
              h.encoding == qnv::PacketEncoding::compact   ? "compact"
              : h.encoding == qnv::PacketEncoding::entropy ? "entropy"
                                                           : "plain");
  std::printf("  bytes       %llu (%.2f bits per vector, header included)\n",
              static_cast<unsigned long long>(st.bytesFed),
              h.vectorCount
                  ? 8.0 * static_cast<double>(st.bytesFed) / static_cast<double>(h.vectorCount)
                  : 0.0);
  std::printf("  bounds      %g %g %g .. %g %g %g\n", h.boundsMin.x, h.boundsMin.y, h.boundsMin.z,
              h.boundsMax.x, h.boundsMax.y, h.boundsMax.z);
  if (h.kind == qnv::StreamKind::gaussian)
    std::printf("  splats      %llu of %u records each, SH degree %u, scales %g .. %g\n",
                static_cast<unsigned long long>(h.vectorCount / h.recordsPerElement()),
                h.recordsPerElement(), h.shDegree, std::exp(h.valueMin), std::exp(h.valueMax));
  if (h.kind == qnv::StreamKind::volume)
    std::printf("  volume      %u x %u x %u voxels, spacing %g %g %g, values %g .. %g\n",
                h.volumeDims.x, h.volumeDims.y, h.volumeDims.z, h.voxelSpacing.x, h.voxelSpacing.y,
                h.voxelSpacing.z, h.valueMin, h.valueMax);
  std::printf("  magnitude   %s, %g .. %g",
              h.mapping == qnv::MagnitudeMapping::logarithmic ? "logarithmic" : "linear",
              h.magnitudeMin, h.magnitudeMax);
  // Exact codes fit fewer bits by chance with odds 2^-(dropped bits x distinct codes):
  // reported when those are under 2^-32.
  const int dropped = qnv::kMagnitudeBits - magnitudeBits;
  if (dropped > 0 && distinctCodes * static_cast<std::uint64_t>(dropped) >= 32)
    std::printf(", codes rounded to %d of 15 bits (encode --magnitude-bits)", magnitudeBits);
  std::printf("\n");
  std::printf("  opacity     Gaussian, sigma %g, scale %g\n", h.profile.sigma,
              h.profile.opacityScale);
  std::printf(
      "  decoded     %llu vectors in %llu packets; %llu damaged, %llu missing, %llu bytes "
      "skipped\n",
      static_cast<unsigned long long>(st.vectorsDecoded),
      static_cast<unsigned long long>(st.packetsDecoded),
      static_cast<unsigned long long>(st.packetsCorrupt),
      static_cast<unsigned long long>(st.packetsMissing),
      static_cast<unsigned long long>(st.bytesSkipped));
  std::printf("  magnitude histogram (%s bins, largest first):\n",
              h.mapping == qnv::MagnitudeMapping::logarithmic ? "logarithmic" : "linear");
  std::uint64_t most = 1;
  for (std::uint64_t n : histogram) most = std::max(most, n);
  for (int b = kHistogramBins - 1; b >= 0; --b) {
    auto edge = [&](int i) {
      const double t = static_cast<double>(i) / kHistogramBins;
      return h.mapping == qnv::MagnitudeMapping::logarithmic
                 ? h.magnitudeMin *
                       std::pow(static_cast<double>(h.magnitudeMax) / h.magnitudeMin, t)
                 : h.magnitudeMin + t * (static_cast<double>(h.magnitudeMax) - h.magnitudeMin);
    };
    const std::size_t n = histogram[static_cast<std::size_t>(b)];
    std::printf("    %10.4g .. %-10.4g %-20s %llu\n", edge(b), edge(b + 1),
                std::string(static_cast<std::size_t>(
                                20.0 * static_cast<double>(n) / static_cast<double>(most) + 0.5),
                            '#')
                    .c_str(),
                static_cast<unsigned long long>(n));
  }
  for (const std::string& w : decoder.warnings()) std::printf("  warning: %s\n", w.c_str());
  return 0;
}

}  // namespace gs::app
