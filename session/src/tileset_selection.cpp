#include "session/tileset_selection.hpp"

#include "qnv/record.hpp"
#include "splats/vector_splat.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <queue>
#include <unordered_map>

namespace gs::session {

namespace {

std::uint64_t cellKey(std::uint32_t level, std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  return (std::uint64_t{level} << 48) | (std::uint64_t{x & 0xffffu} << 32) |
         (std::uint64_t{y & 0xffffu} << 16) | std::uint64_t{z & 0xffffu};
}

struct Projected {
  bool visible = false;
  double pixels = 0.0;  // projected diameter
};

Projected project(const qnv::TilesetBrick& b, const TilesetView& v) {
  const glm::vec3 right = glm::normalize(glm::cross(v.forward, v.up));
  const double t = std::tan(static_cast<double>(std::clamp(v.verticalFov, 1e-3f, 3.1f)) / 2.0);
  const double th = t * static_cast<double>(std::max(v.aspect, 1e-3f));
  const double nearZ = std::max(0.0, static_cast<double>(v.nearClip));
  // Eye coordinates of the eight corners; the box is culled when all lie outside one plane.
  int outside[5] = {0, 0, 0, 0, 0};
  glm::dvec3 lo(1e300), hi(-1e300);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 local((corner & 1) ? b.boundsMax.x : b.boundsMin.x,
                          (corner & 2) ? b.boundsMax.y : b.boundsMin.y,
                          (corner & 4) ? b.boundsMax.z : b.boundsMin.z);
    const glm::vec3 w = glm::vec3(v.model * glm::vec4(local, 1.0f));
    lo = glm::min(lo, glm::dvec3(w));
    hi = glm::max(hi, glm::dvec3(w));
    const glm::vec3 d = w - v.position;
    const double x = glm::dot(d, right), y = glm::dot(d, v.up), z = glm::dot(d, v.forward);
    outside[0] += x > th * z;
    outside[1] += -x > th * z;
    outside[2] += y > t * z;
    outside[3] += -y > t * z;
    outside[4] += z < nearZ;
  }
  Projected p;
  for (int plane = 0; plane < 5; ++plane)
    if (outside[plane] == 8) return p;
  p.visible = true;
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const double radius = glm::length(hi - lo) * 0.5;
  const double distance = std::max(glm::length(centre - glm::dvec3(v.position)) - radius,
                                   std::max(nearZ, radius * 1e-3 + 1e-9));
  const double focal = static_cast<double>(std::max(v.heightPixels, 1)) / (2.0 * t);
  p.pixels = std::min(2.0 * radius / distance * focal, 1e9);
  return p;
}

double meanBand(const qnv::TilesetBrick& b) {
  double sum = 0.0, weighted = 0.0;
  for (std::size_t band = 0; band < b.histogram.size(); ++band) {
    sum += b.histogram[band];
    weighted += static_cast<double>(band) * b.histogram[band];
  }
  return sum > 0.0 ? weighted / sum / 15.0 : 0.0;
}

/// Vectors of `b` whose A code lies at or above band position `threshold` (0..16; band b
/// spans [b, b + 1), a band cut in part counts in proportion): the prefix of the brick
/// above one global magnitude.
double aboveThreshold(const qnv::TilesetBrick& b, double threshold) {
  double n = 0.0;
  for (std::size_t band = 0; band < b.histogram.size(); ++band)
    n += b.histogram[band] * std::clamp(static_cast<double>(band) + 1.0 - threshold, 0.0, 1.0);
  return n;
}

/// What the opacity-aware part of the rule knows of each brick of a volume or Gaussian
/// tileset (empty for surfaces): the optical depth its vectors of each band add, averaged over the
/// brick's mean projected area, and the optical depth all its descendants add, averaged over the
/// same area. Both are independent of the view (a splat's opacity and its footprint shrink
/// together with distance).
struct OpticalDepths {
  std::vector<std::array<double, qnv::kTilesetBands>> own;
  std::vector<double> below;
};

/// Optical depth of one vector of band `band` times the area it covers (world units^2):
/// the integral of a volume vector's disc (splats::vectorProfile), peak * 2 pi s^2, s = 2 sigma
/// voxelSize and peak = opacityScale * sqrt(A / magnitudeMax) (clamped to 1) at the band's
/// centre code; the transfer function's alpha is taken as 1 (an upper bound).
double bandOpacityArea(const qnv::StreamHeader& h, std::size_t band) {
  const float a = qnv::reconstructMagnitude(static_cast<std::uint32_t>(band) * 2048u + 1024u,
                                            h.mapping, h.magnitudeMin, h.magnitudeMax);
  const splats::VectorProfile p = splats::vectorProfile(h, a, 1.0f);
  const double spread = p.spread;
  return p.peak * 2.0 * 3.14159265358979 * spread * spread;
}

/// Mean projected area of a brick's box over all directions: a quarter of its surface
/// area (Cauchy's formula for convex bodies).
double meanProjectedArea(const qnv::TilesetBrick& b) {
  const glm::dvec3 e = glm::max(glm::dvec3(b.boundsMax - b.boundsMin), glm::dvec3(1e-9));
  return (e.x * e.y + e.y * e.z + e.z * e.x) / 2.0;
}

OpticalDepths opticalDepths(const qnv::TilesetIndex& index,
                            const std::unordered_map<std::uint64_t, std::size_t>& byCell) {
  OpticalDepths d;
  const qnv::StreamHeader& h = index.header;
  if (h.kind != qnv::StreamKind::volume && h.kind != qnv::StreamKind::gaussian) return d;
  const auto& bricks = index.bricks;
  std::array<double, qnv::kTilesetBands> perVector{};
  for (std::size_t band = 0; band < qnv::kTilesetBands; ++band)
    // A Gaussian's A is its coverage, opacity times area, shared by its records.
    perVector[band] =
        h.kind == qnv::StreamKind::volume
            ? bandOpacityArea(h, band)
            : qnv::reconstructMagnitude(static_cast<std::uint32_t>(band) * 2048u + 1024u, h.mapping,
                                        h.magnitudeMin, h.magnitudeMax) /
                  h.recordsPerElement();
  d.own.resize(bricks.size());
  d.below.assign(bricks.size(), 0.0);
  std::vector<double> total(bricks.size(), 0.0);  // opacity-area of the brick and below
  for (std::size_t i = 0; i < bricks.size(); ++i)
    for (std::size_t band = 0; band < qnv::kTilesetBands; ++band) {
      const double w = bricks[i].histogram[band] * perVector[band];
      d.own[i][band] = w / meanProjectedArea(bricks[i]);
      total[i] += w;
    }
  // Bricks are sorted by level: from the deepest up, each adds its subtree to its parent.
  for (std::size_t k = bricks.size(); k-- > 0;) {
    const auto& b = bricks[k];
    if (b.level == 0) continue;
    const auto parent = byCell.find(cellKey(b.level - 1u, b.x / 2, b.y / 2, b.z / 2));
    if (parent == byCell.end()) continue;
    total[parent->second] += total[k];
    d.below[parent->second] += total[k];
  }
  for (std::size_t i = 0; i < bricks.size(); ++i) d.below[i] /= meanProjectedArea(bricks[i]);
  return d;
}

/// Records of brick `i` the opacity-aware rule keeps: all but its weakest vectors whose
/// optical depth, together, stays within `maxLost` (bands dropped from the weakest up, the
/// last one in part).
double opacityRecords(const qnv::TilesetBrick& b, const std::array<double, qnv::kTilesetBands>& own,
                      double maxLost) {
  double dropped = 0.0, lost = 0.0;
  for (std::size_t band = 0; band < qnv::kTilesetBands; ++band) {
    if (b.histogram[band] == 0) continue;
    if (lost + own[band] <= maxLost) {
      lost += own[band];
      dropped += b.histogram[band];
      continue;
    }
    dropped += b.histogram[band] * std::max(0.0, (maxLost - lost) / own[band]);
    break;
  }
  return static_cast<double>(b.vectorCount) - dropped;
}

/// The walk in priority order at threshold `ppv`, stopping at `limit` records, keeping
/// in each brick only the vectors above band position `threshold` (0: all).
std::vector<BrickChoice> walk(const qnv::TilesetIndex& index,
                              const std::unordered_map<std::uint64_t, std::size_t>& byCell,
                              const OpticalDepths& depths, const TilesetView& view,
                              const TilesetBudget& budget, std::span<const std::uint8_t> skip,
                              std::uint64_t limit, double threshold = 0.0) {
  std::vector<BrickChoice> out;
  const auto& bricks = index.bricks;
  // A Gaussian tileset's splat is recordsPerElement() records: the threshold counts splats.
  const double ppv = std::max(budget.pixelsPerVector, 1e-6) / index.header.recordsPerElement();
  const bool opacityAware = !depths.own.empty() && budget.maxLostOpticalDepth > 0.0;
  using Entry = std::pair<double, std::size_t>;  // priority, brick
  std::priority_queue<Entry> queue;
  std::vector<Projected> seen(bricks.size());
  // A child's priority is capped by its parent's, so that ancestors come first in every
  // merge of views too.
  auto consider = [&](std::size_t i, double cap) {
    if (!skip.empty() && skip[i] != 0) return;
    const Projected p = project(bricks[i], view);
    if (!p.visible || bricks[i].vectorCount == 0) return;
    seen[i] = p;
    queue.push({std::min(cap, p.pixels * (1.0 + meanBand(bricks[i]))), i});
  };
  // Roots: level 0, and any brick whose parent is missing (an index need not hold them).
  for (std::size_t i = 0; i < bricks.size(); ++i) {
    const auto& b = bricks[i];
    if (b.level == 0 || !byCell.count(cellKey(b.level - 1u, b.x / 2, b.y / 2, b.z / 2)))
      consider(i, 1e300);
  }
  const std::uint64_t perPacket = std::max<std::uint64_t>(index.header.recordsPerPacket(), 1);
  std::uint64_t used = 0;
  while (!queue.empty() && used < limit) {
    const auto [priority, i] = queue.top();
    queue.pop();
    const qnv::TilesetBrick& b = bricks[i];
    const double area = seen[i].pixels * seen[i].pixels;
    const double count = static_cast<double>(b.vectorCount);
    double wanted = std::min(count, area / ppv);
    if (opacityAware)
      wanted = std::max(wanted, opacityRecords(b, depths.own[i], budget.maxLostOpticalDepth));
    std::uint64_t records =
        wanted >= count ? b.vectorCount : static_cast<std::uint64_t>(std::ceil(wanted));
    if (threshold > 0.0)
      records =
          std::min(records, static_cast<std::uint64_t>(std::ceil(aboveThreshold(b, threshold))));
    // Nothing above the threshold here: nor in the descendants (each node took the
    // largest vectors of every leaf below it).
    if (records == 0) continue;
    records = std::min(records, limit - used);
    records = std::min(b.vectorCount, (std::max<std::uint64_t>(records, 1) + perPacket - 1) /
                                          perPacket * perPacket);
    BrickChoice c;
    c.brick = i;
    c.records = records;
    c.bytes = qnv::brickPrefixBytes(b, index.header, records);
    c.priority = priority;
    c.pixels = seen[i].pixels;
    out.push_back(c);
    used += records;
    const bool refine =
        area / count > ppv || (opacityAware && depths.below[i] > budget.maxLostOpticalDepth);
    if (refine && b.level < 31) {
      for (std::uint32_t k = 0; k < 8; ++k) {
        const auto it = byCell.find(cellKey(b.level + 1u, b.x * 2 + (k & 1),
                                            b.y * 2 + ((k >> 1) & 1), b.z * 2 + ((k >> 2) & 1)));
        if (it != byCell.end()) consider(it->second, priority);
      }
    }
  }
  return out;
}

std::unordered_map<std::uint64_t, std::size_t> bricksByCell(const qnv::TilesetIndex& index) {
  std::unordered_map<std::uint64_t, std::size_t> byCell;
  byCell.reserve(index.bricks.size());
  for (std::size_t i = 0; i < index.bricks.size(); ++i) {
    const auto& b = index.bricks[i];
    byCell.emplace(cellKey(b.level, b.x, b.y, b.z), i);
  }
  return byCell;
}

}  // namespace

