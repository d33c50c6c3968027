#include "splats/merged_levels.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "base/byte_order.hpp"
#include "qnv/error.hpp"
#include "splats/lod_tree.hpp"

namespace gs::splats {

namespace {

constexpr double kPiMerged = 3.14159265358979323846;
constexpr double kFixedOne = 1099511627776.0;  // 2^40: fixed-point unit of every sum
constexpr char kMergedMagic[8] = {'\x89', 'Q', 'N', 'M', '\r', '\n', '\x1a', '\n'};
constexpr std::size_t kCellBytes = 16 + 16 * MergedCell::kFields;
// Fields of MergedCell::sums.
constexpr int kWeight = 0, kMean = 1, kSecond = 4, kColor = 10, kBand2 = 13;
constexpr double kBand2Scale = kPiMerged / 2.0;
// A merged splat's thinnest scale is at least this share of its cell (a flat wall's cell
// would give 0, which the stream's log-scale range cannot hold next to the wide ones).
constexpr double kThinnestShare = 0.01;

MergedCell::Wide fixedOf(double x) {
  return static_cast<MergedCell::Wide>(std::llround(std::clamp(x, -1e6, 1e6) * kFixedOne));
}
double valueOf(MergedCell::Wide x) {
  return static_cast<double>(x) / kFixedOne;
}

std::uint64_t cellKey(std::uint8_t level, glm::uvec3 c) {
  return std::uint64_t{level} << 60 | std::uint64_t{c.x} << 40 | std::uint64_t{c.y} << 20 |
         std::uint64_t{c.z};
}

}  // namespace

MergedLevelBuilder::MergedLevelBuilder(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2)
    : MergedLevelBuilder(
          layout, cellsLog2, 0,
          static_cast<std::uint8_t>(std::clamp<int>(
              std::min<int>(layout.depth() - 1, qnv::deepestMergedLevel(cellsLog2)), 0, 255))) {}

MergedLevelBuilder::MergedLevelBuilder(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2,
                                       std::uint8_t firstLevel, std::uint8_t lastLevel)
    : layout_(layout),
      cellsLog2_(cellsLog2),
      firstLevel_(firstLevel),
      levelEnd_(static_cast<std::uint8_t>(std::min<int>(lastLevel + 1, layout.depth()))),
      brickVoxels_(layout.options().brickVoxels) {
  if (cellsLog2 < 1 || cellsLog2 > qnv::kTilesetMaxMergedLog2)
    throw qnv::InputError("merged cells per axis must be 2 to 128 (log2 " +
                          std::to_string(cellsLog2) + ")");
  // A tileset of depth 0 has no interior level: nothing is summed (the whole-range
  // constructor's case); a range asked for must be interior levels.
  if (firstLevel > lastLevel || (layout.depth() > 0 && lastLevel >= layout.depth()))
    throw qnv::InputError("merged levels " + std::to_string(firstLevel) + " to " +
                          std::to_string(lastLevel) + " are not interior levels of depth " +
                          std::to_string(layout.depth()));
  const qnv::StreamHeader& h = layout.templateHeader();
  if (h.kind == qnv::StreamKind::gaussian) {
    weightUnit_ = h.magnitudeMax;  // the largest importance: opacity times area
    shDegree_ = h.shDegree;
  } else {
    const float spread = vectorProfile(h, h.magnitudeMax, 1.0f).spread;
    weightUnit_ = meanProjectedArea(glm::vec3(spread, spread, 0.0f));
  }
  if (!(weightUnit_ > 0.0) || !std::isfinite(weightUnit_)) weightUnit_ = 1.0;
}

std::uint32_t MergedLevelBuilder::cellsPerAxis(std::uint8_t level) const {
  const std::uint32_t r = 1u << cellsLog2_;
  if (layout_.templateHeader().kind != qnv::StreamKind::volume) return r;
  // A cell is never smaller than a voxel.
  const std::uint64_t block = std::uint64_t{brickVoxels_} << (layout_.depth() - level);
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(r, block));
}

