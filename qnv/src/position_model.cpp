// The position grid of a stream and its stream model block (docs/qnv-format.md, "Compact
// coding" and "Stream model"): the voxel grid of a volume, and the occupied blocks of the
// index space, so that entropy packets code positions among occupied blocks only, and
// (model kind 2) each occupied block's mean direction, from which packets may code their
// directions.
#include <algorithm>
#include <cmath>

#include "base/byte_order.hpp"
#include "entropy_fields.hpp"
#include "entropy_payload.hpp"
#include "morton.hpp"
#include "qnv/record.hpp"
#include "qnv/stream.hpp"

namespace gs::qnv::detail {

using base::appendLe;
using base::loadLe;

namespace {

constexpr std::uint8_t kModelOccupancy = 1;        // kind: the occupied blocks
constexpr std::uint8_t kModelDirections = 2;       // kind: occupied blocks with their directions
constexpr std::uint8_t kModelSharedTables = 0x80;  // kind bit: shared tables follow
constexpr int kMinBlockShift = 1, kMaxBlockShift = 7;
constexpr std::uint64_t kMaxBlocks = std::uint64_t{1} << 21;  // blocks in the index space
constexpr std::size_t kChunkRecords = 8191;                   // records per entropy payload
constexpr std::size_t kModelPreamble = 6;                     // kind, shift, block count

// Blocks per axis at this shift.
std::array<std::uint32_t, 3> blocksPerAxis(const PositionGrid& grid, int shift) {
  std::array<std::uint32_t, 3> n{};
  for (int a = 0; a < 3; ++a) n[a] = (grid.axisSize(a) + (1u << shift) - 1) >> shift;
  return n;
}

// Reads the occupancy part of a model (after its kind byte) from `at`, which it advances;
// with `directions` (kind 2) each block carries its direction. False when anything is
// inconsistent.
bool loadOccupancy(PositionGrid& grid, std::string_view model, std::size_t& at, bool directions) {
  if (model.size() - at < kModelPreamble - 1) return false;
  const int shift = loadLe<std::uint8_t>(model.data() + at);
  const auto count = loadLe<std::uint32_t>(model.data() + at + 1);
  at += kModelPreamble - 1;
  if (shift < kMinBlockShift || shift > kMaxBlockShift) return false;
  const auto perAxis = blocksPerAxis(grid, shift);
  const std::uint64_t total = std::uint64_t{perAxis[0]} * perAxis[1] * perAxis[2];
  if (total > kMaxBlocks || count == 0 || count > total) return false;
  grid.blocks.clear();
  grid.blocks.reserve(count);
  grid.blockDirections.clear();
  if (directions) grid.blockDirections.reserve(count);
  std::vector<std::uint64_t> records;
  const PositionGrid cells;  // block coordinates are coded as plain cells
  while (grid.blocks.size() < count) {
    const std::size_t n = std::min<std::size_t>(kChunkRecords, count - grid.blocks.size());
    if (model.size() - at < 2) return false;
    const auto bytes = loadLe<std::uint16_t>(model.data() + at);
    at += 2;
    if (model.size() - at < bytes) return false;
    records.resize(n);
    if (!decodeEntropyPayload(model.substr(at, bytes), n, cells, records.data())) return false;
    at += bytes;
    for (std::uint64_t r : records) {
      const RecordFields f = unpackRecord(r);
      // Kind 1 has no directions; in kind 2 the payload decoder already holds theta < 32.
      if (f.x >= perAxis[0] || f.y >= perAxis[1] || f.z >= perAxis[2] || f.a || f.c ||
          (!directions && (f.theta || f.phi)))
        return false;
      const std::uint32_t code = spread3(f.x) | (spread3(f.y) << 1) | (spread3(f.z) << 2);
      if (!grid.blocks.empty() && code <= grid.blocks.back()) return false;
      grid.blocks.push_back(code);
      if (directions)
        grid.blockDirections.push_back(static_cast<std::uint16_t>((f.theta << 6) | f.phi));
    }
  }
  grid.blockShift = shift;
  return true;
}

// Reads the shared tables part (docs/qnv-format.md, "Shared tables") from `at`, which it
// advances; false when anything is inconsistent.
bool loadSharedTables(PositionGrid& grid, std::string_view model, std::size_t& at) {
  if (model.size() - at < 4) return false;
  const auto bytes = loadLe<std::uint32_t>(model.data() + at);
  at += 4;
  if (model.size() - at < bytes) return false;
  const auto* begin = reinterpret_cast<const unsigned char*>(model.data() + at);
  BitReader bits(begin, begin + bytes);
  const std::uint32_t sets = bits.gamma();
  if (bits.overrun() || sets > SharedTables::kMaxSets) return false;
  grid.shared.sets.resize(sets);
  for (auto& set : grid.shared.sets)
    for (int k = 0; k < kFields; ++k)
      if (!readTable(bits, set[static_cast<std::size_t>(k)], kAlphabetBits[k]) || bits.overrun())
        return false;
  at += bytes;
  return (bits.bitsConsumed() + 7) / 8 == bytes;
}

// Reads a model: its kind byte, then the parts it names; false when anything is
// inconsistent.
bool loadModel(PositionGrid& grid, std::string_view model) {
  if (model.empty()) return false;
  const auto kind = loadLe<std::uint8_t>(model.data());
  const int blocks = kind & ~kModelSharedTables;  // 0 none, 1 occupied, 2 with directions
  if (blocks > kModelDirections || kind == 0) return false;
  std::size_t at = 1;
  if (blocks && !loadOccupancy(grid, model, at, blocks == kModelDirections)) return false;
  if ((kind & kModelSharedTables) && !loadSharedTables(grid, model, at)) return false;
  return at == model.size();
}

// The model bytes for these sorted, distinct block codes at `shift`: kind 2 when
// `directions` (theta << 6 | phi per block) is given, else kind 1.
std::string encodeModel(const std::vector<std::uint32_t>& blocks, int shift,
                        const std::vector<std::uint16_t>* directions = nullptr) {
  std::string out;
  appendLe<std::uint8_t>(out, directions ? kModelDirections : kModelOccupancy);
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(shift));
  appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(blocks.size()));
  std::vector<std::uint64_t> records;
  std::string payload;
  const PositionGrid cells;
  for (std::size_t first = 0; first < blocks.size(); first += kChunkRecords) {
    records.clear();
    for (std::size_t i = first; i < std::min(blocks.size(), first + kChunkRecords); ++i) {
      RecordFields f{};
      f.x = static_cast<std::uint16_t>(compact3(blocks[i]));
      f.y = static_cast<std::uint16_t>(compact3(blocks[i] >> 1));
      f.z = static_cast<std::uint16_t>(compact3(blocks[i] >> 2));
      if (directions) {
        f.theta = static_cast<std::uint8_t>((*directions)[i] >> 6);
        f.phi = static_cast<std::uint8_t>((*directions)[i] & 63u);
      }
      records.push_back(packRecord(f));
    }
    payload.clear();
    appendEntropyPayload(payload, records, cells);
    appendLe<std::uint16_t>(out, static_cast<std::uint16_t>(payload.size()));
    out += payload;
  }
  return out;
}

}  // namespace

