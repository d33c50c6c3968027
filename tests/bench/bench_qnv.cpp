// QNV codec figures (docs/qnv-format.md, "Measured"): encode and decode throughput on
// one thread, the paper's figure 2 fractions of CThead, sizes of KiCad worlds and the
// bunny as .wrl/.ply, gzip and .qnv, and the magnitude quantization error.
//
//   bench_qnv [corpus folder]      (default ../shared/corpus, run from the project root)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <zlib.h>

#include "base/file.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "scene/world_triangles.hpp"
#include "session/mesh_input.hpp"
#include "session/volume_input.hpp"
#include "session/world.hpp"

#include <glm/geometric.hpp>

namespace qnv = gs::qnv;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::size_t gzipSize(const std::string& bytes) {
  uLongf size = compressBound(static_cast<uLong>(bytes.size()));
  std::vector<Bytef> out(size);
  compress2(out.data(), &size, reinterpret_cast<const Bytef*>(bytes.data()),
            static_cast<uLong>(bytes.size()), 9);
  return size + 12;  // gzip's header and trailer are 12 bytes longer than zlib's
}

std::size_t fileSize(const std::filesystem::path& p) {
  std::error_code ec;
  const auto n = std::filesystem::file_size(p, ec);
  return ec ? 0 : static_cast<std::size_t>(n);
}

void decodeBenchmark(const qnv::EncodedVectors& e) {
  const std::string stream = qnv::writeStream(e);
  const qnv::Dequantizer dq(e.header);
  std::vector<qnv::DecodedVector> block(4096);
  const std::size_t n = e.records.size();
  double best = 1e9;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = Clock::now();
    for (std::size_t first = 0; first < n; first += block.size())
      dq.decode(e.records.data() + first, std::min(block.size(), n - first), block.data());
    best = std::min(best, since(t0));
  }
  std::printf(
      "decode, table lookups into a 4096-vector block:  %8.1f M vectors/s (%zu vectors, best of "
      "5)\n",
      static_cast<double>(n) / best / 1e6, n);
  std::vector<qnv::DecodedVector> all(n);
  best = 1e9;
  for (int rep = 0; rep < 5; ++rep) {
    const auto t0 = Clock::now();
    dq.decode(e.records.data(), n, all.data());
    best = std::min(best, since(t0));
  }
  std::printf("decode into one %5.0f MB array:                  %8.1f M vectors/s\n",
              static_cast<double>(n * sizeof(qnv::DecodedVector)) / 1e6,
              static_cast<double>(n) / best / 1e6);
  for (std::size_t chunk : {std::size_t{1400}, std::size_t{1} << 16}) {
    best = 1e9;
    std::uint64_t got = 0;
    for (int rep = 0; rep < 3; ++rep) {
      qnv::StreamDecoder d("bench");
      got = 0;
      const auto t0 = Clock::now();
      const auto sink = [&](std::uint64_t, std::span<const qnv::DecodedVector> v) {
        got += v.size();
      };
      for (std::size_t at = 0; at < stream.size(); at += chunk)
        d.feed(std::string_view(stream).substr(at, chunk), sink);
      d.finish(sink);
      best = std::min(best, since(t0));
    }
    std::printf(
        "StreamDecoder, %6zu-byte chunks, CRC checked:    %8.1f M vectors/s (%llu vectors, %.0f "
        "MB/s)\n",
        chunk, static_cast<double>(got) / best / 1e6, static_cast<unsigned long long>(got),
        static_cast<double>(stream.size()) / best / 1e6);
  }
}