MergedChoice chooseMerged(const qnv::TilesetIndex& index, const std::vector<TilesetView>& views,
                          double mergedPixels, std::span<const std::uint8_t> unavailable) {
  MergedChoice out;
  if (index.mergedCellsLog2 == 0 || index.bricks.empty()) return out;
  const auto byCell = bricksByCell(index);
  const auto& bricks = index.bricks;
  const double cells = static_cast<double>(1u << index.mergedCellsLog2);
  enum : std::uint8_t { unseen = 0, merged = 1, refined = 2 };
  std::vector<std::uint8_t> state(bricks.size(), unseen);
  for (const TilesetView& view : views) {
    std::vector<std::size_t> stack;
    for (std::size_t i = 0; i < bricks.size() && bricks[i].level == 0; ++i) stack.push_back(i);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      const qnv::TilesetBrick& b = bricks[i];
      const Projected p = project(b, view);
      if (!p.visible) continue;
      const bool readable = unavailable.empty() || unavailable[i] == 0;
      if (index.hasMerged(b.level) && readable && p.pixels / cells <= mergedPixels) {
        if (state[i] == unseen) state[i] = merged;
        continue;
      }
      state[i] = refined;
      for (std::uint32_t k = 0; k < 8; ++k) {
        const auto it = byCell.find(cellKey(b.level + 1u, b.x * 2 + (k & 1),
                                            b.y * 2 + ((k >> 1) & 1), b.z * 2 + ((k >> 2) & 1)));
        if (it != byCell.end()) stack.push_back(it->second);
      }
    }
  }
  // A refined brick all of whose children are merged, or out of every view (its vectors
  // lie in its children's regions), has nothing left to draw: it is skipped too. Bottom
  // up: bricks are sorted by level.
  std::vector<std::uint8_t> covered(bricks.size(), 0);
  for (std::size_t i = bricks.size(); i-- > 0;) {
    const qnv::TilesetBrick& b = bricks[i];
    if (state[i] == merged) covered[i] = 1;
    if (state[i] != refined || b.level >= index.depth) continue;
    bool all = true;
    for (std::uint32_t k = 0; k < 8 && all; ++k) {
      const auto it = byCell.find(cellKey(b.level + 1u, b.x * 2 + (k & 1), b.y * 2 + ((k >> 1) & 1),
                                          b.z * 2 + ((k >> 2) & 1)));
      all = it == byCell.end() || state[it->second] == unseen || covered[it->second] != 0;
    }
    covered[i] = all;
  }
  // Top down: whether a merged brick lies above is known for a parent before its children.
  out.skip.assign(bricks.size(), 0);
  std::vector<std::uint8_t> belowMerged(bricks.size(), 0);
  for (std::size_t i = 0; i < bricks.size(); ++i) {
    const qnv::TilesetBrick& b = bricks[i];
    bool under = false;
    if (b.level > 0)
      if (const auto parent = byCell.find(cellKey(b.level - 1u, b.x / 2, b.y / 2, b.z / 2));
          parent != byCell.end())
        under = belowMerged[parent->second] != 0 || state[parent->second] == merged;
    belowMerged[i] = under;
    if (under || covered[i] != 0) out.skip[i] = 1;
    if (!under && state[i] == merged) out.merged.push_back(i);
  }
  if (out.merged.empty()) out.skip.clear();
  return out;
}

