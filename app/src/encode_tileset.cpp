// `ghostspace encode --tileset OUT/ [--bricks I/N] [--memory MB]` and `ghostspace tileset
// index OUT/`: options in, the library's tileset encodes (encode/tileset.hpp) called,
// their results printed.
#include "encode_tileset.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "app/commands.hpp"
#include "base/fetch.hpp"
#include "session/splat_inputs.hpp"

namespace gs::app {

namespace fs = std::filesystem;

bool tilesetTarget(const EncodeOptions& e, const qnv::WriteOptions& write,
                   encode::TilesetTarget& target) {
  target.dir = e.tileset;
  target.whole = e.bricks.empty();
  target.share = 0;
  target.shares = 1;
  if (!target.whole && !encode::parseShare(e.bricks, target.share, target.shares)) {
    std::fprintf(stderr,
                 "ghostspace: encode: --bricks: expected I/N with 0 <= I < N <= %u, got '%s'\n",
                 qnv::kMaxTilesetShares, e.bricks.c_str());
    return false;
  }
  target.cut.brickVoxels = e.brickVoxels;
  // (Not given: 16384; encodeGaussianTileset picks its own.)
  target.cut.brickVectors =
      e.brickVectors == 0 ? qnv::TilesetOptions{}.brickVectors : e.brickVectors;
  target.cut.write = write;
  target.cut.mergedCellsLog2 = 0;  // --merged-cells R: log2 R (0: no merged levels)
  // (Not given: 16; encodeGaussianTileset picks its own.)
  for (unsigned r = e.mergedCells == 1 ? 16 : e.mergedCells; r > 1; r /= 2)
    ++target.cut.mergedCellsLog2;
  return true;
}

void printMerged(const fs::path& dir, const encode::Merged& m) {
  std::uint64_t leaves = 0;
  for (const qnv::TilesetBrick& b : m.index.bricks) leaves += b.level == m.index.depth;
  const bool gaussian = m.index.header.kind == qnv::StreamKind::gaussian;
  std::printf(
      "%s: %zu bricks (%llu leaves, depth %u), %llu %s, index %llu bytes, %llu bytes in "
      "all\n",
      dir.string().c_str(), m.index.bricks.size(), static_cast<unsigned long long>(leaves),
      static_cast<unsigned>(m.index.depth),
      static_cast<unsigned long long>(m.index.header.vectorCount /
                                      m.index.header.recordsPerElement()),
      gaussian ? "splats" : "vectors", static_cast<unsigned long long>(m.indexBytes),
      static_cast<unsigned long long>(m.totalBytes));
}

void printEncodeResult(const encode::TilesetTarget& target, const std::string& input,
                       const encode::TilesetResult& r, double seconds) {
  const fs::path& dir = target.dir;
  if (target.whole) {
    printMerged(dir, r.merged);
    std::printf("%s: encoded in %.3f s\n", input.c_str(), seconds);
    return;
  }
  std::printf(
      "%s: share %u of %u: leaves %llu..%llu of %llu (depth %u), %llu bytes; %.3f s. After "
      "every share: ghostspace tileset index %s\n",
      dir.string().c_str(), target.share, target.shares,
      static_cast<unsigned long long>(r.leaves.first),
      static_cast<unsigned long long>(r.leaves.second),
      static_cast<unsigned long long>(r.leafCount), r.depth,
      static_cast<unsigned long long>(r.shareBytes), seconds, dir.string().c_str());
}

namespace {

encode::OutOfCoreOptions outOfCore(const EncodeOptions& e) {
  encode::OutOfCoreOptions ooc;
  ooc.memoryBytes = static_cast<std::uint64_t>(e.memoryMB * 1048576.0);
  ooc.threads = e.threads;
  return ooc;
}

}  // namespace

CLI::App* addTilesetCommand(CLI::App& cli, std::string& folder) {
  CLI::App* tileset = cli.add_subcommand("tileset", "Work on QNV tilesets (docs/qnv-format.md)");
  CLI::App* index = tileset->add_subcommand(
      "index",
      "Merge the shares of a split `encode --tileset OUT/ --bricks I/N` into the interior "
      "bricks and OUT/index.qnvt");
  index->add_option("OUT", folder, "The tileset folder")->required();
  tileset->require_subcommand(1);
  return tileset;
}

int writeTileset(const Options& options, const qnv::SelectedVectors& selected,
                 const qnv::WriteOptions& write, const std::string& input, double seconds) {
  encode::TilesetTarget target;
  if (!tilesetTarget(options.encode, write, target)) return 2;
  const encode::TilesetResult r = encode::writeTileset(target, selected);
  if (r.failure == encode::Failure::input) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", r.error.c_str());
    return 2;
  }
  if (!r.ok()) {
    std::fprintf(stderr, "ghostspace: %s\n", r.error.c_str());
    return 1;
  }
  printEncodeResult(target, input, r, seconds + r.seconds);
  return 0;
}

int writeVolumeTilesetOutOfCore(const Options& options, qnv::VolumeSlabReader& reader,
                                const qnv::VolumeEncodeOptions& encode,
                                const qnv::WriteOptions& write, const std::string& input) {
  const EncodeOptions& e = options.encode;
  encode::TilesetTarget target;
  if (!tilesetTarget(e, write, target)) return 2;
  const encode::VolumeOutOfCoreResult r =
      encode::writeVolumeTilesetOutOfCore(target, reader, encode, outOfCore(e));
  if (!r.tileset.ok()) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", r.tileset.error.c_str());
    return 1;
  }
  const qnv::EncodeSummary& s = r.summary;
  std::printf(
      "%s: %llu voxels, %llu with a non-zero magnitude, kept %llu (%.2f%%); out of core in "
      "%g MiB: %u selection pass%s %.3f s, vector pass over slices %u..%u (%u per slab) "
      "%.3f s, spilled %llu + %llu bytes\n",
      input.c_str(), static_cast<unsigned long long>(s.elements),
      static_cast<unsigned long long>(s.candidates), static_cast<unsigned long long>(s.kept),
      s.elements ? 100.0 * static_cast<double>(s.kept) / static_cast<double>(s.elements) : 0.0,
      e.memoryMB, r.passes, r.passes > 1 ? "es" : "", r.planSeconds, r.z0, r.z1, r.slabSlices,
      r.vectorSeconds, static_cast<unsigned long long>(r.leafSpillBytes),
      static_cast<unsigned long long>(r.interiorSpillBytes));
  printEncodeResult(target, input, r.tileset, r.tileset.seconds);
  return 0;
}

