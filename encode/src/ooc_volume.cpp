// The out-of-core tileset encode of a volume (docs/out-of-core.md, "Tileset encoding").
// Memory is what OutOfCoreOptions::memoryBytes allows (--memory), split as:
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
#include <chrono>
#include <filesystem>
#include <optional>

#include "encode/tileset.hpp"
#include "ooc_share.hpp"
#include "qnv/error.hpp"
#include "qnv/tileset_writer.hpp"
#include "qnv/volume_tileset.hpp"

namespace gs::encode {

namespace fs = std::filesystem;

using ooc::ShareEncoder;
using ooc::since;

VolumeOutOfCoreResult writeVolumeTilesetOutOfCore(const TilesetTarget& target,
                                                  qnv::VolumeSlabReader& reader,
                                                  const qnv::VolumeEncodeOptions& encode,
                                                  const OutOfCoreOptions& ooc) {
  VolumeOutOfCoreResult result;
  TilesetResult& out = result.tileset;
  const std::uint32_t share = target.share, shares = target.shares;
  const qnv::TilesetOptions& cut = target.cut;
  const std::uint32_t brickVoxels = cut.brickVoxels;
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path& dir = target.dir;
  const std::uint64_t memory = ooc.memoryBytes;
  const unsigned threads = ooc::workerThreads(ooc);
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
        std::min<std::uint64_t>(std::uint64_t{rowFirst} * brickVoxels, info.dims.z));
    const std::uint32_t z1 = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(std::uint64_t{rowEnd} * brickVoxels, info.dims.z));

    const qnv::VolumeSelectionPlan plan = qnv::planVolumeSelection(reader, encode, step, z0);
    result.planSeconds = since(t0);
    const qnv::TilesetLayout layout(plan.header, cut);
    if (target.whole) ooc::removeStale(dir);  // the whole output: nothing stale may remain
    const fs::path part = dir / "parts" / shareName(share, shares);
    std::optional<ShareEncoder> encoder;
    encoder.emplace(dir, part, layout, share, shares, memory, threads);
    ShareEncoder& writer = *encoder;
    const auto t1 = std::chrono::steady_clock::now();
    if (z0 < z1) {
      qnv::VolumeKeepFilter filter(plan);
      qnv::VolumeVectorOptions pass = step;
      pass.valueWindow = encode.valueWindow;
      if (!pass.valueWindow) pass.valueRange = plan.colorDomain;
      const std::uint64_t slice = info.sliceVoxels();
      std::uint32_t row = rowFirst;
      std::uint64_t rowEndIndex =
          slice * std::min<std::uint64_t>(std::uint64_t{row + 1} * brickVoxels, info.dims.z);
      const auto summary = qnv::forEachVolumeVector(
          reader, z0, z1, pass, [&](std::span<const qnv::VolumeVector> vectors) {
            for (const qnv::VolumeVector& v : vectors) {
              while (v.index >= rowEndIndex) {  // every slice of leaf row `row` is done
                writer.finishRow(row++);
                rowEndIndex = slice * std::min<std::uint64_t>(std::uint64_t{row + 1} * brickVoxels,
                                                              info.dims.z);
              }
              if (!filter.keep(v)) continue;
              const qnv::SourceVector s = qnv::toSourceVector(v);
              const std::uint64_t leaf = layout.leafIndex(layout.leafOf(s));
              if (leaf >= writer.range().first && leaf < writer.range().second) writer.add(leaf, s);
            }
          });
      result.slabSlices = summary.slabSlices;
      for (; row < rowEnd; ++row) writer.finishRow(row);
    }
    if (std::string error = writer.writeParts(part, cut); !error.empty())
      throw qnv::InputError(error);
    result.vectorSeconds = since(t1);
    out.shareBytes = writer.bytesWritten();
    result.leafSpillBytes = writer.leafSpillBytes();
    result.interiorSpillBytes = writer.interiorSpillBytes();
    encoder.reset();  // removes the spill files
    if (target.whole)
      if (std::string error = mergeShares(dir, out.merged); !error.empty())
        throw qnv::InputError(error);
    result.summary = plan.summary;
    result.passes = plan.passes;
    result.z0 = z0;
    result.z1 = z1;
    out.leaves = leaves;
    out.leafCount = layout.leafCount();
    out.depth = layout.depth();
  } catch (const qnv::InputError& error) {
    out.failure = Failure::input;
    out.error = error.what();
  }
  out.seconds = since(t0);
  return result;
}

}  // namespace gs::encode