std::vector<BrickChoice> selectBricks(const qnv::TilesetIndex& index, const TilesetView& view,
                                      const TilesetBudget& budget,
                                      std::span<const std::uint8_t> skip) {
  const std::uint64_t limit = std::min(budget.vectors, budget.memoryVectors);
  const auto byCell = bricksByCell(index);
  const OpticalDepths depths = opticalDepths(index, byCell);
  auto records = [](const std::vector<BrickChoice>& choices) {
    std::uint64_t n = 0;
    for (const BrickChoice& c : choices) n += c.records;
    return n;
  };
  std::vector<BrickChoice> out = walk(index, byCell, depths, view, budget, skip, UINT64_MAX);
  if (records(out) <= limit) return out;
  // Over budget: keep the vectors above one magnitude threshold over every visible brick
  // (read from the histograms), as the single stream's prefix keeps the largest vectors
  // of the whole data; bisection on the threshold until the choice fits.
  double low = 0.0, high = 16.0;
  for (int i = 0; i < 30; ++i) {
    const double mid = (low + high) / 2.0;
    (records(walk(index, byCell, depths, view, budget, skip, UINT64_MAX, mid)) > limit ? low
                                                                                       : high) =
        mid;
  }
  return walk(index, byCell, depths, view, budget, skip, limit, high);
}

std::vector<BrickChoice> mergeChoices(const std::vector<std::vector<BrickChoice>>& views) {
  std::map<std::size_t, BrickChoice> best;
  for (const auto& choices : views)
    for (const BrickChoice& c : choices) {
      auto [it, inserted] = best.emplace(c.brick, c);
      if (inserted) continue;
      BrickChoice& b = it->second;
      if (c.records > b.records) {
        b.records = c.records;
        b.bytes = c.bytes;
      }
      b.priority = std::max(b.priority, c.priority);
      b.pixels = std::max(b.pixels, c.pixels);
    }
  std::vector<BrickChoice> out;
  for (const auto& [i, c] : best) out.push_back(c);
  // Stable on the index order (levels ascending) so ancestors stay before children when
  // priorities tie.
  std::stable_sort(out.begin(), out.end(), [](const BrickChoice& a, const BrickChoice& b) {
    return a.priority > b.priority;
  });
  return out;
}

std::uint64_t totalBytes(const std::vector<BrickChoice>& choices) {
  std::uint64_t n = 0;
  for (const BrickChoice& c : choices) n += c.bytes;
  return n;
}

}  // namespace gs::session