glm::uvec3 MergedLevelBuilder::cellOf(const qnv::SourceVector& v, std::uint8_t level) const {
  const qnv::StreamHeader& h = layout_.templateHeader();
  const std::uint32_t r = cellsPerAxis(level);
  const glm::uvec3 node = layout_.leafOf(v) >> glm::uvec3(layout_.depth() - level);
  glm::uvec3 cell(0);
  if (h.kind == qnv::StreamKind::volume) {
    const std::uint64_t block = std::uint64_t{brickVoxels_} << (layout_.depth() - level);
    const glm::uvec3 voxel = layout_.voxelOf(v);
    for (int a = 0; a < 3; ++a)
      cell[a] = static_cast<std::uint32_t>(std::uint64_t{voxel[a]} * r / block);
  } else {
    const double n = static_cast<double>(std::uint64_t{r} << level);
    for (int a = 0; a < 3; ++a) {
      const double lo = h.boundsMin[a], hi = h.boundsMax[a];
      const double t = hi > lo ? (v.position[a] - lo) / (hi - lo) : 0.0;
      const double c = std::floor(t * n);
      cell[a] = c > 0.0 ? static_cast<std::uint32_t>(std::min(c, n - 1.0)) : 0u;
    }
  }
  // Always inside the node the octree puts the vector in.
  return glm::clamp(cell, node * r, node * r + glm::uvec3(r - 1));
}

MergedLevelBuilder::CellFrame MergedLevelBuilder::frameOf(std::uint8_t level,
                                                          glm::uvec3 cell) const {
  const qnv::StreamHeader& h = layout_.templateHeader();
  const std::uint32_t r = cellsPerAxis(level);
  CellFrame f;
  if (h.kind == qnv::StreamKind::volume) {
    const double side =
        static_cast<double>(std::uint64_t{brickVoxels_} << (layout_.depth() - level)) / r;
    const glm::dvec3 spacing(h.voxelSpacing);
    f.origin = glm::dvec3(h.boundsMin) + glm::dvec3(cell) * side * spacing;
    f.size = side * std::max({spacing.x, spacing.y, spacing.z, 1e-12});
  } else {
    const double n = static_cast<double>(std::uint64_t{r} << level);
    const glm::dvec3 lo(h.boundsMin), extent = glm::dvec3(h.boundsMax) - lo;
    f.origin = lo + extent * (glm::dvec3(cell) / n);
    f.size = std::max({extent.x, extent.y, extent.z, 1e-12}) / n;
  }
  return f;
}

void MergedLevelBuilder::add(const qnv::SourceVector& v) {
  const qnv::StreamHeader& h = layout_.templateHeader();
  const qnv::Rgba8 rgba = h.palette[v.color];
  const VectorProfile profile = vectorProfile(h, v.magnitude, rgba.a / 255.0f);
  const double length = glm::length(glm::dvec3(v.normal));
  if (!(profile.peak >= kVisiblePeak) || !(profile.spread > 0.0f) || !(length > 0.0) ||
      !std::isfinite(length))
    return;
  const glm::dvec3 normal = glm::dvec3(v.normal) / length;
  const double spread = profile.spread;
  // The renderer skips each pixel where the profile is below kVisiblePeak: a disc's drawn
  // integral is 2 pi s^2 (peak - kVisiblePeak), so its coverage counts that share.
  const double weight = (profile.peak - kVisiblePeak) *
                        meanProjectedArea(glm::vec3(profile.spread, profile.spread, 0.0f)) /
                        weightUnit_;
  // The headlight's |n . d| on SH bands 0 and 2: its Legendre series to degree 2,
  // 1/2 + 5/8 P2(n . d) (the least-squares fit over directions); by the addition theorem,
  // band 2's coefficients are (5/8) (4 pi / 5) Y_2m(n) = (pi / 2) Y_2m(n).
  float basis[16];
  shBasis(2, glm::vec3(normal), basis);
  const glm::dvec3 color(rgba.r / 255.0, rgba.g / 255.0, rgba.b / 255.0);
  for (std::uint8_t level = firstLevel_; level < levelEnd_; ++level) {
    const glm::uvec3 c = cellOf(v, level);
    const CellFrame f = frameOf(level, c);
    const glm::dvec3 q = (glm::dvec3(v.position) - f.origin) / f.size;
    const double s2 = spread * spread / (f.size * f.size);
    MergedCell& cell = cells_[cellKey(level, c)];
    ++cell.count;
    MergedCell::Wide* sum = cell.sums;
    sum[kWeight] += fixedOf(weight);
    for (int a = 0; a < 3; ++a) sum[kMean + a] += fixedOf(weight * q[a]);
    // The disc's covariance s^2 (I - n n^T) plus the centre's q q^T.
    int k = kSecond;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b)
        sum[k++] +=
            fixedOf(weight * (s2 * ((a == b ? 1.0 : 0.0) - normal[a] * normal[b]) + q[a] * q[b]));
    for (int a = 0; a < 3; ++a) sum[kColor + a] += fixedOf(weight * color[a]);
    for (int m = 0; m < 5; ++m) sum[kBand2 + m] += fixedOf(weight * kBand2Scale * basis[4 + m]);
  }
}