std::int64_t PositionGrid::blockRank(std::uint32_t block) const {
  const auto it = std::lower_bound(blocks.begin(), blocks.end(), block);
  return it != blocks.end() && *it == block ? it - blocks.begin() : -1;
}

PositionGrid PositionGrid::forHeader(const StreamHeader& header) {
  PositionGrid grid;
  for (int a = 0; a < 3; ++a) {
    const std::uint32_t dims = header.kind == StreamKind::volume ? header.volumeDims[a] : 0;
    if (dims >= 2 && dims <= kPositionSteps) {
      grid.active = grid.active || dims < kPositionSteps;
      for (std::uint32_t i = 0; i < dims; ++i)
        grid.cellOf[a].push_back(static_cast<std::uint16_t>(
            std::min<std::uint32_t>(kPositionSteps - 1, i * kPositionSteps / (dims - 1))));
    } else {
      for (std::uint32_t i = 0; i < kPositionSteps; ++i)
        grid.cellOf[a].push_back(static_cast<std::uint16_t>(i));
    }
    grid.cellOrOutside[a] = grid.cellOf[a];
    grid.cellOrOutside[a].resize(kPositionSteps, 0x8000);
    grid.indexOf[a].assign(kPositionSteps, -1);
    for (std::size_t i = 0; i < grid.cellOf[a].size(); ++i)
      grid.indexOf[a][grid.cellOf[a][i]] = static_cast<std::int16_t>(i);
  }
  if (!header.model.empty() && !loadModel(grid, header.model)) {
    grid.modelValid = false;
    grid.shared.sets.clear();
    grid.blocks.clear();
    grid.blockDirections.clear();
    grid.blockShift = 0;
  }
  grid.blockOrigins.reserve(grid.blocks.size());
  for (std::size_t i = 0; i < grid.blocks.size(); ++i) {
    const std::uint32_t block = grid.blocks[i];
    const std::uint64_t direction = i < grid.blockDirections.size() ? grid.blockDirections[i] : 0;
    const std::uint64_t x = compact3(block), y = compact3(block >> 1), z = compact3(block >> 2);
    const std::uint64_t last = (std::uint64_t{1} << grid.blockShift) - 1;
    const bool partial = ((x << grid.blockShift) + last >= grid.axisSize(0)) ||
                         ((y << grid.blockShift) + last >= grid.axisSize(1)) ||
                         ((z << grid.blockShift) + last >= grid.axisSize(2));
    grid.blockOrigins.push_back((std::uint64_t{partial} << 63) | (direction << 32) |
                                (x << (20 + grid.blockShift)) | (y << (10 + grid.blockShift)) |
                                (z << grid.blockShift));
  }
  return grid;
}