void magnitudeError(const char* what, const qnv::EncodedVectors& reference,
                    const std::vector<float>& exact) {
  (void)reference;
  std::vector<float> sorted = exact;
  std::sort(sorted.begin(), sorted.end());
  const float lo = sorted.front(), hi = sorted.back();
  for (auto mapping : {qnv::MagnitudeMapping::logarithmic, qnv::MagnitudeMapping::linear}) {
    std::vector<double> rel;
    rel.reserve(exact.size());
    for (float a : exact)
      rel.push_back(std::abs(qnv::reconstructMagnitude(qnv::quantizeMagnitude(a, mapping, lo, hi),
                                                       mapping, lo, hi) -
                             a) /
                    a);
    std::sort(rel.begin(), rel.end());
    std::printf(
        "  %-8s %-11s relative error: median %.2e, 99th %.2e, max %.2e (range %.3g .. %.3g)\n",
        what, mapping == qnv::MagnitudeMapping::logarithmic ? "logarithmic" : "linear",
        rel[rel.size() / 2], rel[rel.size() * 99 / 100], rel.back(), lo, hi);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path corpus = argc > 1 ? argv[1] : "../shared/corpus";
  const std::filesystem::path cthead = corpus / "volume/cthead/CThead.nhdr";
  if (!std::filesystem::exists(cthead)) {
    std::fprintf(stderr, "bench_qnv: no %s (run from the project root with ../shared beside it)\n",
                 cthead.string().c_str());
    return 1;
  }
  std::printf("== CThead (%s) ==\n", cthead.string().c_str());
  auto t0 = Clock::now();
  const qnv::Volume volume = gs::session::loadVolumeFile(cthead.string());
  std::printf("read and convert: %.3f s (%zu voxels)\n", since(t0), volume.voxelCount());
  qnv::EncodeSummary summary;
  double best = 1e9;
  qnv::EncodedVectors all;
  for (int rep = 0; rep < 3; ++rep) {
    t0 = Clock::now();
    all = qnv::encodeVolume(volume, {}, &summary);
    best = std::min(best, since(t0));
  }
  std::printf("encode every voxel: %.3f s = %.1f M voxels/s; %llu voxels have a gradient\n", best,
              static_cast<double>(volume.voxelCount()) / best / 1e6,
              static_cast<unsigned long long>(summary.candidates));
  decodeBenchmark(all);

  std::printf("\nfigure 2 fractions (of all %zu voxels):\n", volume.voxelCount());
  std::printf("  %-7s %10s %12s %12s %10s %10s %8s\n", "top", "vectors", ".qnv bytes", "compact",
              "bits/vec", "compact", "encode");
  for (double f : {0.012, 0.035, 0.091, 1.0}) {
    qnv::VolumeEncodeOptions o;
    o.selection.fraction = f;
    t0 = Clock::now();
    const qnv::EncodedVectors e = qnv::encodeVolume(volume, o, &summary);
    const double seconds = since(t0);
    const std::string plain = qnv::writeStream(e);
    t0 = Clock::now();
    const std::string compact =
        qnv::writeStream(e, {qnv::kDefaultPacketBytes, qnv::PacketEncoding::compact});
    const double compactSeconds = since(t0);
    const double n = static_cast<double>(e.records.size());
    std::printf("  %5.1f%% %10zu %12zu %12zu %10.1f %10.1f %7.3fs (zstd %.2fs)\n", f * 100,
                e.records.size(), plain.size(), compact.size(),
                8.0 * static_cast<double>(plain.size() - qnv::kHeaderBytes) / n,
                8.0 * static_cast<double>(compact.size() - qnv::kHeaderBytes) / n, seconds,
                compactSeconds);
  }
  {
    std::vector<float> exact;
    for (std::uint32_t z = 1; z + 1 < volume.dims.z; z += 3)
      for (std::uint32_t y = 1; y + 1 < volume.dims.y; ++y)
        for (std::uint32_t x = 1; x + 1 < volume.dims.x; ++x) {
          const float gx =
              (volume.at(x + 1, y, z) - volume.at(x - 1, y, z)) / (2 * volume.spacing.x);
          const float gy =
              (volume.at(x, y + 1, z) - volume.at(x, y - 1, z)) / (2 * volume.spacing.y);
          const float gz =
              (volume.at(x, y, z + 1) - volume.at(x, y, z - 1)) / (2 * volume.spacing.z);
          const float m = std::sqrt(gx * gx + gy * gy + gz * gz);
          if (m > 0) exact.push_back(m);
        }
    std::printf("\nmagnitude quantization (15 bits):\n");
    magnitudeError("CThead", all, exact);
  }

  std::printf("\n== surfaces: source, gzip -9, .qnv (all triangles) ==\n");
  std::printf("  %-44s %10s %10s %10s %10s %10s %8s\n", "file", "bytes", "gzip", "triangles",
              ".qnv", "compact", "encode");
  std::vector<std::filesystem::path> surfaces = {corpus / "mesh/bunny/bun_zipper.ply"};
  std::vector<std::filesystem::path> kicad;
  for (const auto& entry : std::filesystem::directory_iterator(corpus / "vrml/kicad"))
    if (entry.path().extension() == ".wrl") kicad.push_back(entry.path());
  std::sort(kicad.begin(), kicad.end(),
            [](const auto& a, const auto& b) { return fileSize(a) > fileSize(b); });
  surfaces.insert(surfaces.end(), kicad.begin(), kicad.end());
  std::size_t totals[5] = {0, 0, 0, 0, 0};
  for (const auto& p : surfaces) {
    std::string bytes, error;
    if (!gs::base::readFile(p.string(), bytes, error)) {
      std::printf("  %-44s (missing: %s)\n", p.filename().string().substr(0, 44).c_str(),
                  error.c_str());
      continue;
    }
    t0 = Clock::now();
    qnv::TriangleMesh mesh =
        p.extension() == ".ply"
            ? gs::session::loadMeshFile(p.string())
            : gs::scene::worldTriangles(gs::session::loadWorld(p.string()).scene);
    const qnv::EncodedVectors e = qnv::encodeSurface(mesh, {}, &summary);
    const double seconds = since(t0);
    const std::size_t sizes[5] = {
        bytes.size(), gzipSize(bytes), mesh.triangleCount(), qnv::writeStream(e).size(),
        qnv::writeStream(e, {qnv::kDefaultPacketBytes, qnv::PacketEncoding::compact}).size()};
    const bool isKicad = p.extension() == ".wrl";
    if (isKicad)
      for (int i = 0; i < 5; ++i) totals[i] += sizes[i];
    const std::size_t rank = static_cast<std::size_t>(&p - surfaces.data());
    if (!isKicad || rank <= 3)
      std::printf("  %-44s %10zu %10zu %10zu %10zu %10zu %7.3fs\n",
                  p.filename().string().substr(0, 44).c_str(), sizes[0], sizes[1], sizes[2],
                  sizes[3], sizes[4], seconds);
    if (p.extension() == ".ply") {
      std::vector<float> exact;
      for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                        b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        const float area = 0.5f * glm::length(glm::cross(b - a, c - a));
        if (area > 0) exact.push_back(area);
      }
      magnitudeError("bunny", e, exact);
    }
  }
  std::printf("  %-44s %10zu %10zu %10zu %10zu %10zu\n", "all KiCad worlds together", totals[0],
              totals[1], totals[2], totals[3], totals[4]);
  return 0;
}