void MergedLevelBuilder::addGaussian(const GaussianCloud& cloud, std::size_t i) {
  const glm::vec3 scale = glm::abs(cloud.scales[i]);
  const double weight = splatCoverage(scale, cloud.opacities[i]) / weightUnit_;
  if (!(weight > 0.0) || !std::isfinite(weight)) return;
  const glm::dmat3 sigma(covariance(scale, glm::normalize(cloud.rotations[i])));
  // The colour: band 0 in the fixed-point sums, the higher bands (linear in the
  // coefficients, so the members' weighted mean is the mean of their colours) beside.
  const glm::dvec3 color = glm::dvec3(0.5) + double{kShC0} * glm::dvec3(cloud.shDc[i]);
  const int rest = std::min(cloud.shRestPerSplat(), shCoefficients(shDegree_) - 1);
  qnv::SourceVector v;
  v.position = cloud.positions[i];
  for (std::uint8_t level = firstLevel_; level < levelEnd_; ++level) {
    const glm::uvec3 c = cellOf(v, level);
    const CellFrame f = frameOf(level, c);
    const glm::dvec3 q = (glm::dvec3(v.position) - f.origin) / f.size;
    MergedCell& cell = cells_[cellKey(level, c)];
    ++cell.count;
    MergedCell::Wide* sum = cell.sums;
    sum[kWeight] += fixedOf(weight);
    for (int a = 0; a < 3; ++a) sum[kMean + a] += fixedOf(weight * q[a]);
    int k = kSecond;  // the splat's own covariance plus the centre's q q^T, in cell units
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b)
        sum[k++] += fixedOf(weight * (sigma[a][b] / (f.size * f.size) + q[a] * q[b]));
    for (int a = 0; a < 3; ++a) sum[kColor + a] += fixedOf(weight * color[a]);
    if (rest > 0) {
      std::vector<glm::dvec3>& sh = shSums_[cellKey(level, c)];
      sh.resize(static_cast<std::size_t>(rest), glm::dvec3(0.0));
      for (int j = 0; j < rest; ++j)
        sh[static_cast<std::size_t>(j)] +=
            weight * glm::dvec3(cloud.shRest[i * static_cast<std::size_t>(cloud.shRestPerSplat()) +
                                             static_cast<std::size_t>(j)]);
    }
  }
}

std::string MergedLevelBuilder::serialize() const {
  std::vector<std::uint64_t> keys;
  keys.reserve(cells_.size());
  for (const auto& [key, cell] : cells_) keys.push_back(key);
  std::sort(keys.begin(), keys.end());
  std::string out(kMergedMagic, sizeof kMergedMagic);
  base::appendLe<std::uint8_t>(out, cellsLog2_);
  out.append(3, '\0');
  base::appendLe<std::uint64_t>(out, keys.size());
  for (const std::uint64_t key : keys) {
    const MergedCell& cell = cells_.at(key);
    base::appendLe<std::uint64_t>(out, key);
    base::appendLe<std::uint64_t>(out, cell.count);
    for (const MergedCell::Wide s : cell.sums) {
      const auto u = static_cast<MergedCell::UnsignedWide>(s);
      base::appendLe<std::uint64_t>(out, static_cast<std::uint64_t>(u));
      base::appendLe<std::uint64_t>(out, static_cast<std::uint64_t>(u >> 64));
    }
  }
  base::appendLe<std::uint32_t>(out, qnv::crc32(out));
  return out;
}

