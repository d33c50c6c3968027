// The out-of-core tileset encode of a volume (docs/out-of-core.md, "Tileset encoding").
// Memory is what --memory allows, split as:
//   - a quarter for the gradient step (qnv::slabSlicesForMemory: window, read-ahead and
//     the slab's vectors);
//   - the rest for the open leaves' vectors (40 bytes each, counted by capacity) plus the
//     interior contributions held (24 bytes each): when they pass it, every open leaf's
//     vectors go to OUT/parts/I-of-N/leaves.spill and come back when the leaf finishes;
//     interior contributions past an eighth of the bound go to interior.spill after each
//     row of leaves, and come back node by node when interior.qnvp is written.
// Finishing a row of leaves (sort, quantize, code, write) runs on --threads workers, one
// leaf each at a time, while the vector pass reads and computes the next row; they hold
// a leaf's records and brick on top of the bound (its vectors are counted).
#include "ooc_tileset.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>

#include "encode_tileset.hpp"
#include "ooc_share.hpp"
#include "qnv/error.hpp"
#include "qnv/tileset_writer.hpp"
#include "qnv/volume_tileset.hpp"

namespace gs::app {

namespace fs = std::filesystem;

using ooc::ShareEncoder;
using ooc::since;

int writeVolumeTilesetOutOfCore(const Options& options, qnv::VolumeSlabReader& reader,
                                const qnv::VolumeEncodeOptions& encode,
                                const qnv::WriteOptions& write, const std::string& input) {
  const EncodeOptions& e = options.encode;
  std::uint32_t share = 0, shares = 1;
  qnv::TilesetOptions cut;
  if (!tilesetShareOptions(e, write, share, shares, cut)) return 2;
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = e.tileset;
  const auto memory = static_cast<std::uint64_t>(e.memoryMB * 1048576.0);
  const unsigned threads =
      e.threads > 0 ? e.threads : std::max(1u, std::thread::hardware_concurrency());
  try {
    const qnv::VolumeGridInfo& info = reader.info();
    qnv::VolumeVectorOptions step;
    step.memoryBytes = memory / 4;
    step.threads = threads;
    // The leaf rows of this share decide the slices of the vector pass; the layout of
    // volumes does not depend on the kept count, so it is known before the selection.
    qnv::StreamHeader shape;
    shape.kind = qnv::StreamKind::volume;
    shape.volumeDims = info.dims;
    const qnv::TilesetLayout shapeLayout(shape, cut);
    const auto leaves = shapeLayout.shareLeaves(share, shares);
    const std::uint64_t perRow = std::uint64_t{shapeLayout.leafGrid().x} * shapeLayout.leafGrid().y;
    const std::uint32_t rowFirst = static_cast<std::uint32_t>(leaves.first / perRow);
    const std::uint32_t rowEnd = leaves.second > leaves.first
                                     ? static_cast<std::uint32_t>((leaves.second - 1) / perRow + 1)
                                     : rowFirst;
    const std::uint32_t z0 = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(std::uint64_t{rowFirst} * e.brickVoxels, info.dims.z));
    const std::uint32_t z1 = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(std::uint64_t{rowEnd} * e.brickVoxels, info.dims.z));

    const qnv::VolumeSelectionPlan plan = qnv::planVolumeSelection(reader, encode, step, z0);
    const double planSeconds = since(t0);
    const qnv::TilesetLayout layout(plan.header, cut);
    if (e.bricks.empty()) {  // the whole output: nothing stale may remain
      std::error_code ec;
      fs::remove_all(dir / "bricks", ec);
      fs::remove_all(dir / "parts", ec);
      fs::remove(dir / "index.qnvt", ec);
    }
    const fs::path part = dir / "parts" / shareName(share, shares);
    std::optional<ShareEncoder> encoder;
    encoder.emplace(dir, part, layout, share, shares, memory, threads);
    ShareEncoder& writer = *encoder;
    const auto t1 = std::chrono::steady_clock::now();
    std::uint32_t slabSlices = 0;
    if (z0 < z1) {
      qnv::VolumeKeepFilter filter(plan);
      qnv::VolumeVectorOptions pass = step;
      pass.valueWindow = encode.valueWindow;
      if (!pass.valueWindow) pass.valueRange = plan.colorDomain;
      const std::uint64_t slice = info.sliceVoxels();
      std::uint32_t row = rowFirst;
      std::uint64_t rowEndIndex =
          slice * std::min<std::uint64_t>(std::uint64_t{row + 1} * e.brickVoxels, info.dims.z);
      const auto summary = qnv::forEachVolumeVector(
          reader, z0, z1, pass, [&](std::span<const qnv::VolumeVector> vectors) {
            for (const qnv::VolumeVector& v : vectors) {
              while (v.index >= rowEndIndex) {  // every slice of leaf row `row` is done
                writer.finishRow(row++);
                rowEndIndex = slice * std::min<std::uint64_t>(
                                          std::uint64_t{row + 1} * e.brickVoxels, info.dims.z);
              }
              if (!filter.keep(v)) continue;
              const qnv::SourceVector s = qnv::toSourceVector(v);
              const std::uint64_t leaf = layout.leafIndex(layout.leafOf(s));
              if (leaf >= writer.range().first && leaf < writer.range().second) writer.add(leaf, s);
            }
          });
      slabSlices = summary.slabSlices;
      for (; row < rowEnd; ++row) writer.finishRow(row);
    }
    if (std::string error = writer.writeParts(part, cut); !error.empty())
      throw qnv::InputError(error);
    const double vectorSeconds = since(t1);
    const std::uint64_t written = writer.bytesWritten();
    const std::uint64_t leafSpill = writer.leafSpillBytes();
    const std::uint64_t interiorSpill = writer.interiorSpillBytes();
    encoder.reset();  // removes the spill files
    Merged merged;
    if (e.bricks.empty())
      if (std::string error = mergeShares(dir, merged); !error.empty())
        throw qnv::InputError(error);
    const qnv::EncodeSummary& s = plan.summary;
    std::printf(
        "%s: %llu voxels, %llu with a non-zero magnitude, kept %llu (%.2f%%); out of core in "
        "%g MiB: %u selection pass%s %.3f s, vector pass over slices %u..%u (%u per slab) "
        "%.3f s, spilled %llu + %llu bytes\n",
        input.c_str(), static_cast<unsigned long long>(s.elements),
        static_cast<unsigned long long>(s.candidates), static_cast<unsigned long long>(s.kept),
        s.elements ? 100.0 * static_cast<double>(s.kept) / static_cast<double>(s.elements) : 0.0,
        e.memoryMB, plan.passes, plan.passes > 1 ? "es" : "", planSeconds, z0, z1, slabSlices,
        vectorSeconds, static_cast<unsigned long long>(leafSpill),
        static_cast<unsigned long long>(interiorSpill));
    ooc::printEncodeResult(dir, input, e.bricks.empty(), merged, share, shares, leaves, layout,
                           written, t0);
  } catch (const qnv::InputError& error) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", error.what());
    return 1;
  }
  return 0;
}

}  // namespace gs::app
