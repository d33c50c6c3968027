#include "entropy_payload.hpp"
#include "entropy_fields.hpp"
#include "morton.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "base/byte_order.hpp"
#include "qnv/record.hpp"
#include "qnv/stream.hpp"
#include "rans.hpp"

namespace gs::qnv::detail {

using base::appendLe;
using base::loadLe;

namespace {

int bitLength(std::uint32_t v) {
  return v ? 32 - __builtin_clz(v) : 0;
}
int gammaBits(std::uint32_t v) {
  return 2 * (bitLength(v) - 1) + 1;
}

// The rANS state each field uses: two interleaved states halve the decoder's chain of
// dependent multiplications.
constexpr std::array<int, kFields> kLane = {0, 1, 0, 1};
constexpr std::size_t kPreambleBytes = 6;  // flags, aMin, aBits, rANS bytes

// Frequencies summing to 2^bits, at least 1 for every symbol seen; empty when there are
// more distinct symbols than slots.
std::vector<std::uint16_t> normalize(const std::vector<std::uint32_t>& counts, std::size_t n,
                                     int bits) {
  const std::uint32_t total = 1u << bits;
  std::size_t distinct = 0;
  for (std::uint32_t c : counts) distinct += c > 0;
  if (distinct > total) return {};
  std::vector<std::uint16_t> f(counts.size(), 0);
  std::int64_t sum = 0;
  for (std::size_t s = 0; s < counts.size(); ++s) {
    if (counts[s] == 0) continue;
    const double exact = static_cast<double>(counts[s]) * total / static_cast<double>(n);
    f[s] = static_cast<std::uint16_t>(std::max(1.0, std::floor(exact + 0.5)));
    sum += f[s];
  }
  while (sum != total) {  // take from or give to the largest frequencies
    const auto largest = static_cast<std::size_t>(std::max_element(f.begin(), f.end()) - f.begin());
    if (sum < total) {
      f[largest] = static_cast<std::uint16_t>(f[largest] + (total - sum));
      sum = total;
    } else {
      const std::int64_t take = std::min<std::int64_t>(sum - total, f[largest] - 1);
      if (take <= 0) return {};  // cannot happen: distinct <= total
      std::int64_t step = std::max<std::int64_t>(1, take / 2);
      f[largest] = static_cast<std::uint16_t>(f[largest] - step);
      sum -= step;
    }
  }
  return f;
}

double tableBits(const std::vector<std::uint16_t>& f) {
  double bits = 4;
  std::uint32_t present = 0, previous = 0;
  bool first = true;
  std::vector<std::uint32_t> freqs;
  for (std::size_t s = 0; s < f.size(); ++s) {
    if (!f[s]) continue;
    bits += gammaBits(static_cast<std::uint32_t>(s) - (first ? 0 : previous + 1) + 1);
    previous = static_cast<std::uint32_t>(s);
    first = false;
    ++present;
    freqs.push_back(f[s]);
  }
  bits += gammaBits(present);
  for (std::size_t i = 0; i + 1 < freqs.size(); ++i) bits += gammaBits(freqs[i]);
  return bits;
}

}  // namespace

FieldCoder planField(const std::vector<std::uint32_t>& counts, std::size_t n, int alphabetBits,
                     double* bitsOut) {
  FieldCoder best;
  if (bitsOut) *bitsOut = 4.0 + alphabetBits;  // constant
  std::size_t distinct = 0;
  for (std::size_t s = 0; s < counts.size(); ++s)
    if (counts[s]) {
      ++distinct;
      best.constant = static_cast<unsigned>(s);
    }
  if (distinct == 1) {
    best.mode = kModeConstant;
    if (bitsOut) *bitsOut = 4.0 + alphabetBits;
    return best;
  }
  double bestBits = 4.0 + static_cast<double>(n) * alphabetBits;  // raw
  for (int bits = 4; bits <= kMaxProbBits; ++bits) {
    std::vector<std::uint16_t> f = normalize(counts, n, bits);
    if (f.empty()) continue;
    double cost = tableBits(f);
    for (std::size_t s = 0; s < counts.size(); ++s)
      if (counts[s]) cost += counts[s] * (bits - std::log2(static_cast<double>(f[s])));
    if (cost < bestBits) {
      bestBits = cost;
      best.mode = bits;
      best.model.probBits = bits;
      best.model.freq = std::move(f);
    }
  }
  if (best.mode != kModeRaw) best.model.build();
  if (bitsOut) *bitsOut = bestBits;
  return best;
}

double sharedTableBits(const FieldCoder& c, const std::vector<std::uint32_t>& counts, std::size_t n,
                       int alphabetBits, int indexBits) {
  constexpr double kNever = 1e300;
  double bits = 4.0 + indexBits;
  if (c.mode == kModeRaw) return bits + static_cast<double>(n) * alphabetBits;
  for (std::size_t s = 0; s < counts.size(); ++s) {
    if (!counts[s]) continue;
    if (c.mode == kModeConstant) {
      if (s != c.constant) return kNever;
      continue;
    }
    if (!c.model.freq[s]) return kNever;
    bits += counts[s] * (c.mode - std::log2(static_cast<double>(c.model.freq[s])));
  }
  return bits;
}

namespace {}  // namespace

void writeTable(BitWriter& bits, const FieldCoder& coder, int alphabetBits) {
  if (coder.sharedSet >= 0) {
    bits.put(kModeShared, 4);
    bits.put(static_cast<std::uint32_t>(coder.sharedSet), coder.sharedIndexBits);
    return;
  }
  bits.put(static_cast<std::uint32_t>(coder.mode), 4);
  if (coder.mode == kModeConstant) {
    bits.put(coder.constant, alphabetBits);
    return;
  }
  if (coder.mode == kModeRaw) return;
  const auto& f = coder.model.freq;
  std::uint32_t present = 0;
  for (std::uint16_t v : f) present += v > 0;
  bits.gamma(present);
  std::uint32_t next = 0, written = 0;
  for (std::size_t s = 0; s < f.size(); ++s) {
    if (!f[s]) continue;
    bits.gamma(static_cast<std::uint32_t>(s) - next + 1);
    next = static_cast<std::uint32_t>(s) + 1;
    if (++written < present) bits.gamma(f[s]);
  }
}

namespace {

// The rest of a table whose 4-bit mode was read.
bool readTableAfterMode(BitReader& bits, FieldCoder& coder, int alphabetBits, int mode) {
  coder.mode = mode;
  if (coder.mode == kModeConstant) {
    coder.constant = bits.get(alphabetBits);
    return !bits.overrun();
  }
  if (coder.mode == kModeRaw) return true;
  if (coder.mode > kMaxProbBits) return false;
  const std::uint32_t alphabet = 1u << alphabetBits, total = 1u << coder.mode;
  const std::uint32_t present = bits.gamma();
  if (present > alphabet || present > total || bits.overrun()) return false;
  coder.model.probBits = coder.mode;
  coder.model.freq.assign(alphabet, 0);
  std::uint32_t next = 0, sum = 0;
  for (std::uint32_t i = 0; i < present; ++i) {
    const std::uint32_t s = next + bits.gamma() - 1;
    if (s >= alphabet || bits.overrun()) return false;
    next = s + 1;
    const std::uint32_t f = i + 1 < present ? bits.gamma() : total - sum;
    if (f == 0 || sum + f > total || bits.overrun()) return false;
    coder.model.freq[s] = static_cast<std::uint16_t>(f);
    sum += f;
  }
  if (sum != total) return false;
  coder.model.build();
  return true;
}

}  // namespace

bool readTable(BitReader& bits, FieldCoder& coder, int alphabetBits) {
  return readTableAfterMode(bits, coder, alphabetBits, static_cast<int>(bits.get(4)));
}

const FieldCoder* readPacketTable(BitReader& bits, FieldCoder& own, int field,
                                  const SharedTables& shared) {
  const int alphabetBits = kAlphabetBits[static_cast<std::size_t>(field)];
  const auto mode = static_cast<int>(bits.get(4));
  if (mode == kModeShared) {
    const std::uint32_t set = bits.get(shared.indexBits());
    if (bits.overrun() || set >= shared.sets.size()) return nullptr;
    return &shared.sets[set][static_cast<std::size_t>(field)];
  }
  return readTableAfterMode(bits, own, alphabetBits, mode) ? &own : nullptr;
}

namespace {

// A packet sorted and turned into symbols, before its tables are chosen.
struct PacketPlan {
  std::vector<std::pair<std::uint32_t, std::uint64_t>> sorted;  // coded Morton code, record
  std::vector<std::array<std::uint32_t, kFields>> symbols;
  std::array<std::vector<std::uint32_t>, kFields> counts;
  std::uint32_t aMin = 0;
  int aBits = 0;
  int aShift = 0;
  std::uint8_t flags = 0;
};

PacketPlan planPacket(std::span<const std::uint64_t> records, const PositionGrid& grid) {
  const std::size_t n = records.size();
  // Grid mode when every position of the packet lies on the grid.
  bool onGrid = grid.active;
  for (std::size_t i = 0; i < n && onGrid; ++i) {
    const RecordFields f = unpackRecord(records[i]);
    onGrid = grid.indexOf[0][f.x] >= 0 && grid.indexOf[1][f.y] >= 0 && grid.indexOf[2][f.z] >= 0;
  }
  PacketPlan plan;
  auto& sorted = plan.sorted;
  sorted.reserve(n);
  std::uint32_t aMin = kMagnitudeSteps, aMax = 0;
  for (std::uint64_t r : records) {
    const RecordFields f = unpackRecord(r);
    std::uint32_t x = f.x, y = f.y, z = f.z;
    if (onGrid) {
      x = static_cast<std::uint32_t>(grid.indexOf[0][x]);
      y = static_cast<std::uint32_t>(grid.indexOf[1][y]);
      z = static_cast<std::uint32_t>(grid.indexOf[2][z]);
    }
    sorted.emplace_back(spread3(x) | (spread3(y) << 1) | (spread3(z) << 2), r);
    aMin = std::min<std::uint32_t>(aMin, f.a);
    aMax = std::max<std::uint32_t>(aMax, f.a);
  }
  // Block mode: the model's blocks live in the grid's index space (or the cells' when
  // there is no grid); every record's block must be one of them.
  bool useBlocks = grid.blockShift > 0 && onGrid == grid.active;
  const int blockBits = 3 * grid.blockShift;
  for (std::size_t i = 0; i < n && useBlocks; ++i) {
    const std::int64_t rank = grid.blockRank(sorted[i].first >> blockBits);
    useBlocks = rank >= 0;
    if (useBlocks)
      sorted[i].first = (static_cast<std::uint32_t>(rank) << blockBits) |
                        (sorted[i].first & ((1u << blockBits) - 1));
  }
  if (!useBlocks && grid.blockShift > 0)  // undo the ranks already taken
    for (std::size_t i = 0; i < n; ++i) {
      const RecordFields f = unpackRecord(sorted[i].second);
      std::uint32_t x = f.x, y = f.y, z = f.z;
      if (onGrid) {
        x = static_cast<std::uint32_t>(grid.indexOf[0][x]);
        y = static_cast<std::uint32_t>(grid.indexOf[1][y]);
        z = static_cast<std::uint32_t>(grid.indexOf[2][z]);
      }
      sorted[i].first = spread3(x) | (spread3(y) << 1) | (spread3(z) << 2);
    }
  std::sort(sorted.begin(), sorted.end());
  // The offsets A - aMin, shifted right by the trailing zero bits they all share (magnitude
  // codes rounded to fewer bits: ghostspace encode --magnitude-bits).
  std::uint32_t offsetBitsUsed = 0;
  for (const auto& s : sorted) offsetBitsUsed |= magnitudeCode(s.second) - aMin;
  const int aShift = offsetBitsUsed == 0 ? 0 : std::countr_zero(offsetBitsUsed);
  const int aBits = bitLength((aMax - aMin) >> aShift);

  // Symbols per record: gap token, theta and phi deltas from the previous record, colour.
  auto& symbols = plan.symbols;
  symbols.resize(n);
  auto& counts = plan.counts;
  for (int k = 0; k < kFields; ++k) counts[k].assign(std::size_t{1} << kAlphabetBits[k], 0);
  std::uint32_t previousCode = 0, previousTheta = 0, previousPhi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const RecordFields f = unpackRecord(sorted[i].second);
    auto& s = symbols[i];
    s[kGap] = static_cast<std::uint32_t>(bitLength(sorted[i].first - previousCode));
    s[kTheta] = (f.theta - previousTheta) & 63u;
    s[kPhi] = (f.phi - previousPhi) & 63u;
    s[kColor] = f.c;
    previousCode = sorted[i].first;
    previousTheta = f.theta;
    previousPhi = f.phi;
    for (int k = 0; k < kFields; ++k) ++counts[k][s[k]];
  }
  // With a kind-2 model, theta and phi may instead be coded from the record's block
  // direction: whichever costs fewer bits with the packet's own tables.
  bool useDirections = false;
  if (useBlocks && !grid.blockDirections.empty()) {
    std::array<double, kFields> planned{};
    for (int k : {kTheta, kPhi}) planField(counts[k], n, kAlphabetBits[k], &planned[k]);
    std::vector<std::array<std::uint32_t, 2>> alternative(n);
    std::array<std::vector<std::uint32_t>, 2> altCounts;
    for (auto& c : altCounts) c.assign(64, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const RecordFields f = unpackRecord(sorted[i].second);
      const std::uint32_t d = grid.blockDirections[sorted[i].first >> blockBits];
      alternative[i] = {(f.theta - (d >> 6)) & 63u, (f.phi - d) & 63u};
      ++altCounts[0][alternative[i][0]];
      ++altCounts[1][alternative[i][1]];
    }
    double thetaBits = 0, phiBits = 0;
    planField(altCounts[0], n, kAlphabetBits[kTheta], &thetaBits);
    planField(altCounts[1], n, kAlphabetBits[kPhi], &phiBits);
    if (thetaBits + phiBits < planned[kTheta] + planned[kPhi]) {
      useDirections = true;
      counts[kTheta] = std::move(altCounts[0]);
      counts[kPhi] = std::move(altCounts[1]);
      for (std::size_t i = 0; i < n; ++i) {
        symbols[i][kTheta] = alternative[i][0];
        symbols[i][kPhi] = alternative[i][1];
      }
    }
  }
  plan.aMin = aMin;
  plan.aBits = aBits;
  plan.aShift = aShift;
  plan.flags = static_cast<std::uint8_t>((onGrid ? kFlagGrid : 0) | (useBlocks ? kFlagBlocks : 0) |
                                         (useDirections ? kFlagBlockDirections : 0));
  return plan;
}

}  // namespace

