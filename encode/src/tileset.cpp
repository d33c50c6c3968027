// The files of a QNV tileset (docs/qnv-format.md, "Tilesets"). A share writes the leaf
// bricks of its contiguous range of leaves (in (z, y, x) order) and, under
// OUT/parts/I-of-N/, its leaves' index (leaves.qnvt, the index format) and what it gives
// the interior nodes (interior.qnvp); the merge turns every share's parts into the
// interior bricks and OUT/index.qnvt. An unsplit run is share 0 of 1 and the merge.
#include "encode/tileset.hpp"

#include <charconv>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "qnv/error.hpp"
#include "qnv/tileset_writer.hpp"
#include "splats/gaussian_tileset.hpp"
#include "splats/merged_levels.hpp"
#include "splats/qnv_gaussians.hpp"

namespace gs::encode {

namespace fs = std::filesystem;

bool parseShare(std::string_view text, std::uint32_t& share, std::uint32_t& shares) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return false;
  const char* s = text.data();
  auto [p, ec] = std::from_chars(s, s + slash, share);
  auto [q, ec2] = std::from_chars(s + slash + 1, s + text.size(), shares);
  return ec == std::errc() && p == s + slash && ec2 == std::errc() && q == s + text.size() &&
         shares >= 1 && shares <= qnv::kMaxTilesetShares && share < shares;
}

std::string shareName(std::uint32_t share, std::uint32_t shares) {
  return std::to_string(share) + "-of-" + std::to_string(shares);
}

std::string writeFile(const fs::path& path, std::string_view bytes) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) return "cannot write '" + path.string() + "'";
  return {};
}