std::vector<std::string> streamModelCandidates(const StreamHeader& header,
                                               std::span<const std::uint64_t> records) {
  StreamHeader plain = header;
  plain.model.clear();
  const PositionGrid grid = PositionGrid::forHeader(plain);
  if (records.empty()) return {};
  // Index-space Morton codes of all records with their direction cells, sorted; none when
  // some record is off the grid.
  std::vector<std::pair<std::uint32_t, std::uint16_t>> codes;
  codes.reserve(records.size());
  for (std::uint64_t r : records) {
    const RecordFields f = unpackRecord(r);
    std::array<std::uint32_t, 3> q = {f.x, f.y, f.z};
    if (grid.active) {
      for (int a = 0; a < 3; ++a) {
        const int index = grid.indexOf[a][q[a]];
        if (index < 0) return {};
        q[a] = static_cast<std::uint32_t>(index);
      }
    }
    codes.emplace_back(spread3(q[0]) | (spread3(q[1]) << 1) | (spread3(q[2]) << 2),
                       static_cast<std::uint16_t>((f.theta << 6) | f.phi));
  }
  std::sort(codes.begin(), codes.end());
  const auto occupied = [&](int shift) {
    std::vector<std::uint32_t> blocks;
    for (const auto& c : codes)
      if (blocks.empty() || blocks.back() != c.first >> (3 * shift))
        blocks.push_back(c.first >> (3 * shift));
    return blocks;
  };
  std::string best;
  int bestShift = 0;
  double bestSaving = 0;
  for (int shift = kMinBlockShift; shift <= kMaxBlockShift; ++shift) {
    const auto perAxis = blocksPerAxis(grid, shift);
    const double total = static_cast<double>(perAxis[0]) * perAxis[1] * perAxis[2];
    if (total > static_cast<double>(kMaxBlocks)) continue;
    const std::vector<std::uint32_t> blocks = occupied(shift);
    std::string model = encodeModel(blocks, shift);
    // Positions cost about log2(space / n) bits each: the occupied blocks shrink the space.
    const double saving = static_cast<double>(records.size()) *
                              std::log2(total / static_cast<double>(blocks.size())) -
                          8.0 * static_cast<double>(model.size() + 9);
    if (saving > bestSaving && model.size() <= kMaxModelBytes) {
      bestSaving = saving;
      best = std::move(model);
      bestShift = shift;
    }
  }
  if (best.empty()) return {};
  std::vector<std::string> out;
  out.push_back(std::move(best));
  // Kind 2 at the chosen block size and its neighbours. A block's direction is the cell
  // nearest to its vectors' cells in the L1 sense, axis by axis: the median theta and the
  // circular median phi (measured: 0.4-0.6 bits per vector below the cell of the mean
  // normal on CThead, 0.2 on the bunny).
  for (int shift : {bestShift, bestShift - 1, bestShift + 1}) {
    if (shift < kMinBlockShift || shift > kMaxBlockShift) continue;
    const auto perAxis = blocksPerAxis(grid, shift);
    if (std::uint64_t{perAxis[0]} * perAxis[1] * perAxis[2] > kMaxBlocks) continue;
    std::vector<std::uint32_t> blocks;
    std::vector<std::uint16_t> directions;
    for (std::size_t i = 0; i < codes.size();) {
      const std::uint32_t block = codes[i].first >> (3 * shift);
      std::array<std::uint32_t, kThetaSteps> thetas{};
      std::array<std::uint32_t, kPhiSteps> phis{};
      std::uint32_t members = 0;
      for (; i < codes.size() && codes[i].first >> (3 * shift) == block; ++i, ++members) {
        ++thetas[codes[i].second >> 6];
        ++phis[codes[i].second & 63u];
      }
      std::uint32_t theta = 0;
      for (std::uint32_t below = 0; below + thetas[theta] <= members / 2; ++theta)
        below += thetas[theta];
      std::uint32_t phi = 0;
      std::uint64_t bestCost = ~std::uint64_t{0};
      for (std::uint32_t p = 0; p < kPhiSteps; ++p) {
        if (!phis[p]) continue;
        std::uint64_t cost = 0;
        for (std::uint32_t q = 0; q < kPhiSteps; ++q) {
          const std::uint32_t d = (p - q) & 63u;
          cost += std::uint64_t{phis[q]} * std::min(d, 64 - d);
        }
        if (cost < bestCost) {
          bestCost = cost;
          phi = p;
        }
      }
      blocks.push_back(block);
      directions.push_back(static_cast<std::uint16_t>((theta << 6) | phi));
    }
    std::string model = encodeModel(blocks, shift, &directions);
    if (model.size() <= kMaxModelBytes) out.push_back(std::move(model));
  }
  return out;
}