bool MergedLevelBuilder::addSerialized(std::string_view bytes, const std::string& name,
                                       std::string& error) {
  const auto fail = [&](const std::string& why) {
    error = name + ": " + why;
    return false;
  };
  if (bytes.size() < 24 || !std::equal(kMergedMagic, kMergedMagic + 8, bytes.data()))
    return fail("not a tileset's merged-level part (signature)");
  const char* p = bytes.data();
  if (static_cast<std::uint8_t>(p[8]) != cellsLog2_ || p[9] != 0 || p[10] != 0 || p[11] != 0)
    return fail("merged cells per axis differ from this encode's");
  const auto count = base::loadLe<std::uint64_t>(p + 12);
  if (count > (bytes.size() - 24) / kCellBytes || 24 + count * kCellBytes != bytes.size())
    return fail("its cell count does not fit its size");
  if (qnv::crc32(bytes.substr(0, bytes.size() - 4)) !=
      base::loadLe<std::uint32_t>(p + bytes.size() - 4))
    return fail("damaged or truncated (CRC mismatch)");
  for (std::uint64_t i = 0; i < count; ++i) {
    const char* c = p + 20 + i * kCellBytes;
    const auto key = base::loadLe<std::uint64_t>(c);
    const auto level = static_cast<std::uint8_t>(key >> 60);
    const std::uint64_t grid = std::uint64_t{cellsPerAxis(0)} << level;
    const std::uint64_t x = (key >> 40) & 0xfffffu, y = (key >> 20) & 0xfffffu, z = key & 0xfffffu;
    if (level < firstLevel_ || level >= levelEnd_ || x >= grid || y >= grid || z >= grid)
      return fail("cell " + std::to_string(i) + " lies outside the octree");
    MergedCell& cell = cells_[key];
    cell.count += base::loadLe<std::uint64_t>(c + 8);
    for (int f = 0; f < MergedCell::kFields; ++f) {
      const auto lo = base::loadLe<std::uint64_t>(c + 16 + 16 * f);
      const auto hi = base::loadLe<std::uint64_t>(c + 24 + 16 * f);
      cell.sums[f] +=
          static_cast<MergedCell::Wide>((static_cast<MergedCell::UnsignedWide>(hi) << 64) | lo);
    }
  }
  return true;
}

std::map<qnv::TilesetCell, GaussianCloud> MergedLevelBuilder::build() const {
  const qnv::StreamHeader& h = layout_.templateHeader();
  const double ambient = h.kind == qnv::StreamKind::volume ? 0.2 : 0.0;
  std::vector<std::uint64_t> keys;
  keys.reserve(cells_.size());
  for (const auto& [key, cell] : cells_) keys.push_back(key);
  // (level, z, y, x) order: the key holds x above z, so sort by a reordered key.
  const auto zyx = [](std::uint64_t k) {
    return (k >> 60) << 60 | (k & 0xfffffu) << 40 | ((k >> 20) & 0xfffffu) << 20 |
           ((k >> 40) & 0xfffffu);
  };
  std::sort(keys.begin(), keys.end(),
            [&](std::uint64_t a, std::uint64_t b) { return zyx(a) < zyx(b); });
  std::map<qnv::TilesetCell, GaussianCloud> nodes;
  for (const std::uint64_t key : keys) {
    const MergedCell& cell = cells_.at(key);
    const double w = valueOf(cell.sums[kWeight]);
    if (!(w > 0.0)) continue;
    const auto level = static_cast<std::uint8_t>(key >> 60);
    const glm::uvec3 c(static_cast<std::uint32_t>((key >> 40) & 0xfffffu),
                       static_cast<std::uint32_t>((key >> 20) & 0xfffffu),
                       static_cast<std::uint32_t>(key & 0xfffffu));
    const CellFrame f = frameOf(level, c);
    glm::dvec3 mean;
    for (int a = 0; a < 3; ++a) mean[a] = valueOf(cell.sums[kMean + a]) / w;
    glm::dmat3 sigma(0.0);
    int k = kSecond;
    for (int a = 0; a < 3; ++a)
      for (int b = a; b < 3; ++b) {
        const double v = (valueOf(cell.sums[k++]) / w - mean[a] * mean[b]) * f.size * f.size;
        sigma[a][b] = sigma[b][a] = v;
      }
    glm::vec3 scale;
    glm::quat rotation;
    covarianceToScaleRotation(sigma, scale, rotation);
    scale = glm::max(scale, glm::vec3(static_cast<float>(kThinnestShare * f.size)));
    const float opacity = mergedOpacity(w * weightUnit_, scale);
    if (!(opacity > 0.0f)) continue;
    const qnv::TilesetCell node{level, c / cellsPerAxis(level)};
    GaussianCloud& cloud = nodes[node];
    const bool gaussian = h.kind == qnv::StreamKind::gaussian;
    if (cloud.empty()) cloud.setShDegree(gaussian ? shDegree_ : 2);
    cloud.positions.push_back(glm::vec3(f.origin + mean * f.size));
    cloud.scales.push_back(scale);
    cloud.rotations.push_back(rotation);
    cloud.opacities.push_back(opacity);
    // colour(d) = rgb (ambient + (1 - ambient) shade(d)), shade's band 0 being 1/2.
    glm::dvec3 rgb;
    for (int a = 0; a < 3; ++a) rgb[a] = valueOf(cell.sums[kColor + a]) / w;
    // A Gaussian scene's colours are not shaded: rgb is the members' band-0 colour.
    const double shade =
        h.kind == qnv::StreamKind::gaussian ? 1.0 : ambient + (1.0 - ambient) * 0.5;
    const glm::dvec3 dc = (rgb * shade - 0.5) / double{kShC0};
    cloud.shDc.push_back(glm::vec3(dc));
    if (gaussian) {  // the members' weighted mean of each higher coefficient
      const auto sh = shSums_.find(key);
      for (int j = 0; j < cloud.shRestPerSplat(); ++j)
        cloud.shRest.push_back(sh != shSums_.end()
                                   ? glm::vec3(sh->second[static_cast<std::size_t>(j)] / w)
                                   : glm::vec3(0.0f));
      continue;
    }
    for (int m = 0; m < 3; ++m) cloud.shRest.push_back(glm::vec3(0.0f));
    for (int m = 0; m < 5; ++m)
      cloud.shRest.push_back(glm::vec3(rgb * (1.0 - ambient) * valueOf(cell.sums[kBand2 + m]) / w));
  }
  return nodes;
}