namespace {

std::optional<std::string> readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Share `share` of `shares`: leaf bricks and the parts. "" or the error.
std::string writeShare(const fs::path& dir, const qnv::TilesetLayout& layout,
                       const qnv::TilesetOptions& cut, const qnv::SelectedVectors& selected,
                       std::uint32_t share, std::uint32_t shares, std::uint64_t& bytes) {
  qnv::TilesetShareWriter writer(layout, share, shares);
  std::optional<splats::MergedLevelBuilder> merged;
  if (cut.mergedCellsLog2 > 0 && layout.depth() > 0) merged.emplace(layout, cut.mergedCellsLog2);
  for (const qnv::SourceVector& v : selected.vectors)
    if (writer.add(v) && merged) merged->add(v);
  std::vector<qnv::TilesetBrick> leaves;
  for (const glm::uvec3& leaf : writer.openLeaves()) {
    std::optional<qnv::BrickFile> brick = writer.finishLeaf(leaf);
    if (!brick) continue;
    if (std::string error = writeFile(dir / brick->brick.path(), brick->bytes); !error.empty())
      return error;
    bytes += brick->bytes.size();
    leaves.push_back(std::move(brick->brick));
  }
  const fs::path part = dir / "parts" / shareName(share, shares);
  const std::string index = serializeTilesetIndex(assembleTilesetIndex(layout, std::move(leaves)));
  const std::string interior = serializeInteriorParts(writer.interior(), cut);
  bytes += index.size() + interior.size();
  if (std::string error = writeFile(part / "leaves.qnvt", index); !error.empty()) return error;
  if (merged) {
    const std::string sums = merged->serialize();
    bytes += sums.size();
    if (std::string error = writeFile(part / "merged.qnvm", sums); !error.empty()) return error;
  }
  return writeFile(part / "interior.qnvp", interior);
}

// The merged bricks (splats/merged_levels.hpp) from every share's merged.qnvm, one per
// interior brick of `index` (an empty stream where a node's vectors merge to nothing);
// sets index.mergedCellsLog2. Nothing when no share wrote one. "" or the error.
std::string writeMergedLevels(const fs::path& dir, const std::map<std::uint32_t, fs::path>& found,
                              const qnv::TilesetLayout& layout, qnv::TilesetIndex& index,
                              std::uint64_t& bytes) {
  std::optional<splats::MergedLevelBuilder> merged;
  std::uint8_t cellsLog2 = 0;
  for (const auto& [i, folder] : found) {
    const fs::path path = folder / "merged.qnvm";
    std::error_code ec;
    if (!fs::exists(path, ec)) {
      if (merged) return "'" + path.string() + "' is missing (the other shares have one)";
      continue;
    }
    const auto sums = readFile(path);
    if (!sums) return "cannot read '" + path.string() + "'";
    if (!merged) {
      if (i != found.begin()->first) return "'" + path.string() + "' has no match in share 0";
      if (sums->size() < 9) return "'" + path.string() + "' is truncated";
      cellsLog2 = static_cast<std::uint8_t>((*sums)[8]);
      merged.emplace(layout, cellsLog2);
    }
    std::string error;
    if (!merged->addSerialized(*sums, path.string(), error)) return error;
  }
  if (!merged) return {};
  std::map<qnv::TilesetCell, splats::GaussianCloud> clouds = merged->build();
  index.mergedCellsLog2 = cellsLog2;
  for (const qnv::TilesetBrick& b : index.bricks) {
    if (!index.hasMerged(b.level)) continue;
    const auto it = clouds.find(qnv::TilesetCell{b.level, glm::uvec3(b.x, b.y, b.z)});
    const qnv::EncodedVectors vectors =
        splats::encodeGaussianStream(it != clouds.end() ? it->second : splats::GaussianCloud{});
    qnv::WriteOptions write;
    write.packetBytes = vectors.header.packetBytes;
    write.encoding = qnv::PacketEncoding::compact;
    const std::string stream = qnv::writeStream(vectors, write);
    if (std::string error = writeFile(dir / b.mergedPath(), stream); !error.empty()) return error;
    bytes += stream.size();
  }
  return {};
}

// Every Gaussian share's gaussian.txt (encode/src/gaussian_tileset.cpp) says share 0's SH
// options: "" or why not, naming the file.
std::string sameShOptions(const std::map<std::uint32_t, fs::path>& found) {
  std::optional<std::string> first;
  const auto line = [](const std::string& s) { return s.substr(0, s.find('\n')); };
  for (const auto& [i, folder] : found) {
    const fs::path path = folder / "gaussian.txt";
    const auto text = readFile(path);
    if (!text) return "cannot read '" + path.string() + "'";
    if (!first) first = text;
    if (*text != *first)
      return "'" + path.string() + "' says other SH options than share 0's (" + line(*text) +
             ", not " + line(*first) +
             "): encode every share with the same --sh-bits and --sh-full";
  }
  return {};
}

// The template header without its vector count, to compare shares.
std::string templateKey(qnv::StreamHeader h) {
  h.vectorCount = 0;
  return qnv::serializeHeader(h);
}

}  // namespace