std::array<std::vector<std::uint32_t>, kFields> packetSymbolCounts(
    std::span<const std::uint64_t> records, const PositionGrid& grid) {
  return planPacket(records, grid).counts;
}

void appendEntropyPayload(std::string& out, std::span<const std::uint64_t> records,
                          const PositionGrid& grid, EntropyFieldBits* report, bool fast) {
  const std::size_t n = records.size();
  PacketPlan plan = planPacket(records, grid);
  const auto& sorted = plan.sorted;
  const auto& symbols = plan.symbols;
  const auto& counts = plan.counts;
  const std::uint32_t aMin = plan.aMin;
  const int aBits = plan.aBits;
  const int aShift = plan.aShift;
  const std::uint8_t flags = plan.flags;
  const bool useBlocks = flags & kFlagBlocks;
  // Each field: its own table, or a shared one of the stream model where that is smaller.
  std::array<FieldCoder, kFields> coders;
  const int indexBits = grid.shared.indexBits();
  for (int k = 0; k < kFields; ++k) {
    double bits = 0;
    coders[k] = planField(counts[k], n, kAlphabetBits[k], &bits);
    for (std::size_t set = 0; set < grid.shared.sets.size(); ++set) {
      const FieldCoder& shared = grid.shared.sets[set][static_cast<std::size_t>(k)];
      const double with = sharedTableBits(shared, counts[k], n, kAlphabetBits[k], indexBits);
      if (with < bits) {
        bits = with;
        coders[k] = shared;
        coders[k].sharedSet = static_cast<int>(set);
        coders[k].sharedIndexBits = indexBits;
      }
    }
  }

  std::string payload;
  if (fast) {
    appendFastLayout(payload, PacketSymbols{sorted, symbols, &coders, aMin, aBits, aShift, flags});
  } else {
    std::string bitBytes;
    BitWriter bits(bitBytes);
    for (int k = 0; k < kFields; ++k) writeTable(bits, coders[k], kAlphabetBits[k]);
    std::uint32_t previousCode = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto& s = symbols[i];
      const std::uint32_t gap = sorted[i].first - previousCode;
      previousCode = sorted[i].first;
      for (int k = 0; k < kFields; ++k) {
        if (coders[k].mode == kModeRaw) bits.put(s[k], kAlphabetBits[k]);
        if (k == kGap && s[kGap] >= 2) bits.put(gap, static_cast<int>(s[kGap]) - 1);
        if (k == kPhi) bits.put((magnitudeCode(sorted[i].second) - aMin) >> aShift, aBits);
      }
    }
    bits.finish();
    RansEncoder rans;
    for (std::size_t i = n; i-- > 0;)
      for (int k = kFields; k-- > 0;)
        if (coders[k].mode != kModeRaw && coders[k].mode != kModeConstant)
          rans.put(coders[k].model, symbols[i][k], kLane[k]);
    std::string ransBytes;
    rans.finish(ransBytes);
    appendLe<std::uint8_t>(payload, flags);
    appendLe<std::uint16_t>(payload, static_cast<std::uint16_t>(aMin));
    appendLe<std::uint8_t>(payload, static_cast<std::uint8_t>(aBits | (aShift << 4)));
    appendLe<std::uint16_t>(payload, static_cast<std::uint16_t>(ransBytes.size()));
    payload += ransBytes;
    payload += bitBytes;
  }

  if (report) {
    std::array<double, kFields> fieldBits{};
    for (int k = 0; k < kFields; ++k) {
      const FieldCoder& c = coders[k];
      if (c.mode == kModeRaw) fieldBits[k] = static_cast<double>(n) * kAlphabetBits[k];
      if (c.mode == kModeRaw || c.mode == kModeConstant) continue;
      for (std::size_t s = 0; s < counts[k].size(); ++s)
        if (counts[k][s])
          fieldBits[k] += counts[k][s] * (c.mode - std::log2(static_cast<double>(c.model.freq[s])));
    }
    double gapExtra = 0;
    for (const auto& s : symbols) gapExtra += s[kGap] >= 2 ? s[kGap] - 1 : 0;
    report->position += fieldBits[kGap] + gapExtra;
    report->direction += fieldBits[kTheta] + fieldBits[kPhi];
    report->magnitude += static_cast<double>(n) * aBits;
    report->color += fieldBits[kColor];
    double tables = 0;
    {
      std::string scratch;
      BitWriter w(scratch);
      for (int k = 0; k < kFields; ++k) writeTable(w, coders[k], kAlphabetBits[k]);
      w.finish();
      tables = 8.0 * static_cast<double>(scratch.size());
    }
    report->tables += tables;
    const double total = 8.0 * static_cast<double>(payload.size());
    report->framing += total - (fieldBits[kGap] + gapExtra + fieldBits[kTheta] + fieldBits[kPhi] +
                                static_cast<double>(n) * aBits + fieldBits[kColor] + tables);
  }
  if (report && useBlocks) ++report->blockPackets;
  out += payload;
}

