// A Gaussian splatting scene as a QNV tileset: the rules are in
// splats/gaussian_tileset.hpp and docs/tilesets.md, "Gaussian tilesets".
#include "splats/gaussian_tileset.hpp"

#include <algorithm>
#include <atomic>
#include <future>
#include <map>

#include "qnv/error.hpp"
#include "splats/merged_levels.hpp"

namespace gs::splats {

std::uint64_t defaultGaussianBrickVectors(std::uint64_t kept) {
  constexpr std::uint64_t kDefault = 16384, kSmallest = 2048;
  if (kept <= 8 * kSmallest || kept > 8 * kDefault) return kDefault;
  std::uint64_t k = kDefault;
  while (8 * k >= kept) k /= 2;
  return k;
}

std::uint32_t gaussianRootCell(const qnv::StreamHeader& frame, glm::vec3 position) {
  const glm::dvec3 lo(frame.boundsMin);
  const glm::dvec3 extent = glm::max(glm::dvec3(frame.boundsMax) - lo, glm::dvec3(1e-12));
  const double fine = kGaussianRootCells;
  const glm::dvec3 q = glm::clamp(glm::floor((glm::dvec3(position) - lo) / extent * fine),
                                  glm::dvec3(0.0), glm::dvec3(fine - 1.0));
  return static_cast<std::uint32_t>(q.x) +
         kGaussianRootCells * (static_cast<std::uint32_t>(q.y) +
                               kGaussianRootCells * static_cast<std::uint32_t>(q.z));
}

std::uint8_t gaussianMergedCellsLog2For(std::uint64_t occupiedCells, std::uint64_t kept) {
  return kept > 0 && 8 * occupiedCells <= kept ? 5 : 4;
}

std::uint8_t defaultGaussianMergedCellsLog2(const GaussianCloud& cloud) {
  const GaussianFrame frame = gaussianFrame(cloud);
  std::vector<std::uint32_t> cells;
  cells.reserve(frame.kept.size());
  for (const std::uint32_t i : frame.kept)
    cells.push_back(gaussianRootCell(frame.header, cloud.positions[i]));
  std::sort(cells.begin(), cells.end());
  const auto occupied =
      static_cast<std::size_t>(std::unique(cells.begin(), cells.end()) - cells.begin());
  return gaussianMergedCellsLog2For(occupied, frame.kept.size());
}

qnv::TilesetLayout gaussianLayoutForSplats(const qnv::StreamHeader& frame, std::uint64_t kept,
                                           const qnv::TilesetOptions& cut) {
  if (cut.brickVectors == 0) throw qnv::InputError("--brick-vectors must be at least 1");
  qnv::StreamHeader whole = frame;
  whole.vectorCount = kept;  // the octree's depth counts splats
  const std::uint32_t words = whole.recordsPerElement();
  qnv::TilesetOptions layoutCut = cut;
  const std::uint64_t perPacket =
      std::clamp<std::uint64_t>(cut.brickVectors / 16, 128,
                                std::min<std::uint64_t>(1024, qnv::kMaxPacketBytes / (8 * words)));
  layoutCut.write.packetBytes = static_cast<std::uint32_t>(8 * words * perPacket);
  // Gaussian streams are plain or compact (entropy coding is for vectors).
  layoutCut.write.encoding = cut.write.encoding == qnv::PacketEncoding::plain
                                 ? qnv::PacketEncoding::plain
                                 : qnv::PacketEncoding::compact;
  return qnv::TilesetLayout(whole, layoutCut);
}

std::vector<std::pair<qnv::TilesetCell, std::size_t>> splitGaussianLeaf(
    const qnv::TilesetLayout& layout, glm::uvec3 leaf, std::size_t count) {
  std::vector<std::pair<qnv::TilesetCell, std::size_t>> parts;
  const std::uint8_t depth = layout.depth();
  std::size_t next = 0;
  for (std::uint8_t level = 0; level <= depth && next < count; ++level) {
    const unsigned shift = depth - level;
    const std::size_t end =
        level == depth
            ? count
            : static_cast<std::size_t>(std::min<std::uint64_t>(count, next + layout.quota(level)));
    parts.emplace_back(qnv::TilesetCell{level, leaf >> glm::uvec3(shift)}, end);
    next = end;
  }
  return parts;
}

std::string encodeMergedBrick(const GaussianCloud& merged) {
  const qnv::EncodedVectors vectors = encodeGaussianStream(merged);
  qnv::WriteOptions write;
  write.packetBytes = vectors.header.packetBytes;
  write.encoding = qnv::PacketEncoding::compact;
  return qnv::writeStream(vectors, write);
}

std::vector<std::pair<qnv::TilesetCell, std::string>> gaussianMergedBricks(
    const std::map<qnv::TilesetCell, std::string>& merged, const qnv::TilesetIndex& index) {
  std::vector<std::pair<qnv::TilesetCell, std::string>> out;
  for (const qnv::TilesetBrick& b : index.bricks) {
    if (!index.hasMerged(b.level)) continue;
    const qnv::TilesetCell node{b.level, glm::uvec3(b.x, b.y, b.z)};
    const auto it = merged.find(node);
    out.emplace_back(node, it != merged.end() ? it->second : encodeMergedBrick({}));
  }
  return out;
}

qnv::TilesetLayout gaussianTilesetLayout(const qnv::StreamHeader& whole,
                                         const qnv::TilesetOptions& cut) {
  qnv::StreamHeader splats = whole;
  splats.vectorCount = whole.vectorCount / whole.recordsPerElement();  // depth counts splats
  qnv::TilesetOptions layoutCut = cut;
  layoutCut.write.packetBytes = whole.packetBytes;
  layoutCut.write.encoding = whole.encoding;
  return qnv::TilesetLayout(splats, layoutCut);
}

namespace {

// `leaves` (TilesetLayout::leafIndex values) sorted by mortonOfCell of their cells: the
// order GaussianMergedLevels takes them in, as the out-of-core encode's buckets give them.
std::vector<std::uint64_t> leavesInMortonOrder(const qnv::TilesetLayout& layout,
                                               std::vector<std::uint64_t> leaves) {
  std::vector<std::pair<std::uint64_t, std::uint64_t>> coded;
  coded.reserve(leaves.size());
  for (const std::uint64_t leaf : leaves)
    coded.emplace_back(mortonOfCell(layout.leafAt(leaf)), leaf);
  std::sort(coded.begin(), coded.end());
  for (std::size_t i = 0; i < coded.size(); ++i) leaves[i] = coded[i].second;
  return leaves;
}

}  // namespace

GaussianTilesetFiles buildGaussianTileset(const GaussianCloud& cloud,
                                          const qnv::TilesetOptions& cut,
                                          const GaussianStreamOptions& options, std::uint32_t share,
                                          std::uint32_t shares, unsigned threads) {
  if (shares == 0 || shares > qnv::kMaxTilesetShares || share >= shares)
    throw qnv::InputError("share " + std::to_string(share) + " of " + std::to_string(shares) +
                          " does not exist");
  const GaussianFrame frame = gaussianFrame(cloud);
  if (frame.kept.empty())
    throw qnv::InputError("nothing to encode: " + std::to_string(cloud.size()) +
                          " Gaussians, none with an opacity and a size");
  const qnv::TilesetLayout layout = gaussianLayoutForSplats(frame.header, frame.kept.size(), cut);
  const std::uint8_t depth = layout.depth();
  const std::uint32_t words = layout.templateHeader().recordsPerElement();

  // Splats by leaf (index into frame.kept), then ranked within each leaf.
  std::map<std::uint64_t, std::vector<std::uint32_t>> leaves;
  qnv::SourceVector at;
  for (std::uint32_t k = 0; k < frame.kept.size(); ++k) {
    at.position = cloud.positions[frame.kept[k]];
    leaves[layout.leafIndex(layout.leafOf(at))].push_back(k);
  }
  const auto rankedBefore = [&](std::uint32_t a, std::uint32_t b) {
    return frame.importance[a] > frame.importance[b] ||
           (frame.importance[a] == frame.importance[b] && a < b);
  };
  GaussianTilesetFiles out;
  // The merged levels (share 0): leaf by leaf in Morton order, each leaf's splats in
  // scene order, as the out-of-core encode adds them; each node's merged brick encoded as
  // it is done. On a thread of its own beside the bricks' when there are threads.
  const bool merged = cut.mergedCellsLog2 > 0 && depth > 0;
  std::vector<std::pair<glm::uvec3, std::vector<std::uint32_t>>> mergedLeaves;
  if (merged && share == 0) {
    std::vector<std::uint64_t> keys;
    for (const auto& [index, members] : leaves) keys.push_back(index);
    for (const std::uint64_t index : leavesInMortonOrder(layout, std::move(keys))) {
      std::vector<std::uint32_t> inCloud;
      for (const std::uint32_t k : leaves.at(index)) inCloud.push_back(frame.kept[k]);
      mergedLeaves.emplace_back(layout.leafAt(index), std::move(inCloud));
    }
  }
  const auto mergeLevels = [&] {
    std::map<qnv::TilesetCell, std::string> bricks;
    if (mergedLeaves.empty()) return bricks;
    GaussianMergedLevels levels(layout, cut.mergedCellsLog2,
                                [&](const qnv::TilesetCell& node, GaussianCloud&& c) {
                                  bricks.emplace(node, encodeMergedBrick(c));
                                });
    for (const auto& [leaf, members] : mergedLeaves) levels.addLeaf(leaf, cloud, members);
    levels.finish();
    return bricks;
  };
  std::future<std::map<qnv::TilesetCell, std::string>> mergedTask;
  if (threads > 1 && !mergedLeaves.empty())
    mergedTask = std::async(std::launch::async, mergeLevels);
  std::map<qnv::TilesetCell, std::vector<std::uint32_t>> nodes;
  for (auto& [index, members] : leaves) {
    std::sort(members.begin(), members.end(), rankedBefore);
    std::size_t next = 0;
    for (const auto& [node, end] :
         splitGaussianLeaf(layout, layout.leafAt(index), members.size())) {
      std::vector<std::uint32_t>& to = nodes[node];
      to.insert(to.end(), members.begin() + static_cast<std::ptrdiff_t>(next),
                members.begin() + static_cast<std::ptrdiff_t>(end));
      next = end;
    }
  }

  out.splats = frame.kept.size();
  out.depth = depth;
  out.leafCount = layout.leafCount();
  out.leaves = layout.shareLeaves(share, shares);
  const auto mine = [&](const qnv::TilesetCell& node) {
    if (node.level < depth) return share == 0;  // interior bricks: share 0's
    const std::uint64_t leaf = layout.leafIndex(node.cell);
    return leaf >= out.leaves.first && leaf < out.leaves.second;
  };
  std::vector<std::pair<qnv::TilesetCell, std::vector<std::uint32_t>*>> work;
  for (auto& [node, members] : nodes)  // (level, z, y, x): index order
    if (mine(node)) work.emplace_back(node, &members);
  out.bricks.resize(work.size());
  // Each brick on its own, `threads` at a time: the same bytes in the same slots.
  std::atomic<std::size_t> next{0};
  const auto encodeBricks = [&] {
    for (std::size_t i; (i = next++) < work.size();) {
      const qnv::TilesetCell& node = work[i].first;
      std::vector<std::uint32_t>& members = *work[i].second;
      std::sort(members.begin(), members.end(), rankedBefore);  // an interior node's leaves
      std::vector<std::uint32_t> order(members.size());
      for (std::size_t r = 0; r < members.size(); ++r) order[r] = frame.kept[members[r]];
      const qnv::StreamHeader h = layout.brickHeader(node, order.size() * words);
      out.bricks[i] = qnv::writeBrick(node, h, encodeGaussianSplats(cloud, order, h, options));
    }
  };
  std::vector<std::future<void>> helpers;
  for (unsigned t = 1; t < std::max(1u, threads); ++t)
    helpers.push_back(std::async(std::launch::async, encodeBricks));
  encodeBricks();
  for (std::future<void>& helper : helpers) helper.get();
  std::vector<qnv::TilesetBrick> bricks;
  for (const qnv::BrickFile& file : out.bricks) bricks.push_back(file.brick);
  out.index = qnv::assembleTilesetIndex(layout, std::move(bricks));

  if (merged) {
    out.index.mergedCellsLog2 = cut.mergedCellsLog2;
    out.index.mergedEveryLevel = true;
  }
  if (merged && share == 0)
    out.merged =
        gaussianMergedBricks(mergedTask.valid() ? mergedTask.get() : mergeLevels(), out.index);
  return out;
}

}  // namespace gs::splats
