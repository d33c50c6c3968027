#include "qnv/tileset_writer.hpp"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "qnv/error.hpp"

namespace gs::qnv {

namespace {

std::uint32_t ceilDiv(std::uint32_t a, std::uint32_t b) {
  return (a + b - 1) / b;
}

// Position of boundary `i` of `n` equal cells over [lo, hi]; the last one is hi exactly.
float cellEdge(float lo, float hi, std::uint64_t i, std::uint64_t n) {
  if (i >= n) return hi;
  return std::clamp(lo + (hi - lo) * (static_cast<float>(i) / static_cast<float>(n)), lo, hi);
}

bool rankedBefore(const SourceVector& a, const SourceVector& b) {
  return a.magnitude > b.magnitude || (a.magnitude == b.magnitude && a.source < b.source);
}

}  // namespace

TilesetLayout::TilesetLayout(const StreamHeader& whole, const TilesetOptions& options)
    : whole_(whole), options_(options) {
  if (options.brickVoxels == 0) throw InputError("--brick-voxels must be at least 1");
  if (options.brickVectors == 0) throw InputError("--brick-vectors must be at least 1");
  whole_.packetBytes = options.write.packetBytes;
  whole_.encoding = options.write.encoding;
  if (whole.kind == StreamKind::volume) {
    const std::uint32_t largest =
        std::max({whole.volumeDims.x, whole.volumeDims.y, whole.volumeDims.z, 1u});
    while ((std::uint64_t{options.brickVoxels} << depth_) < largest) ++depth_;
    if (depth_ > kTilesetMaxDepth)
      throw InputError("--brick-voxels " + std::to_string(options.brickVoxels) +
                       " needs an octree deeper than " + std::to_string(kTilesetMaxDepth) +
                       " levels for this volume");
    for (int a = 0; a < 3; ++a)
      leafGrid_[a] = std::max(1u, ceilDiv(whole.volumeDims[a], options.brickVoxels));
  } else {
    std::uint64_t capacity = options.brickVectors;
    while (depth_ < 8 && capacity < whole.vectorCount) {
      ++depth_;
      capacity = capacity > (std::uint64_t{1} << 60) ? capacity : capacity * 8;
    }
    leafGrid_ = glm::uvec3(1u << depth_);
  }
}

std::uint64_t TilesetLayout::leafCount() const {
  return std::uint64_t{leafGrid_.x} * leafGrid_.y * leafGrid_.z;
}

glm::uvec3 TilesetLayout::leafOf(const SourceVector& v) const {
  glm::uvec3 leaf(0);
  if (whole_.kind == StreamKind::volume) {
    leaf = voxelOf(v) / options_.brickVoxels;
  } else {
    for (int a = 0; a < 3; ++a) {
      const float lo = whole_.boundsMin[a], hi = whole_.boundsMax[a];
      const double t = hi > lo ? (v.position[a] - lo) / (double{hi} - lo) : 0.0;
      const double cell = std::floor(t * leafGrid_[a]);
      leaf[a] =
          cell > 0.0 ? static_cast<std::uint32_t>(std::min<double>(cell, leafGrid_[a] - 1)) : 0u;
    }
  }
  return glm::min(leaf, leafGrid_ - glm::uvec3(1));
}

glm::uvec3 TilesetLayout::voxelOf(const SourceVector& v) const {
  const glm::uvec3 d = whole_.volumeDims;
  if (d.x == 0 || d.y == 0) return glm::uvec3(0);
  return glm::uvec3(static_cast<std::uint32_t>(v.source % d.x),
                    static_cast<std::uint32_t>((v.source / d.x) % d.y),
                    static_cast<std::uint32_t>(v.source / (std::uint64_t{d.x} * d.y)));
}

std::uint64_t TilesetLayout::leafIndex(glm::uvec3 leaf) const {
  return leaf.x + std::uint64_t{leafGrid_.x} * (leaf.y + std::uint64_t{leafGrid_.y} * leaf.z);
}

glm::uvec3 TilesetLayout::leafAt(std::uint64_t index) const {
  return glm::uvec3(static_cast<std::uint32_t>(index % leafGrid_.x),
                    static_cast<std::uint32_t>((index / leafGrid_.x) % leafGrid_.y),
                    static_cast<std::uint32_t>(index / (std::uint64_t{leafGrid_.x} * leafGrid_.y)));
}

std::pair<std::uint64_t, std::uint64_t> TilesetLayout::shareLeaves(std::uint32_t share,
                                                                   std::uint32_t shares) const {
  // At most 2^36 leaves (depth 12) times 2^20 shares: no overflow.
  const std::uint64_t n = leafCount();
  return {n * share / shares, n * (share + std::uint64_t{1}) / shares};
}

std::uint64_t TilesetLayout::quota(std::uint8_t level) const {
  const unsigned shift = 3u * (depth_ - level);
  if (shift >= 63) return 1;
  const std::uint64_t cells = std::uint64_t{1} << shift;
  return (options_.brickVectors + cells - 1) / cells;
}

glm::uvec3 TilesetLayout::blockStart(const TilesetCell& node) const {
  const std::uint64_t side = std::uint64_t{options_.brickVoxels} << (depth_ - node.level);
  glm::uvec3 start(0);
  for (int a = 0; a < 3; ++a)
    start[a] = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(node.cell[a] * side, whole_.volumeDims[a]));
  return start;
}

