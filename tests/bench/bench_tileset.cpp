// A tileset against the single stream (docs/qnv-format.md, "Tilesets", "Measured"): reads
// CThead (gzip, int16 big-endian, 256 x 256 x 113, spacing 1 1 2), keeps the top
// FRACTION of its voxels, and prints for each coding the single stream's bytes and encode
// time (gradients, selection, quantization, sort, packets) against the tileset's
// (gradients, selection, octree assignment, per-brick quantization, packets, merge):
// bricks, depth, index bytes, total bytes. Thread CPU time, best of 3, one thread.
//
//   bench_tileset [CThead.raw.gz] [FRACTION]
#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"

namespace qnv = gs::qnv;

namespace {

double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double best(const std::function<void()>& run) {
  double fastest = 1e30;
  for (int i = 0; i < 3; ++i) {
    const double t0 = cpuSeconds();
    run();
    fastest = std::min(fastest, cpuSeconds() - t0);
  }
  return fastest;
}

bool readCThead(const std::string& path, qnv::Volume& v) {
  v.dims = {256, 256, 113};
  v.spacing = {1, 1, 2};
  std::vector<unsigned char> bytes(v.voxelCount() * 2);
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) return false;
  const int n = gzread(f, bytes.data(), static_cast<unsigned>(bytes.size()));
  gzclose(f);
  if (n != static_cast<int>(bytes.size())) return false;
  v.samples.resize(v.voxelCount());
  for (std::size_t i = 0; i < v.samples.size(); ++i)
    v.samples[i] =
        static_cast<float>(static_cast<std::int16_t>((bytes[2 * i] << 8) | bytes[2 * i + 1]));
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string path =
      argc > 1 ? argv[1] : std::string(GS_CORPUS_DIR) + "/volume/cthead/CThead.raw.gz";
  const double fraction = argc > 2 ? std::atof(argv[2]) : 0.091;
  qnv::Volume volume;
  if (!readCThead(path, volume)) {
    std::fprintf(stderr, "bench_tileset: cannot read %s\n", path.c_str());
    return 1;
  }
  qnv::VolumeEncodeOptions options;
  options.selection.fraction = fraction;
  std::printf("CThead top %.1f%%, one thread, best of 3 (CPU s)\n", 100 * fraction);
  std::printf("%-8s %6s | %11s %7s | %6s %5s %5s %11s %11s %7s\n", "coding", "packet", "stream B",
              "s", "bricks", "depth", "leaf", "index B", "total B", "s");
  for (const auto& [encoding, packetBytes] : {std::pair{qnv::PacketEncoding::plain, 1376u},
                                              {qnv::PacketEncoding::entropy, 1376u},
                                              {qnv::PacketEncoding::entropy, 16384u}}) {
    const qnv::WriteOptions write{packetBytes, encoding};
    std::size_t streamBytes = 0;
    const double streamSeconds = best(
        [&] { streamBytes = qnv::writeStream(qnv::encodeVolume(volume, options), write).size(); });
    qnv::TilesetFiles files;
    qnv::TilesetOptions cut;
    cut.write = write;
    const double tilesetSeconds =
        best([&] { files = qnv::buildTileset(qnv::selectVolumeVectors(volume, options), cut); });
    const std::size_t indexBytes = qnv::serializeTilesetIndex(files.index).size();
    std::size_t total = indexBytes, leaves = 0;
    for (const qnv::BrickFile& b : files.bricks) {
      total += b.bytes.size();
      leaves += b.brick.level == files.index.depth;
    }
    std::printf("%-8s %6u | %11zu %7.3f | %6zu %5u %5zu %11zu %11zu %7.3f\n",
                encoding == qnv::PacketEncoding::plain ? "plain" : "entropy", packetBytes,
                streamBytes, streamSeconds, files.bricks.size(),
                static_cast<unsigned>(files.index.depth), leaves, indexBytes, total,
                tilesetSeconds);
  }
  return 0;
}