int writeMeshTilesetOutOfCore(const Options& options, const std::string& input,
                              const qnv::SurfaceEncodeOptions& encode,
                              const qnv::WriteOptions& write) {
  const EncodeOptions& e = options.encode;
  encode::TilesetTarget target;
  if (!tilesetTarget(e, write, target)) return 2;
  const encode::MeshOutOfCoreResult r =
      encode::writeMeshTilesetOutOfCore(target, input, encode, outOfCore(e));
  if (!r.tileset.ok()) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", r.tileset.error.c_str());
    return 1;
  }
  const qnv::EncodeSummary& s = r.summary;
  std::printf(
      "%s: %llu triangles (%llu vertices), %llu with a non-zero area, kept %llu (%.2f%%), %llu "
      "colours; out "
      "of core in %g MiB: copied %llu bytes %.3f s, %u selection pass%s %.3f s, vector pass "
      "%.3f s, %llu vertex block reads, spilled %llu + %llu bytes\n",
      input.c_str(), static_cast<unsigned long long>(s.elements),
      static_cast<unsigned long long>(r.vertices), static_cast<unsigned long long>(s.candidates),
      static_cast<unsigned long long>(s.kept),
      s.elements ? 100.0 * static_cast<double>(s.kept) / static_cast<double>(s.elements) : 0.0,
      static_cast<unsigned long long>(r.colors), e.memoryMB,
      static_cast<unsigned long long>(r.copiedBytes), r.copySeconds, r.passes,
      r.passes > 1 ? "es" : "", r.planSeconds, r.vectorSeconds,
      static_cast<unsigned long long>(r.cacheMisses),
      static_cast<unsigned long long>(r.leafSpillBytes),
      static_cast<unsigned long long>(r.interiorSpillBytes));
  printEncodeResult(target, input, r.tileset, r.tileset.seconds);
  return 0;
}

int writeGaussianTilesetOutOfCore(const Options& options, const encode::TilesetTarget& target,
                                  const std::string& input) {
  const EncodeOptions& e = options.encode;
  encode::GaussianOutOfCoreResult r;
  try {
    base::LocalFetcher fetcher;  // SOG's meta.json names its textures beside it
    const std::unique_ptr<splats::GaussianBatchReader> reader =
        splats::openGaussianBatches(input, session::sideFileReader(fetcher, input));
    r = encode::writeGaussianTilesetOutOfCore(
        target, *reader, {.shBits = e.shBits, .shFullFraction = e.shFull},
        {.brickVectors = e.brickVectors == 0, .mergedCells = e.mergedCells == 1}, outOfCore(e));
  } catch (const splats::NotPiecewiseError& error) {  // a usage error: the format
    std::fprintf(stderr,
                 "ghostspace: encode: --memory: %s; without --memory the tileset is written "
                 "from memory (docs/out-of-core.md)\n",
                 error.what());
    return 2;
  } catch (const splats::FormatError& error) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", error.what());
    return 1;
  }
  if (!r.tileset.ok()) {
    // As the in-memory encode: a scene that cannot be read or a file not written 1, a
    // scene with nothing to encode or a bad cut 2.
    std::fprintf(stderr, "ghostspace: encode: %s: %s\n", input.c_str(), r.tileset.error.c_str());
    return r.tileset.failure == encode::Failure::input && !r.unreadable ? 2 : 1;
  }
  const std::string mergedCells = r.mergedCellsLog2 == 0
                                      ? std::string("none")
                                      : std::to_string(1u << r.mergedCellsLog2) + "^3 a node";
  std::printf(
      "%s: %llu Gaussians (SH degree %d), kept %llu, K %llu; out of core in %g MiB: %u passes "
      "over the scene, frame %.3f s, leaves %.3f s, bricks %.3f s, merged levels %.3f s (%llu "
      "cells, %s, at most %llu held), spilled %llu + %llu bytes\n",
      input.c_str(), static_cast<unsigned long long>(r.splats), r.shDegree,
      static_cast<unsigned long long>(r.kept), static_cast<unsigned long long>(r.brickVectors),
      e.memoryMB, r.passes, r.frameSeconds, r.bucketSeconds, r.brickSeconds, r.mergedSeconds,
      static_cast<unsigned long long>(r.mergedCells), mergedCells.c_str(),
      static_cast<unsigned long long>(r.mergedPeakCells),
      static_cast<unsigned long long>(r.leafSpillBytes),
      static_cast<unsigned long long>(r.interiorSpillBytes));
  printEncodeResult(target, input, r.tileset, r.tileset.seconds);
  return 0;
}

int runTilesetIndex(const Options& options) {
  const fs::path dir = options.tilesetDir;
  encode::Merged merged;
  if (const std::string error = encode::mergeShares(dir, merged); !error.empty()) {
    std::fprintf(stderr, "ghostspace: tileset index: %s\n", error.c_str());
    return 1;
  }
  printMerged(dir, merged);
  return 0;
}

}  // namespace gs::app