bool decodeEntropyPayload(std::string_view payload, std::size_t count, const PositionGrid& grid,
                          std::uint64_t* out) {
  if (payload.size() < kPreambleBytes || count == 0) return false;
  const auto flags = loadLe<std::uint8_t>(payload.data());
  if (flags & kFlagFast) return decodeFastLayout(payload, count, grid, out);
  const auto aMin = loadLe<std::uint16_t>(payload.data() + 1);
  const int aBits = loadLe<std::uint8_t>(payload.data() + 3) & 15;
  const int aShift = loadLe<std::uint8_t>(payload.data() + 3) >> 4;
  const auto ransSize = loadLe<std::uint16_t>(payload.data() + 4);
  const bool useBlocks = flags & kFlagBlocks;
  const bool useDirections = flags & kFlagBlockDirections;
  if (flags > (kFlagGrid | kFlagBlocks | kFlagBlockDirections) || aMin >= kMagnitudeSteps ||
      !validMagnitudeWidth(aBits, aShift) || ransSize > payload.size() - kPreambleBytes ||
      ((flags & kFlagGrid) && !grid.active) ||
      (useBlocks && (grid.blockShift == 0 || ((flags & kFlagGrid) != 0) != grid.active)) ||
      (useDirections && (!useBlocks || grid.blockDirections.size() != grid.blocks.size())))
    return false;
  const auto* begin = reinterpret_cast<const unsigned char*>(payload.data());
  const unsigned char* ransBegin = begin + kPreambleBytes;
  const unsigned char* bitsBegin = ransBegin + ransSize;
  const unsigned char* end = begin + payload.size();
  BitReader bits(bitsBegin, end);
  std::array<FieldCoder, kFields> own;
  std::array<const FieldCoder*, kFields> coders{};
  for (int k = 0; k < kFields; ++k)
    if (!(coders[k] = readPacketTable(bits, own[k], k, grid.shared))) return false;
  RansDecoder rans(ransBegin, bitsBegin);
  const bool useGrid = flags & kFlagGrid;
  const std::array<std::size_t, 3> limit = {useGrid ? grid.cellOf[0].size() : kPositionSteps,
                                            useGrid ? grid.cellOf[1].size() : kPositionSteps,
                                            useGrid ? grid.cellOf[2].size() : kPositionSteps};
  auto field = [&](int k) -> std::uint32_t {
    const FieldCoder& c = *coders[k];
    if (c.mode == kModeConstant) return c.constant;
    if (c.mode == kModeRaw) return bits.get(kAlphabetBits[k]);
    return rans.get(c.model, kLane[k]);
  };
  // Range errors are gathered in `bad` and checked once at the end; indices are clamped
  // so that nothing is read out of bounds meanwhile.
  const int blockBits = useBlocks ? 3 * grid.blockShift : 0;
  const std::uint64_t codeLimit =
      useBlocks ? std::uint64_t{grid.blocks.size()} << blockBits : std::uint64_t{1} << 30;
  const std::uint32_t lowMask = (1u << blockBits) - 1;
  // One loop per position mode, so that the common ones carry no dead branches.
  const auto records = [&]<bool kBlocks, bool kGrid, bool kDirections>() {
    std::uint64_t code = 0;
    std::uint32_t theta = 0, phi = 0;
    bool bad = false;
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint32_t token = field(kGap);  // 0..31
      const std::uint32_t extra = bits.get(static_cast<int>(std::max(token, 1u)) - 1);
      const std::uint32_t gap = token < 2 ? token : ((1u << (token - 1)) | extra);
      code += gap;
      bad |= code >= codeLimit;
      const auto m = static_cast<std::uint32_t>(code);
      std::uint32_t xyz = 0, d = 0;  // X << 20 | Y << 10 | Z; the block's direction
      if constexpr (kBlocks) {       // the block (by rank), then the offset inside it
        const std::uint64_t origin =
            grid.blockOrigins[std::min<std::size_t>(code >> blockBits, grid.blocks.size() - 1)];
        xyz = static_cast<std::uint32_t>(origin) + mortonToXyz(m & lowMask);
        d = static_cast<std::uint16_t>(origin >> 32);
      } else {
        xyz = mortonToXyz(m);
      }
      if constexpr (kDirections) {  // from the block's direction
        theta = ((d >> 6) + field(kTheta)) & 63u;
        phi = (d + field(kPhi)) & 63u;
      } else {
        theta = (theta + field(kTheta)) & 63u;
        phi = (phi + field(kPhi)) & 63u;
      }
      const std::uint32_t a = aMin + (bits.get(aBits) << aShift);
      const std::uint32_t c = field(kColor);
      std::uint32_t x = xyz >> 20, y = (xyz >> 10) & 1023u, z = xyz & 1023u;
      bad |= theta >= kThetaSteps || a >= kMagnitudeSteps || x >= limit[0] || y >= limit[1] ||
             z >= limit[2];
      if constexpr (kGrid) {
        x = grid.cellOf[0][std::min<std::size_t>(x, limit[0] - 1)];
        y = grid.cellOf[1][std::min<std::size_t>(y, limit[1] - 1)];
        z = grid.cellOf[2][std::min<std::size_t>(z, limit[2] - 1)];
      }
      out[i] = (std::uint64_t{x} << 54) | (std::uint64_t{y} << 44) | (std::uint64_t{z} << 34) |
               (std::uint64_t{theta} << 29) | (std::uint64_t{phi} << 23) | (std::uint64_t{a} << 8) |
               c;
    }
    return !bad;
  };
  const bool good = useDirections ? (useGrid ? records.template operator()<true, true, true>()
                                             : records.template operator()<true, false, true>())
                    : useBlocks   ? (useGrid ? records.template operator()<true, true, false>()
                                             : records.template operator()<true, false, false>())
                                  : (useGrid ? records.template operator()<false, true, false>()
                                             : records.template operator()<false, false, false>());
  const std::size_t bitBytes = static_cast<std::size_t>(end - bitsBegin);
  return good && !bits.overrun() && (bits.bitsConsumed() + 7) / 8 == bitBytes &&
         rans.finishedCleanly();
}

}  // namespace gs::qnv::detail