std::string mergeShares(const fs::path& dir, Merged& merged) {
  const fs::path partsDir = dir / "parts";
  std::error_code ec;
  if (!fs::is_directory(partsDir, ec))
    return "'" + partsDir.string() +
           "' holds no shares to merge (run encode --tileset with --bricks I/N first)";
  std::map<std::uint32_t, fs::path> found;
  std::uint32_t shares = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(partsDir, ec)) {
    const std::string name = entry.path().filename().string();
    const std::size_t of = name.find("-of-");
    std::uint32_t i = 0, n = 0;
    if (of == std::string::npos ||
        !parseShare(name.substr(0, of) + "/" + name.substr(of + 4), i, n))
      return "'" + entry.path().string() + "' is not a share's folder (I-of-N)";
    if (shares != 0 && n != shares)
      return "'" + partsDir.string() + "' mixes shares of " + std::to_string(shares) + " and " +
             std::to_string(n) + " (left over from another encode?)";
    shares = n;
    found[i] = entry.path();
  }
  if (shares == 0) return "'" + partsDir.string() + "' holds no shares to merge";
  for (std::uint32_t i = 0; i < shares; ++i)
    if (!found.count(i))
      return "share " + std::to_string(i) + " of " + std::to_string(shares) + " is missing ('" +
             (partsDir / shareName(i, shares)).string() + "'): run encode with --bricks " +
             std::to_string(i) + "/" + std::to_string(shares);

  // The interior parts stay on disk: each share's is checked and indexed by node, then
  // every node is merged from the shares' spans, one node in memory at a time.
  struct SharePart {
    std::shared_ptr<std::ifstream> file;
    fs::path path;
    std::vector<qnv::InteriorPartSpan> spans;
  };
  const auto readerOf = [](const SharePart& part) -> qnv::PartReader {
    return [&part](std::uint64_t offset, std::size_t n, char* out) {
      part.file->clear();
      part.file->seekg(static_cast<std::streamoff>(offset));
      part.file->read(out, static_cast<std::streamsize>(n));
      if (part.file->gcount() != static_cast<std::streamsize>(n))
        throw qnv::InputError("cannot read '" + part.path.string() + "'");
    };
  };
  std::vector<qnv::TilesetBrick> bricks;
  std::vector<SharePart> interior;
  std::optional<qnv::TilesetIndex> first;
  qnv::TilesetOptions cut;
  std::uint64_t total = 0, mergedBytes = 0;
  try {
    for (const auto& [i, folder] : found) {
      std::string error;
      const fs::path leavesPath = folder / "leaves.qnvt", interiorPath = folder / "interior.qnvp";
      const auto leavesBytes = readFile(leavesPath);
      SharePart part{
          std::make_shared<std::ifstream>(interiorPath, std::ios::binary), interiorPath, {}};
      const std::uint64_t size = fs::file_size(interiorPath, ec);
      if (!leavesBytes || !*part.file || ec)
        return "cannot read '" + (leavesBytes ? interiorPath : leavesPath).string() + "'";
      auto leaves = qnv::parseTilesetIndex(*leavesBytes, leavesPath.string(), error);
      if (!leaves) return error;
      qnv::TilesetOptions shareCut;
      auto spans =
          qnv::scanInteriorParts(size, readerOf(part), interiorPath.string(), shareCut, error);
      if (!spans) return error;
      part.spans = std::move(*spans);
      if (!first) {
        first = leaves;
        cut = shareCut;
      } else if (leaves->depth != first->depth ||
                 templateKey(leaves->header) != templateKey(first->header) ||
                 shareCut.brickVoxels != cut.brickVoxels ||
                 shareCut.brickVectors != cut.brickVectors) {
        return "'" + folder.string() + "' comes from another encode than share 0 (its header, " +
               "depth or brick options differ)";
      }
      total += leaves->header.vectorCount;
      for (const qnv::InteriorPartSpan& span : part.spans) total += span.count;
      for (qnv::TilesetBrick& b : leaves->bricks) {
        const fs::path path = dir / b.path();
        if (!fs::is_regular_file(path, ec) || fs::file_size(path, ec) != b.fileBytes)
          return "'" + path.string() + "' is missing or not the brick share " + std::to_string(i) +
                 " wrote";
        bricks.push_back(std::move(b));
      }
      interior.push_back(std::move(part));
    }

    if (first->header.kind == qnv::StreamKind::gaussian) {
      // A Gaussian scene's shares wrote every brick, share 0 the interior and merged ones
      // (splats/gaussian_tileset.hpp): the merge indexes them.
      if (std::string error = sameShOptions(found); !error.empty()) return error;
      for (const SharePart& part : interior)
        if (!part.spans.empty())
          return "'" + part.path.string() + "' has interior entries: not a Gaussian share's";
      qnv::StreamHeader whole = first->header;
      whole.vectorCount = total;
      const qnv::TilesetLayout layout = splats::gaussianTilesetLayout(whole, cut);
      if (layout.depth() != first->depth)
        return "the shares' octree depth does not fit their splats";
      merged.index = qnv::assembleTilesetIndex(layout, std::move(bricks));
      merged.index.mergedCellsLog2 = first->mergedCellsLog2;
      merged.index.mergedEveryLevel = first->mergedEveryLevel;
      for (const qnv::TilesetBrick& b : merged.index.bricks) {
        if (!merged.index.hasMerged(b.level)) continue;
        const fs::path path = dir / b.mergedPath();
        const std::uintmax_t size = fs::file_size(path, ec);
        if (ec) return "'" + path.string() + "' is missing (share 0 writes the merged bricks)";
        mergedBytes += size;
      }
    } else {
      qnv::StreamHeader whole = first->header;
      whole.vectorCount = total;
      cut.write.packetBytes = whole.packetBytes;
      cut.write.encoding = whole.encoding;
      const qnv::TilesetLayout layout(whole, cut);
      if (layout.depth() != first->depth)
        return "the shares' octree depth does not fit their vectors";
      std::map<qnv::TilesetCell, std::vector<std::pair<const SharePart*, qnv::InteriorPartSpan>>>
          nodes;
      for (const SharePart& part : interior)
        for (const qnv::InteriorPartSpan& span : part.spans)
          nodes[span.node].push_back({&part, span});
      for (const auto& [node, spans] : nodes) {
        std::vector<qnv::InteriorEntry> entries;
        for (const auto& [part, span] : spans) {
          std::vector<qnv::InteriorEntry> more = qnv::loadInteriorEntries(span, readerOf(*part));
          entries.insert(entries.end(), more.begin(), more.end());
        }
        if (entries.empty()) continue;
        const qnv::BrickFile b = qnv::mergeInteriorNode(node, std::move(entries), layout);
        if (std::string error = writeFile(dir / b.brick.path(), b.bytes); !error.empty())
          return error;
        bricks.push_back(b.brick);
      }
      merged.index = qnv::assembleTilesetIndex(layout, std::move(bricks));
      if (std::string error = writeMergedLevels(dir, found, layout, merged.index, mergedBytes);
          !error.empty())
        return error;
    }
  } catch (const qnv::InputError& e) {
    return e.what();
  }
  const std::string bytes = qnv::serializeTilesetIndex(merged.index);
  std::string error;
  // The reader's checks on what we are about to publish (duplicate cells across shares...).
  if (!qnv::parseTilesetIndex(bytes, (dir / "index.qnvt").string(), error)) return error;
  if (std::string e = writeFile(dir / "index.qnvt", bytes); !e.empty()) return e;
  merged.indexBytes = bytes.size();
  merged.totalBytes = bytes.size() + mergedBytes;
  for (const qnv::TilesetBrick& b : merged.index.bricks) merged.totalBytes += b.fileBytes;
  fs::remove_all(partsDir, ec);
  return {};
}

TilesetResult writeTileset(const TilesetTarget& target, const qnv::SelectedVectors& selected) {
  const auto t0 = std::chrono::steady_clock::now();
  TilesetResult result;
  const fs::path& dir = target.dir;
  try {
    const qnv::TilesetLayout layout(selected.header, target.cut);
    result.leaves = layout.shareLeaves(target.share, target.shares);
    result.leafCount = layout.leafCount();
    result.depth = layout.depth();
    std::error_code ec;
    if (target.whole) {  // the whole output: nothing stale may remain
      fs::remove_all(dir / "bricks", ec);
      fs::remove_all(dir / "parts", ec);
      fs::remove_all(dir / "merged", ec);
      fs::remove(dir / "index.qnvt", ec);
    }
    std::string error = writeShare(dir, layout, target.cut, selected, target.share, target.shares,
                                   result.shareBytes);
    if (error.empty() && target.whole) error = mergeShares(dir, result.merged);
    if (!error.empty()) {
      result.failure = Failure::write;
      result.error = std::move(error);
    }
  } catch (const qnv::InputError& error) {
    result.failure = Failure::input;
    result.error = error.what();
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace gs::encode
