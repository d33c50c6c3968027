// The files of a Gaussian splatting scene's tileset (splats/gaussian_tileset.hpp;
// docs/tilesets.md, "Gaussian tilesets"): the bricks, the merged bricks and the index; or,
// for a share (--bricks I/N), its bricks and its parts, which mergeShares indexes.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "encode/tileset.hpp"
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

TilesetResult writeGaussianTileset(const TilesetTarget& target, const splats::GaussianCloud& cloud,
                                   const splats::GaussianStreamOptions& options) {
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
    files = splats::buildGaussianTileset(cloud, target.cut, options, target.share, target.shares);
  } catch (const qnv::InputError& error) {
    return fail(Failure::input, error.what());
  }
  result.depth = files.depth;
  result.leafCount = files.leafCount;
  result.leaves = files.leaves;
  const fs::path& dir = target.dir;
  std::error_code ec;
  if (target.whole) {  // the whole output: nothing stale may remain
    fs::remove_all(dir / "bricks", ec);
    fs::remove_all(dir / "parts", ec);
    fs::remove_all(dir / "merged", ec);
    fs::remove(dir / "index.qnvt", ec);
  }
  Merged& merged = result.merged;
  for (const qnv::BrickFile& b : files.bricks) {
    if (std::string error = writeFile(dir / b.brick.path(), b.bytes); !error.empty())
      return fail(Failure::write, error);
    merged.totalBytes += b.bytes.size();
  }
  for (std::size_t i = 0, m = 0; i < files.index.bricks.size() && m < files.merged.size(); ++i) {
    const qnv::TilesetBrick& b = files.index.bricks[i];
    if (!files.index.hasMerged(b.level)) continue;
    const std::string& stream = files.merged[m++].second;
    if (std::string error = writeFile(dir / b.mergedPath(), stream); !error.empty())
      return fail(Failure::write, error);
    merged.totalBytes += stream.size();
  }
  const std::string index = qnv::serializeTilesetIndex(files.index);
  if (!target.whole) {
    // The share's index of its bricks and an interior part without entries (the bricks
    // are whole already), which carries the brick options: mergeShares indexes them all.
    const fs::path part = dir / "parts" / shareName(target.share, target.shares);
    const std::string interior = qnv::serializeInteriorParts({}, target.cut);
    // The SH options change the bricks' bytes but not their headers: the merge compares.
    const std::string shOptions = shareShOptions(options);
    if (std::string error = writeFile(part / "leaves.qnvt", index); !error.empty())
      return fail(Failure::write, error);
    if (std::string error = writeFile(part / "interior.qnvp", interior); !error.empty())
      return fail(Failure::write, error);
    if (std::string error = writeFile(part / "gaussian.txt", shOptions); !error.empty())
      return fail(Failure::write, error);
    result.shareBytes = merged.totalBytes + index.size() + interior.size() + shOptions.size();
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return result;
  }
  std::string error;
  // The reader's checks on what is about to be published.
  if (!qnv::parseTilesetIndex(index, (dir / "index.qnvt").string(), error))
    return fail(Failure::write, error);
  if (error = writeFile(dir / "index.qnvt", index); !error.empty())
    return fail(Failure::write, error);
  merged.indexBytes = index.size();
  merged.totalBytes += index.size();
  merged.index = std::move(files.index);
  result.shareBytes = merged.totalBytes;
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace gs::encode