StreamHeader TilesetLayout::brickHeader(const TilesetCell& node, std::uint64_t vectorCount) const {
  StreamHeader h = whole_;
  h.vectorCount = vectorCount;
  if (whole_.kind == StreamKind::volume) {
    const std::uint64_t side = std::uint64_t{options_.brickVoxels} << (depth_ - node.level);
    const glm::uvec3 start = blockStart(node);
    for (int a = 0; a < 3; ++a) {
      const std::uint64_t end =
          std::min<std::uint64_t>((node.cell[a] + std::uint64_t{1}) * side, whole_.volumeDims[a]);
      const std::uint32_t dims =
          static_cast<std::uint32_t>(std::max<std::uint64_t>(end, start[a] + 1) - start[a]);
      h.volumeDims[a] = dims;
      // The same expression as the whole box's, so the last block ends on it exactly.
      h.boundsMin[a] = whole_.boundsMin[a] + static_cast<float>(start[a]) * whole_.voxelSpacing[a];
      h.boundsMax[a] =
          whole_.boundsMin[a] + static_cast<float>(start[a] + dims - 1) * whole_.voxelSpacing[a];
      if (start[a] + dims == whole_.volumeDims[a]) h.boundsMax[a] = whole_.boundsMax[a];
      h.boundsMin[a] = std::min(h.boundsMin[a], h.boundsMax[a]);
    }
  } else {
    const std::uint64_t n = std::uint64_t{1} << node.level;
    for (int a = 0; a < 3; ++a) {
      h.boundsMin[a] = cellEdge(whole_.boundsMin[a], whole_.boundsMax[a], node.cell[a], n);
      h.boundsMax[a] = cellEdge(whole_.boundsMin[a], whole_.boundsMax[a], node.cell[a] + 1, n);
    }
  }
  return h;
}

BrickFile writeBrick(const TilesetCell& node, const StreamHeader& header,
                     std::span<const std::uint64_t> records) {
  BrickFile out;
  TilesetBrick& b = out.brick;
  b.level = node.level;
  b.x = node.cell.x;
  b.y = node.cell.y;
  b.z = node.cell.z;
  b.boundsMin = header.boundsMin;
  b.boundsMax = header.boundsMax;
  b.vectorCount = records.size();
  StreamHeader h = header;
  h.vectorCount = records.size();
  out.bytes = serializeHeader(h);
  const std::size_t per = h.recordsPerPacket();
  std::uint32_t sequence = 0;
  for (std::size_t first = 0; first < records.size(); first += per, ++sequence) {
    appendPacket(out.bytes, sequence, records.subspan(first, std::min(per, records.size() - first)),
                 h.encoding, &h);
    b.packetEnds.push_back(out.bytes.size());
  }
  // A Gaussian splat's words all count in the band of its first word's A code.
  const std::size_t step = h.kind == StreamKind::gaussian ? h.recordsPerElement() : 1;
  for (std::size_t i = 0; i < records.size(); i += step)
    b.histogram[tilesetBand(magnitudeCode(records[i]))] +=
        static_cast<std::uint32_t>(std::min(step, records.size() - i));
  b.fileBytes = out.bytes.size();
  return out;
}