namespace {
// The 21 low bits of `v` spread to every third bit.
std::uint64_t spreadBits(std::uint32_t v) {
  std::uint64_t x = v & 0x1fffffu;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}
}  // namespace

std::uint64_t mortonOfCell(glm::uvec3 cell) {
  return spreadBits(cell.x) | spreadBits(cell.y) << 1 | spreadBits(cell.z) << 2;
}

glm::uvec3 cellOfMorton(std::uint64_t code) {
  glm::uvec3 cell(0);
  for (unsigned bit = 0; bit < 21; ++bit)
    for (unsigned a = 0; a < 3; ++a)
      cell[static_cast<int>(a)] |= static_cast<std::uint32_t>((code >> (3 * bit + a)) & 1u) << bit;
  return cell;
}

GaussianMergedLevels::GaussianMergedLevels(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2,
                                           Sink sink)
    : layout_(layout), sink_(std::move(sink)) {
  if (layout.depth() == 0) throw qnv::InputError("a tileset of depth 0 has no merged levels");
  for (std::uint8_t level = 0; level < layout.depth(); ++level)
    levels_.emplace_back(layout, cellsLog2, level, level);
  open_.resize(levels_.size());
}

void GaussianMergedLevels::flush(std::size_t level) {
  if (!open_[level]) return;
  MergedLevelBuilder& cells = levels_[level];
  cellsMerged_ += cells.cellCount();
  const qnv::TilesetCell open{static_cast<std::uint8_t>(level), *open_[level]};
  open_[level].reset();
  std::map<qnv::TilesetCell, GaussianCloud> built = cells.build();
  cells.clear();
  for (auto& [node, cloud] : built) {
    // Every cell of a splat lies in the node the octree puts it in (cellOf clamps it).
    if (!(node == open))
      throw std::logic_error("GaussianMergedLevels: a merged cell outside its open node");
    sink_(node, std::move(cloud));
  }
}

void GaussianMergedLevels::addLeaf(glm::uvec3 leaf, const GaussianCloud& cloud,
                                   std::span<const std::uint32_t> members) {
  const std::uint64_t code = mortonOfCell(leaf);
  if (lastLeaf_ && code <= *lastLeaf_)
    throw std::logic_error("GaussianMergedLevels: leaves must come in increasing Morton order");
  lastLeaf_ = code;
  const std::uint8_t depth = layout_.depth();
  for (std::size_t level = levels_.size(); level-- > 0;) {  // deepest first
    const glm::uvec3 node = leaf >> glm::uvec3(depth - level);
    if (open_[level] && *open_[level] != node) flush(level);
    open_[level] = node;
  }
  std::size_t held = 0;
  for (MergedLevelBuilder& cells : levels_) {
    for (const std::uint32_t i : members) cells.addGaussian(cloud, i);
    held += cells.cellCount();
  }
  peakCells_ = std::max(peakCells_, held);
}

void GaussianMergedLevels::finish() {
  for (std::size_t level = levels_.size(); level-- > 0;) flush(level);
}

}  // namespace gs::splats