namespace {

// The shared tables part (docs/qnv-format.md, "Shared tables"): one set of tables per
// group of G consecutive packets, G chosen by the bits it saves against every packet's own
// tables; empty when none saves any.
std::string chooseSharedTables(const StreamHeader& header, std::span<const std::uint64_t> records,
                               const PositionGrid& grid) {
  const std::size_t perPacket = header.packetBytes / 8;
  if (perPacket == 0 || records.empty()) return {};
  using Counts = std::array<std::vector<std::uint32_t>, kFields>;
  std::vector<Counts> counts;
  std::vector<std::size_t> sizes;
  std::vector<double> ownBits;  // per packet and field
  for (std::size_t first = 0; first < records.size(); first += perPacket) {
    const auto packet = records.subspan(first, std::min(perPacket, records.size() - first));
    counts.push_back(packetSymbolCounts(packet, grid));
    sizes.push_back(packet.size());
    for (int k = 0; k < kFields; ++k) {
      double bits = 0;
      planField(counts.back()[static_cast<std::size_t>(k)], packet.size(), kAlphabetBits[k], &bits);
      ownBits.push_back(bits);
    }
  }
  const std::size_t packets = counts.size();
  double bestSaving = 0;
  std::string best;
  for (std::size_t group = 1; group <= packets; group *= 2) {
    const std::size_t sets = (packets + group - 1) / group;
    if (sets > SharedTables::kMaxSets) continue;
    SharedTables shared;
    shared.sets.resize(sets);
    for (std::size_t set = 0; set < sets; ++set)
      for (std::size_t k = 0; k < kFields; ++k) {
        std::vector<std::uint32_t> sum(std::size_t{1} << kAlphabetBits[k], 0);
        std::size_t n = 0;
        for (std::size_t p = set * group; p < std::min(packets, (set + 1) * group); ++p) {
          for (std::size_t s = 0; s < sum.size(); ++s) sum[s] += counts[p][k][s];
          n += sizes[p];
        }
        shared.sets[set][k] = planField(sum, n, kAlphabetBits[k]);
      }
    std::string part;
    BitWriter bits(part);
    bits.gamma(static_cast<std::uint32_t>(sets));
    for (const auto& set : shared.sets)
      for (int k = 0; k < kFields; ++k)
        writeTable(bits, set[static_cast<std::size_t>(k)], kAlphabetBits[k]);
    bits.finish();
    double saving = -8.0 * static_cast<double>(part.size() + 4);
    for (std::size_t p = 0; p < packets; ++p)
      for (std::size_t k = 0; k < kFields; ++k) {
        const double own = ownBits[p * kFields + k];
        const double with = sharedTableBits(shared.sets[p / group][k], counts[p][k], sizes[p],
                                            kAlphabetBits[k], shared.indexBits());
        saving += std::max(0.0, own - with);
      }
    if (saving > bestSaving) {
      bestSaving = saving;
      best.clear();
      appendLe<std::uint32_t>(best, static_cast<std::uint32_t>(part.size()));
      best += part;
    }
  }
  return best;
}

}  // namespace

std::string withSharedTables(const StreamHeader& header, std::span<const std::uint64_t> records,
                             const std::string& model) {
  StreamHeader under = header;
  under.model = model;
  const std::string tables = chooseSharedTables(header, records, PositionGrid::forHeader(under));
  if (tables.empty()) return model;
  std::string out = model.empty() ? std::string(1, '\0') : model;
  out[0] = static_cast<char>(static_cast<unsigned char>(out[0]) | kModelSharedTables);
  out += tables;
  return out.size() <= kMaxModelBytes ? out : model;
}

}  // namespace gs::qnv::detail