TilesetShareWriter::TilesetShareWriter(const TilesetLayout& layout, std::uint32_t share,
                                       std::uint32_t shares)
    : layout_(layout) {
  if (shares == 0 || share >= shares || shares > kMaxTilesetShares)
    throw InputError("share " + std::to_string(share) + " of " + std::to_string(shares) +
                     " does not exist (shares are 0 to N-1)");
  range_ = layout.shareLeaves(share, shares);
}

bool TilesetShareWriter::add(const SourceVector& v) {
  const std::uint64_t leaf = layout_.leafIndex(layout_.leafOf(v));
  if (leaf < range_.first || leaf >= range_.second) return false;
  if (finished_.count(leaf))
    throw InputError("a vector arrived for tileset leaf " + std::to_string(leaf) +
                     " after it was finished");
  open_[leaf].push_back(v);
  return true;
}

std::vector<glm::uvec3> TilesetShareWriter::openLeaves() const {
  std::vector<glm::uvec3> out;
  for (const auto& [index, vectors] : open_) out.push_back(layout_.leafAt(index));
  return out;
}

std::optional<BrickFile> TilesetShareWriter::finishLeaf(glm::uvec3 leaf) {
  const std::uint64_t index = layout_.leafIndex(leaf);
  finished_.insert(index);
  const auto found = open_.find(index);
  if (found == open_.end()) return std::nullopt;
  std::vector<SourceVector> vectors = std::move(found->second);
  open_.erase(found);
  return rankLeaf(leaf, std::move(vectors), interior_);
}

void TilesetShareWriter::addInterior(InteriorParts&& parts) {
  for (auto& [node, entries] : parts) {
    std::vector<InteriorEntry>& to = interior_[node];
    if (to.empty())
      to = std::move(entries);
    else
      to.insert(to.end(), entries.begin(), entries.end());
  }
}

std::optional<BrickFile> TilesetShareWriter::rankLeaf(glm::uvec3 leaf,
                                                      std::vector<SourceVector> vectors,
                                                      InteriorParts& interior) const {
  std::sort(vectors.begin(), vectors.end(), rankedBefore);
  const std::uint8_t depth = layout_.depth();
  const StreamHeader& whole = layout_.templateHeader();
  const MagnitudeQuantizer quantizeA(whole.mapping, whole.magnitudeMin, whole.magnitudeMax);
  const auto recordFor = [&](const SourceVector& v, const TilesetCell& node,
                             const StreamHeader& h) {
    if (h.kind != StreamKind::volume) return quantizeVector(v, h, quantizeA);
    const glm::uvec3 grid = layout_.voxelOf(v) - layout_.blockStart(node);
    return quantizeVector(v, h, quantizeA, &grid);
  };
  std::size_t next = 0;
  for (std::uint8_t level = 0; level < depth && next < vectors.size(); ++level) {
    const unsigned shift = depth - level;
    const TilesetCell node{level, glm::uvec3(leaf.x >> shift, leaf.y >> shift, leaf.z >> shift)};
    const StreamHeader h = layout_.brickHeader(node, 0);
    const std::size_t end = static_cast<std::size_t>(
        std::min<std::uint64_t>(vectors.size(), next + layout_.quota(level)));
    std::vector<InteriorEntry>& entries = interior[node];
    for (; next < end; ++next)
      entries.push_back(
          {vectors[next].magnitude, vectors[next].source, recordFor(vectors[next], node, h)});
  }
  if (next == vectors.size()) return std::nullopt;
  const TilesetCell node{depth, leaf};
  const StreamHeader h = layout_.brickHeader(node, vectors.size() - next);
  std::vector<std::uint64_t> records;
  records.reserve(vectors.size() - next);
  for (; next < vectors.size(); ++next) records.push_back(recordFor(vectors[next], node, h));
  return writeBrick(node, h, records);
}

}  // namespace gs::qnv
