// The files of a Gaussian splatting scene's tileset (splats/gaussian_tileset.hpp;
// docs/tilesets.md, "Gaussian tilesets"): the bricks, the merged bricks and the index; or,
// for a share (--bricks I/N), its bricks and its parts, which mergeShares indexes.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "encode/tileset.hpp"
#include "gaussian_files.hpp"
#include "ooc_share.hpp"
#include "qnv/error.hpp"
#include "splats/gaussian_tileset.hpp"

namespace gs::encode {

namespace fs = std::filesystem;

namespace {

// The text of a share's parts/I-of-N/gaussian.txt, which mergeShares compares.
std::string shareShOptions(const splats::GaussianStreamOptions& options) {
  char text[96];
  std::snprintf(text, sizeof text, "sh-bits %d sh-full %.17g\n", options.shBits,
                options.shFullFraction);
  return text;
}

}  // namespace

std::string mergedPathOf(const qnv::TilesetCell& node) {
  qnv::TilesetBrick brick;
  brick.level = node.level;
  brick.x = node.cell.x, brick.y = node.cell.y, brick.z = node.cell.z;
  return brick.mergedPath();
}

TilesetResult& finishGaussianTileset(
    const TilesetTarget& target, const splats::GaussianStreamOptions& options,
    qnv::TilesetIndex index,
    const std::vector<std::pair<qnv::TilesetCell, std::string>>& mergedBricks,
    std::chrono::steady_clock::time_point t0, TilesetResult& result) {
  const auto fail = [&](std::string error) -> TilesetResult& {
    result.failure = Failure::write;
    result.error = std::move(error);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  };
  const fs::path& dir = target.dir;
  Merged& merged = result.merged;
  for (const auto& [node, stream] : mergedBricks) {
    if (std::string error = writeFile(dir / mergedPathOf(node), stream); !error.empty())
      return fail(error);
    merged.totalBytes += stream.size();
  }
  const std::string indexBytes = qnv::serializeTilesetIndex(index);
  if (!target.whole) {
    // The share's index of its bricks and an interior part without entries (the bricks
    // are whole already), which carries the brick options: mergeShares indexes them all.
    const fs::path part = dir / "parts" / shareName(target.share, target.shares);
    const std::string interior = qnv::serializeInteriorParts({}, target.cut);
    // The SH options change the bricks' bytes but not their headers: the merge compares.
    const std::string shOptions = shareShOptions(options);
    if (std::string error = writeFile(part / "leaves.qnvt", indexBytes); !error.empty())
      return fail(error);
    if (std::string error = writeFile(part / "interior.qnvp", interior); !error.empty())
      return fail(error);
    if (std::string error = writeFile(part / "gaussian.txt", shOptions); !error.empty())
      return fail(error);
    result.shareBytes = merged.totalBytes + indexBytes.size() + interior.size() + shOptions.size();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  std::string error;
  // The reader's checks on what is about to be published.
  if (!qnv::parseTilesetIndex(indexBytes, (dir / "index.qnvt").string(), error)) return fail(error);
  if (error = writeFile(dir / "index.qnvt", indexBytes); !error.empty()) return fail(error);
  merged.indexBytes = indexBytes.size();
  merged.totalBytes += indexBytes.size();
  merged.index = std::move(index);
  result.shareBytes = merged.totalBytes;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

TilesetResult writeGaussianTileset(const TilesetTarget& target, const splats::GaussianCloud& cloud,
                                   const splats::GaussianStreamOptions& options, unsigned threads) {
  const auto t0 = std::chrono::steady_clock::now();
  TilesetResult result;
  const auto fail = [&](Failure failure, std::string error) {
    result.failure = failure;
    result.error = std::move(error);
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  };
  splats::GaussianTilesetFiles files;
  try {
    files = splats::buildGaussianTileset(cloud, target.cut, options, target.share, target.shares,
                                         ooc::workerThreads({.threads = threads}));
  } catch (const qnv::InputError& error) {
    return fail(Failure::input, error.what());
  }
  result.depth = files.depth;
  result.leafCount = files.leafCount;
  result.leaves = files.leaves;
  if (target.whole) ooc::removeStale(target.dir);  // the whole output: nothing stale may remain
  for (const qnv::BrickFile& b : files.bricks) {
    if (std::string error = writeFile(target.dir / b.brick.path(), b.bytes); !error.empty())
      return fail(Failure::write, error);
    result.merged.totalBytes += b.bytes.size();
  }
  finishGaussianTileset(target, options, std::move(files.index), files.merged, t0, result);
  return result;
}

}  // namespace gs::encode
