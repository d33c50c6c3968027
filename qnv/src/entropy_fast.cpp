// The fast layout of the entropy packet encoding (flag bit 2; docs/qnv-format.md, "Fast
// layout"). The symbols and tables are those of the original layout; only where the bits
// lie changes, so that a decoder can work on many records at once: each field is a
// separate run of symbols (structure of arrays), the rANS-coded runs share up to 16
// interleaved states, and the gap extra bits and magnitude offsets lie in their own bit
// sections. The decoder makes one pass per field, then one pass that rebuilds records.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "base/byte_order.hpp"
#include "entropy_fields.hpp"
#include "entropy_payload.hpp"
#include "morton.hpp"
#include "qnv/decoder.hpp"
#include "qnv/record.hpp"

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace gs::qnv::detail {

using base::appendLe;

namespace {

constexpr std::size_t kFastPreambleBytes = 9;  // flags, aMin, aBits, lanes, R, G
constexpr int kMaxLanesLog2 = 4;               // at most 16 states
constexpr std::size_t kMaxRecords = 8191;      // a packet's most (65528 / 8)

constexpr int kStateBits = 31;  // bits a state carries (flag bit 4)

// Lanes by packet size, for `carryBits` magnitude offset bits the states may carry. A
// state costs 4 bytes, of which about 8 bits are overhead when it carries 31 raw bits and
// about 24 when it carries none: with bits to carry, lanes double while every lane keeps
// 20 records or more and all lanes can carry; without, small packets get few.
int lanesLog2For(std::size_t n, std::uint64_t carryBits) {
  if (carryBits == 0) return n >= 1024 ? 4 : n >= 256 ? 3 : n >= 64 ? 2 : n >= 16 ? 1 : 0;
  int k = 0;
  while (k < kMaxLanesLog2 && n >= (std::size_t{40} << k) &&
         carryBits >= std::uint64_t{kStateBits} << (k + 1))
    ++k;
  return k;
}

// Bits lane l carries when a packet's states carry `carried` bits in all: 31 each, lane 0
// first.
inline int laneCarry(std::uint64_t carried, std::size_t l) {
  const std::uint64_t before = std::uint64_t{kStateBits} * l;
  return carried <= before
             ? 0
             : static_cast<int>(std::min<std::uint64_t>(kStateBits, carried - before));
}

// A little-endian load from a byte pointer.
template <typename T>
inline T loadLe(const unsigned char* p) {
  return base::loadLe<T>(reinterpret_cast<const char*>(p));
}

// The 64 bits from bit `pos` of [base, base + size), LSB first; zeros past the end.
inline std::uint64_t peekBits(const unsigned char* base, std::size_t size, std::uint64_t pos) {
  const std::size_t byte = static_cast<std::size_t>(pos >> 3);
  std::uint64_t w = 0;
  if (byte + 8 <= size) {
    w = loadLe<std::uint64_t>(base + byte);
  } else {
    for (std::size_t i = 0; byte + i < size && i < 8; ++i)
      w |= std::uint64_t{base[byte + i]} << (8 * i);
  }
  return w >> (pos & 7);
}

using RunDecoder = void (*)(const RansModel&, std::uint32_t*, const unsigned char*&,
                            const unsigned char*, std::uint8_t*, std::size_t, bool&);

// rANS over one run of n symbols, symbol j on lane j mod L, states carried in x.
template <int L>
void decodeRun(const RansModel& model, std::uint32_t* states, const unsigned char*& where,
               const unsigned char* end, std::uint8_t* sym, std::size_t n, bool& overrun) {
  // Local copies: the byte stores to sym may alias anything reached through a pointer.
  std::uint32_t x[L];
  std::memcpy(x, states, sizeof x);
  const unsigned char* p = where;
  const std::uint32_t* slots = model.slots.data();
  const int shift = model.probBits;
  const std::uint32_t mask = (1u << shift) - 1;
  std::size_t j = 0;
  // Whole groups of L symbols while the words they may read are surely there: first every
  // lane's step (independent of each other), then the renormalizations in lane order.
  for (; j + L <= n && end - p >= 2 * L; j += L) {
    std::uint32_t xx[L];
    std::uint8_t out[L];
    for (int l = 0; l < L; ++l) {
      const std::uint32_t e = slots[x[l] & mask];
      xx[l] = ((e >> 20) + 1) * (x[l] >> shift) + ((e >> 8) & 0xfffu);
      out[l] = static_cast<std::uint8_t>(e);
    }
    for (int l = 0; l < L; ++l) {
      // Arithmetic rather than a select, which compilers turn into a branch that the
      // coin-flip renormalizations mispredict.
      const auto need = static_cast<std::uint32_t>(xx[l] < kRansLow);
      const std::uint32_t word = loadLe<std::uint16_t>(p);
      x[l] = (xx[l] << (need << 4)) | (word & (0u - need));
      p += need << 1;
    }
    std::memcpy(sym + j, out, L);
  }
  for (; j < n; ++j) {  // the rest one at a time, bounds-checked
    std::uint32_t& s = x[j & (L - 1)];
    const std::uint32_t e = slots[s & mask];
    s = ((e >> 20) + 1) * (s >> shift) + ((e >> 8) & 0xfffu);
    sym[j] = static_cast<std::uint8_t>(e);
    if (s < kRansLow) {
      if (end - p < 2) {
        overrun = true;
        s <<= 16;
      } else {
        s = (s << 16) | loadLe<std::uint16_t>(p);
        p += 2;
      }
    }
  }
  std::memcpy(states, x, sizeof x);
  where = p;
}

#if defined(__x86_64__)
// For each mask of lanes that renormalize, the word each lane takes: lane i takes word
// popcount(mask & (2^i - 1)) of the next eight.
struct WordPermutes {
  alignas(32) std::array<std::array<std::uint32_t, 8>, 256> lane{};
  constexpr WordPermutes() {
    for (std::uint32_t m = 0; m < 256; ++m) {
      std::uint32_t k = 0;
      for (std::uint32_t i = 0; i < 8; ++i) {
        lane[m][i] = k & 7u;
        k += (m >> i) & 1u;
      }
    }
  }
};
constexpr WordPermutes kWordPermutes;

#define GS_AVX2 __attribute__((target("avx2,popcnt"), always_inline)) inline

// One rANS step of eight states; returns the symbols (one per 32-bit lane).
GS_AVX2 __m256i avx2Step(__m256i& x, const int* slots, __m256i mask, __m128i shift) {
  const __m256i e = _mm256_i32gather_epi32(slots, _mm256_and_si256(x, mask), 4);
  const __m256i f = _mm256_add_epi32(_mm256_srli_epi32(e, 20), _mm256_set1_epi32(1));
  const __m256i offset = _mm256_and_si256(_mm256_srli_epi32(e, 8), _mm256_set1_epi32(0xfff));
  x = _mm256_add_epi32(_mm256_mullo_epi32(f, _mm256_srl_epi32(x, shift)), offset);
  return _mm256_and_si256(e, _mm256_set1_epi32(0xff));
}

// Renormalizes eight states from the words at p, in lane order; advances p.
GS_AVX2 void avx2Renormalize(__m256i& x, const unsigned char*& p) {
  const __m256i need = _mm256_cmpeq_epi32(_mm256_srli_epi32(x, 16), _mm256_setzero_si256());
  const auto bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(need)));
  const __m256i words = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
  const __m256i perm =
      _mm256_load_si256(reinterpret_cast<const __m256i*>(kWordPermutes.lane[bits].data()));
  const __m256i shifted =
      _mm256_or_si256(_mm256_slli_epi32(x, 16), _mm256_permutevar8x32_epi32(words, perm));
  x = _mm256_blendv_epi8(x, shifted, need);
  p += 2 * static_cast<unsigned>(__builtin_popcount(bits));
}

// Stores the 16 symbols of lanes a0..7 then b0..7 as bytes: packed to 16-bit (a0-3 b0-3
// a4-7 b4-7), then to bytes.
GS_AVX2 void storeSymbols16(std::uint8_t* out, __m256i sa, __m256i sb) {
  const __m256i s16 = _mm256_permute4x64_epi64(_mm256_packus_epi32(sa, sb), 0xd8);
  const __m256i s8 = _mm256_packus_epi16(s16, s16);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                   _mm256_castsi256_si128(_mm256_permute4x64_epi64(s8, 0x08)));
}

// The body of decodeRun16Avx2 and decodeRun16Avx512, which differ only in RENORMALIZE: two
// vectors of eight states, the same symbols and words in the same order as decodeRun<16>
// (lanes 0..7 renormalize before 8..15), the rest by decodeRun<16> itself (j is a multiple
// of 16, so lanes line up). A macro, as each function needs its own target attributes,
// which a template's instances cannot have (nor an always_inline callee more than its
// caller's).
#define GS_DECODE_RUN16(RENORMALIZE)                                             \
  const auto* slots = reinterpret_cast<const int*>(model.slots.data());          \
  const __m128i shift = _mm_cvtsi32_si128(model.probBits);                       \
  const __m256i mask = _mm256_set1_epi32((1 << model.probBits) - 1);             \
  __m256i xa = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(states));     \
  __m256i xb = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(states + 8)); \
  const unsigned char* p = where;                                                \
  std::size_t j = 0;                                                             \
  for (; j + 16 <= n && end - p >= 32; j += 16) {                                \
    const __m256i sa = avx2Step(xa, slots, mask, shift);                         \
    const __m256i sb = avx2Step(xb, slots, mask, shift);                         \
    RENORMALIZE(xa, p);                                                          \
    RENORMALIZE(xb, p);                                                          \
    storeSymbols16(sym + j, sa, sb);                                             \
  }                                                                              \
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(states), xa);                   \
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(states + 8), xb);               \
  where = p;                                                                     \
  decodeRun<16>(model, states, where, end, sym + j, n - j, overrun)

// decodeRun<16> with AVX2.
__attribute__((target("avx2,popcnt"))) void decodeRun16Avx2(
    const RansModel& model, std::uint32_t* states, const unsigned char*& where,
    const unsigned char* end, std::uint8_t* sym, std::size_t n, bool& overrun) {
  GS_DECODE_RUN16(avx2Renormalize);
}

#define GS_AVX512 __attribute__((target("avx2,avx512f,avx512vl,popcnt"), always_inline)) inline

// avx2Renormalize with AVX-512VL: the words expanded into the lanes that take them
// (vpexpandd), without the permutation table's load on the states' dependency chain.
GS_AVX512 void avx512Renormalize(__m256i& x, const unsigned char*& p) {
  const __mmask8 need = _mm256_cmplt_epu32_mask(x, _mm256_set1_epi32(static_cast<int>(kRansLow)));
  const __m256i words = _mm256_cvtepu16_epi32(_mm_loadu_si128(reinterpret_cast<const __m128i*>(p)));
  x = _mm256_mask_or_epi32(x, need, _mm256_slli_epi32(x, 16),
                           _mm256_maskz_expand_epi32(need, words));
  p += 2 * static_cast<unsigned>(__builtin_popcount(need));
}

// decodeRun<16> with AVX-512VL: the same symbols, words and states.
__attribute__((target("avx2,avx512f,avx512vl,popcnt"))) void decodeRun16Avx512(
    const RansModel& model, std::uint32_t* states, const unsigned char*& where,
    const unsigned char* end, std::uint8_t* sym, std::size_t n, bool& overrun) {
  GS_DECODE_RUN16(avx512Renormalize);
}
#undef GS_DECODE_RUN16

// The 16-lane run decoder for this CPU: AVX-512VL, else AVX2, else none (nullptr: the
// scalar one). GS_QNV_NO_AVX512 and GS_QNV_NO_AVX2 turn them off, to measure the others.
RunDecoder simdRun16() {
  static const RunDecoder run = []() -> RunDecoder {
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("popcnt") ||
        std::getenv("GS_QNV_NO_AVX2") != nullptr)
      return nullptr;
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        std::getenv("GS_QNV_NO_AVX512") == nullptr)
      return decodeRun16Avx512;
    return decodeRun16Avx2;
  }();
  return run;
}
#endif

constexpr RunDecoder kRunDecoders[kMaxLanesLog2 + 1] = {decodeRun<1>, decodeRun<2>, decodeRun<4>,
                                                        decodeRun<8>, decodeRun<16>};

// The gap of a token t: t for t < 2, else 2^(t-1) plus t - 1 extra bits.
struct GapTables {
  std::array<std::uint32_t, 32> base{}, width{}, mask{};
  constexpr GapTables() {
    for (std::uint32_t t = 0; t < 32; ++t) {
      base[t] = t < 2 ? t : 1u << (t - 1);
      width[t] = t < 2 ? 0 : t - 1;
      mask[t] = (1u << width[t]) - 1;
    }
  }
};
constexpr GapTables kGapTables;

}  // namespace

void appendFastLayout(std::string& out, const PacketSymbols& packet) {
  const std::size_t n = packet.sorted.size();
  const auto& coders = *packet.coders;
  // The magnitude offsets, aBits each: the first `carried` bits go into the rANS states'
  // start values (flag bit 4), the rest into the bit part.
  std::string offsetBytes;
  {
    BitWriter offsets(offsetBytes);
    for (std::size_t i = 0; i < n; ++i)
      offsets.put((magnitudeCode(packet.sorted[i].second) - packet.aMin) >> packet.aShift,
                  packet.aBits);
    offsets.finish();
  }
  const std::uint64_t offsetBits = std::uint64_t{n} * static_cast<std::uint64_t>(packet.aBits);
  const int lanesLog2 = lanesLog2For(n, offsetBits);
  const std::size_t laneMask = (std::size_t{1} << lanesLog2) - 1;
  const std::uint64_t carried = std::min<std::uint64_t>(offsetBits, kStateBits * (laneMask + 1));
  const auto* offsetData = reinterpret_cast<const unsigned char*>(offsetBytes.data());
  // `width` (<= 32) offset bits from bit b.
  const auto offsetBitsAt = [&](std::uint64_t b, std::uint64_t width) {
    return static_cast<std::uint32_t>(peekBits(offsetData, offsetBytes.size(), b) &
                                      ((std::uint64_t{1} << width) - 1));
  };

  // rANS: the coded fields in order, each a run of n symbols, symbol j on lane j mod L;
  // encoded back to front, so the words come out in reverse reading order. A state that
  // carries c bits starts at 2^31 plus those bits (the first one lowest), else at 2^16.
  std::array<std::uint32_t, 16> x;
  x.fill(kRansLow);
  for (std::size_t l = 0; l <= laneMask; ++l) {
    const int c = laneCarry(carried, l);
    if (c > 0) x[l] = 0x80000000u | offsetBitsAt(kStateBits * l, static_cast<std::uint64_t>(c));
  }
  std::vector<std::uint16_t> words;
  for (int k = kFields; k-- > 0;) {
    if (!coders[k].coded()) continue;
    const RansModel& m = coders[k].model;
    for (std::size_t j = n; j-- > 0;) {
      std::uint32_t& s = x[j & laneMask];
      const std::uint32_t symbol = packet.symbols[j][static_cast<std::size_t>(k)];
      const std::uint32_t f = m.freq[symbol];
      if (s >= std::uint64_t{(kRansLow >> m.probBits) << 16} * f) {
        words.push_back(static_cast<std::uint16_t>(s));
        s >>= 16;
      }
      s = ((s / f) << m.probBits) + (s % f) + m.start[symbol];
    }
  }
  std::string rans;
  for (std::size_t l = 0; l <= laneMask; ++l) appendLe<std::uint32_t>(rans, x[l]);
  for (auto w = words.rbegin(); w != words.rend(); ++w) appendLe<std::uint16_t>(rans, *w);

  std::string gapBits;
  BitWriter gaps(gapBits);
  std::uint32_t previous = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t code = packet.sorted[i].first;
    const int t = static_cast<int>(packet.symbols[i][kGap]);
    if (t >= 2) gaps.put(code - previous, t - 1);
    previous = code;
  }
  gaps.finish();

  std::string bitPart;
  BitWriter bits(bitPart);
  for (int k = 0; k < kFields; ++k) writeTable(bits, coders[k], kAlphabetBits[k]);
  for (int k = 0; k < kFields; ++k)
    if (coders[k].mode == kModeRaw)
      for (std::size_t i = 0; i < n; ++i)
        bits.put(packet.symbols[i][static_cast<std::size_t>(k)], kAlphabetBits[k]);
  for (std::uint64_t b = carried; b < offsetBits; b += 32) {
    const std::uint64_t width = std::min<std::uint64_t>(32, offsetBits - b);
    bits.put(offsetBitsAt(b, width), static_cast<int>(width));
  }
  bits.finish();

  const std::uint8_t carryFlag = carried > 0 ? kFlagStateBits : 0;
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(packet.flags | kFlagFast | carryFlag));
  appendLe<std::uint16_t>(out, static_cast<std::uint16_t>(packet.aMin));
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(packet.aBits | (packet.aShift << 4)));
  appendLe<std::uint8_t>(out, static_cast<std::uint8_t>(lanesLog2));
  // A part over 65535 bytes makes the payload larger than the plain records, and the
  // writer then falls back to plain for this packet.
  appendLe<std::uint16_t>(out,
                          static_cast<std::uint16_t>(std::min<std::size_t>(rans.size(), 65535)));
  appendLe<std::uint16_t>(out,
                          static_cast<std::uint16_t>(std::min<std::size_t>(gapBits.size(), 65535)));
  out += rans;
  out += gapBits;
  out += bitPart;
}

namespace {

// A fast payload once its tables are read and its rANS runs decoded: one run of symbols
// per field, and where the gap and magnitude bits lie.
struct FastSymbols {
  alignas(64) std::uint8_t sym[kFields][kMaxRecords + 1];
  std::uint32_t xyz[kMaxRecords];        // positions, X << 20 | Y << 10 | Z in the index space
  std::uint16_t direction[kMaxRecords];  // flag bit 3: each record's block direction
  std::uint16_t magnitude[kMaxRecords];  // the offsets A - aMin
  std::uint16_t partial[kMaxRecords];    // records in blocks that cross the grid's far faces
  std::size_t count = 0;
  std::uint32_t aMin = 0;
  int aBits = 0, aShift = 0;
  bool useGrid = false, useBlocks = false, useDirections = false;
  const unsigned char* gapBase = nullptr;
  std::size_t gapSize = 0;
  const unsigned char* bitBase = nullptr;
  std::size_t bitSize = 0;
  std::uint64_t aPos = 0;  // bit of the bit part's first magnitude offset bit
  // Flag bit 4: the first `carried` magnitude offset bits, from the states, LSB first.
  std::uint64_t carried = 0;
  std::uint8_t carriedBytes[16 * 4 + 8] = {};
};

// Checks the preamble, reads the tables and decodes the rANS runs; false on any
// inconsistency before the record pass.
bool decodeFastSymbols(std::string_view payload, std::size_t count, const PositionGrid& grid,
                       FastSymbols& s) {
  if (payload.size() < kFastPreambleBytes || count == 0 || count > kMaxRecords) return false;
  const auto* begin = reinterpret_cast<const unsigned char*>(payload.data());
  const std::uint8_t flags = begin[0];
  const auto aMin = loadLe<std::uint16_t>(begin + 1);
  const int aBits = begin[3] & 15;
  const int aShift = begin[3] >> 4;
  const int lanesLog2 = begin[4];
  const std::size_t ransSize = loadLe<std::uint16_t>(begin + 5);
  const std::size_t gapSize = loadLe<std::uint16_t>(begin + 7);
  const bool useGrid = flags & kFlagGrid;
  const bool useBlocks = flags & kFlagBlocks;
  const bool useDirections = flags & kFlagBlockDirections;
  const std::size_t lanes = std::size_t{1} << std::min(lanesLog2, kMaxLanesLog2);
  if (flags > (kFlagGrid | kFlagBlocks | kFlagFast | kFlagBlockDirections | kFlagStateBits) ||
      aMin >= kMagnitudeSteps || !validMagnitudeWidth(aBits, aShift) || lanesLog2 > kMaxLanesLog2 ||
      ransSize + gapSize > payload.size() - kFastPreambleBytes || ransSize < 4 * lanes ||
      (useGrid && !grid.active) ||
      (useBlocks && (grid.blockShift == 0 || useGrid != grid.active)) ||
      (useDirections && (!useBlocks || grid.blockDirections.size() != grid.blocks.size())))
    return false;
  if (useGrid)
    for (const auto& cells : grid.cellOrOutside)
      if (cells.size() != kPositionSteps) return false;
  const unsigned char* ransBegin = begin + kFastPreambleBytes;
  const unsigned char* ransEnd = ransBegin + ransSize;
  s.count = count;
  s.aMin = aMin;
  s.aBits = aBits;
  s.aShift = aShift;
  s.useGrid = useGrid;
  s.useBlocks = useBlocks;
  s.useDirections = useDirections;
  s.gapBase = ransEnd;
  s.gapSize = gapSize;
  s.bitBase = s.gapBase + gapSize;
  s.bitSize = payload.size() - kFastPreambleBytes - ransSize - gapSize;

  BitReader tableBits(s.bitBase, s.bitBase + s.bitSize);
  // Kept per thread so that the tables' storage is reused from packet to packet.
  thread_local std::array<FieldCoder, kFields> own;
  std::array<const FieldCoder*, kFields> coders{};
  for (int k = 0; k < kFields; ++k)
    if (!(coders[k] = readPacketTable(tableBits, own[k], k, grid.shared))) return false;
  if (tableBits.overrun()) return false;
  std::uint64_t bitPos = tableBits.bitsConsumed();

  std::uint32_t x[16];
  const unsigned char* p = ransBegin;
  for (std::size_t l = 0; l < lanes; ++l, p += 4) {
    x[l] = loadLe<std::uint32_t>(p);
    if (x[l] < kRansLow) return false;  // a state the encoder never leaves behind
  }
  bool overrun = false;
  for (int k = 0; k < kFields; ++k) {
    const FieldCoder& c = *coders[k];
    if (c.mode == kModeConstant) {
      std::memset(s.sym[k], static_cast<int>(c.constant), count);
    } else if (c.mode == kModeRaw) {
      const int w = kAlphabetBits[k];
      for (std::size_t i = 0; i < count; ++i, bitPos += static_cast<std::uint64_t>(w))
        s.sym[k][i] =
            static_cast<std::uint8_t>(peekBits(s.bitBase, s.bitSize, bitPos) & ((1u << w) - 1));
    } else {
      RunDecoder run = kRunDecoders[lanesLog2];
#if defined(__x86_64__)
      if (lanesLog2 == 4 && simdRun16() != nullptr) run = simdRun16();
#endif
      run(c.model, x, p, ransEnd, s.sym[k], count, overrun);
    }
  }
  if (overrun || p != ransEnd) return false;
  // The states end where the encoder started them: 2^16, or with flag bit 4 2^31 plus the
  // bits they carry (unused high bits zero).
  const std::uint64_t offsetBits = std::uint64_t{count} * static_cast<std::uint64_t>(aBits);
  s.carried =
      (flags & kFlagStateBits) ? std::min<std::uint64_t>(offsetBits, kStateBits * lanes) : 0;
  if ((flags & kFlagStateBits) && s.carried == 0) return false;  // one encoding per packet
  for (std::size_t l = 0; l < lanes; ++l) {
    const int c = laneCarry(s.carried, l);
    if (c == 0) {
      if (x[l] != kRansLow) return false;
      continue;
    }
    if ((x[l] >> c) != (0x80000000u >> c)) return false;
    // 31 bits at bit 31 * l: within the 5 bytes from byte (31 * l) / 8.
    const std::size_t at = kStateBits * l;
    const std::uint64_t bits = std::uint64_t{x[l] & 0x7fffffffu} << (at % 8);
    for (std::size_t b = 0; b < 5; ++b)
      s.carriedBytes[at / 8 + b] |= static_cast<std::uint8_t>(bits >> (8 * b));
  }
  s.aPos = bitPos;
  return (bitPos + offsetBits - s.carried + 7) / 8 == s.bitSize;
}

// 1 when index-space position xyz (X << 20 | Y << 10 | Z) lies past the grid's sizes.
inline std::uint32_t outsideGrid(std::uint32_t xyz, std::uint32_t sizeX, std::uint32_t sizeY,
                                 std::uint32_t sizeZ) {
  return static_cast<std::uint32_t>((xyz >> 20) >= sizeX) |
         static_cast<std::uint32_t>(((xyz >> 10) & 1023u) >= sizeY) |
         static_cast<std::uint32_t>((xyz & 1023u) >= sizeZ);
}

// The first pass of the record rebuild: the positions, serial through the gap prefix
// sum. Writes xyz[i] = X << 20 | Y << 10 | Z in the index space (voxel indices on a grid,
// else cells); false when a code or index is out of range (all indices stay below 1024
// meanwhile, so the second pass's lookups stay in bounds).
template <bool kBlocks, bool kGrid, bool kSmallBlocks = false>
bool rebuildPositions(FastSymbols& s, const PositionGrid& grid) {
  std::uint32_t* xyzOut = s.xyz;
  std::uint16_t* directionOut = s.direction;  // read only with flag bit 3
  const int blockBits = kBlocks ? 3 * grid.blockShift : 0;
  const std::uint64_t codeLimit =
      kBlocks ? std::uint64_t{grid.blocks.size()} << blockBits : std::uint64_t{1} << 30;
  const std::uint32_t lowMask = (1u << blockBits) - 1;
  const std::uint64_t* origins = grid.blockOrigins.data();
  const std::size_t lastBlock = grid.blockOrigins.empty() ? 0 : grid.blockOrigins.size() - 1;
  const std::uint32_t sizeX = grid.axisSize(0), sizeY = grid.axisSize(1), sizeZ = grid.axisSize(2);
  const std::uint8_t* gaps = s.sym[kGap];
  const unsigned char* gapBase = s.gapBase;
  const std::size_t gapSize = s.gapSize, count = s.count;
  // The codes first, the serial prefix sum alone (codes over 32 bits are out of range
  // anyway: the last one is checked below and they only grow).
  std::uint64_t code = 0, gapPos = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t t = gaps[i];
    const auto extra = static_cast<std::uint32_t>(peekBits(gapBase, gapSize, gapPos));
    gapPos += kGapTables.width[t];
    code += kGapTables.base[t] | (extra & kGapTables.mask[t]);
    xyzOut[i] = static_cast<std::uint32_t>(std::min<std::uint64_t>(code, 0xffffffffu));
  }
  // Then the positions: with blocks, the block's origin (a table of up to 2^21 entries,
  // fetched ahead: the codes are known) plus the position inside it.
  constexpr std::size_t kAhead = 16;
  std::uint32_t outside = 0;
  // With blocks on a grid, only records in blocks that cross the grid's far faces can lie
  // outside it: their indices are listed (branch-free) and checked after the loop.
  std::uint16_t* partial = s.partial;
  std::size_t partialCount = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t m = xyzOut[i];
    std::uint32_t xyz;
    if constexpr (kBlocks) {
      if (i + kAhead < count)
        __builtin_prefetch(origins +
                           std::min<std::size_t>(xyzOut[i + kAhead] >> blockBits, lastBlock));
      const std::uint64_t origin = origins[std::min<std::size_t>(m >> blockBits, lastBlock)];
      // Blocks of at most 16 indices per axis: the offset is one 12-bit piece.
      xyz = static_cast<std::uint32_t>(origin) +
            (kSmallBlocks ? kMortonPieces.xyz[m & lowMask] : mortonToXyz(m & lowMask));
      directionOut[i] = static_cast<std::uint16_t>(origin >> 32);
      if constexpr (kGrid) {
        partial[partialCount] = static_cast<std::uint16_t>(i);
        partialCount += origin >> 63;
      }
    } else {  // bits over 30 are dropped; the code is checked
      xyz = mortonToXyz(m);
    }
    if constexpr (kGrid && !kBlocks) outside |= outsideGrid(xyz, sizeX, sizeY, sizeZ);
    xyzOut[i] = xyz;
  }
  for (std::size_t k = 0; k < partialCount; ++k)
    outside |= outsideGrid(xyzOut[partial[k]], sizeX, sizeY, sizeZ);
  return code < codeLimit && outside == 0 && (gapPos + 7) / 8 == gapSize;
}

// The second pass: directions (deltas from the previous record, or with flag bit 3 from
// the record's block direction), magnitudes and colours, each record handed to
// emit(i, xyz, theta, phi, a, c). Theta and A are range-checked once at the end (ORed into
// `seen`), so emit may see out-of-range values of a packet that is then rejected, never
// indices out of its tables' bounds (theta <= 63, A <= 32767).
template <bool kDirections, typename Emit>
bool emitRecords(FastSymbols& s, Emit&& emit) {
  const std::uint32_t* xyz = s.xyz;
  const std::uint8_t* thetas = s.sym[kTheta];
  const std::uint8_t* phis = s.sym[kPhi];
  const std::uint8_t* colors = s.sym[kColor];
  const std::size_t count = s.count;
  {  // the magnitude offsets first, in a loop of their own
    const unsigned char* bitBase = s.bitBase;
    const std::size_t bitSize = s.bitSize;
    const auto aBits = static_cast<std::uint64_t>(s.aBits);
    const auto aMask = static_cast<std::uint32_t>((1u << s.aBits) - 1);
    const int aShift = s.aShift;  // stored shifted back: A - aMin
    // Offset i lies at bit i * aBits of the carried bits followed by the bit part's: the
    // offsets wholly among the carried bits, the one across the seam, then the rest.
    const std::uint64_t carried = s.carried;
    const std::size_t inStates =
        aBits == 0 ? 0 : std::min<std::size_t>(count, static_cast<std::size_t>(carried / aBits));
    const std::size_t carriedSize = sizeof s.carriedBytes;
    std::size_t i = 0;
    for (std::uint64_t pos = 0; i < inStates; ++i, pos += aBits)
      s.magnitude[i] = static_cast<std::uint16_t>(
          (peekBits(s.carriedBytes, carriedSize, pos) & aMask) << aShift);
    std::uint64_t aPos = s.aPos;
    if (i < count && carried > i * aBits) {  // across the seam
      const std::uint64_t low = carried - i * aBits;
      const std::uint64_t v =
          peekBits(s.carriedBytes, carriedSize, i * aBits) & ((std::uint64_t{1} << low) - 1);
      s.magnitude[i] = static_cast<std::uint16_t>(
          ((v | (peekBits(bitBase, bitSize, aPos) << low)) & aMask) << aShift);
      aPos += aBits - low;
      ++i;
    }
    for (; i < count; ++i, aPos += aBits)
      s.magnitude[i] =
          static_cast<std::uint16_t>((peekBits(bitBase, bitSize, aPos) & aMask) << aShift);
  }
  const std::uint16_t* offsets = s.magnitude;
  const std::uint32_t aMin = s.aMin;
  std::uint32_t theta = 0, phi = 0, seen = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if constexpr (kDirections) {  // from the block's direction (model kind 2)
      theta = ((s.direction[i] >> 6) + thetas[i]) & 63u;
      phi = (s.direction[i] + phis[i]) & 63u;
    } else {
      theta = (theta + thetas[i]) & 63u;
      phi = (phi + phis[i]) & 63u;
    }
    const std::uint32_t a = aMin + offsets[i];
    seen |= (theta << 16) | a;
    emit(i, xyz[i], theta, phi, a & 32767u, colors[i]);
  }
  static_assert(kThetaSteps == 32 && kMagnitudeSteps == 32768);
  return (seen & ((32u << 16) | 32768u)) == 0;
}

// Rebuilds the records from the symbols: the positions, then the rest (above).
template <typename Emit>
bool rebuildRecords(FastSymbols& s, const PositionGrid& grid, Emit&& emit) {
  const bool small = grid.blockShift <= 4;
  const bool positions = s.useBlocks
                             ? (s.useGrid ? (small ? rebuildPositions<true, true, true>(s, grid)
                                                   : rebuildPositions<true, true>(s, grid))
                                          : (small ? rebuildPositions<true, false, true>(s, grid)
                                                   : rebuildPositions<true, false>(s, grid)))
                             : (s.useGrid ? rebuildPositions<false, true>(s, grid)
                                          : rebuildPositions<false, false>(s, grid));
  if (!positions) return false;
  return s.useDirections ? emitRecords<true>(s, emit) : emitRecords<false>(s, emit);
}

}  // namespace

bool decodeFastLayout(std::string_view payload, std::size_t count, const PositionGrid& grid,
                      std::uint64_t* out) {
  FastSymbols s;
  if (!decodeFastSymbols(payload, count, grid, s)) return false;
  const std::uint16_t* cellX = grid.cellOrOutside[0].data();
  const std::uint16_t* cellY = grid.cellOrOutside[1].data();
  const std::uint16_t* cellZ = grid.cellOrOutside[2].data();
  const bool useGrid = s.useGrid;
  return rebuildRecords(s, grid,
                        [=](std::size_t i, std::uint32_t xyz, std::uint32_t theta,
                            std::uint32_t phi, std::uint32_t a, std::uint32_t c) {
                          if (useGrid)
                            xyz = (std::uint32_t{cellX[xyz >> 20]} << 20) |
                                  (std::uint32_t{cellY[(xyz >> 10) & 1023u]} << 10) |
                                  cellZ[xyz & 1023u];
                          out[i] = (std::uint64_t{xyz} << 34) | (std::uint64_t{theta} << 29) |
                                   (std::uint64_t{phi} << 23) | (std::uint64_t{a} << 8) | c;
                        });
}

VectorTables::VectorTables(const Dequantizer& dequantizer, const PositionGrid& grid)
    : magnitude(dequantizer.magnitudes(), dequantizer.magnitudes() + kMagnitudeSteps) {
  for (int a = 0; a < 3; ++a) {
    std::copy_n(dequantizer.axis(a).begin(), kPositionSteps, cellAxis[a].begin());
    for (std::size_t i = 0; i < grid.cellOf[a].size() && i < kPositionSteps; ++i)
      gridAxis[a][i] = dequantizer.axis(a)[grid.cellOf[a][i]];
  }
  std::copy_n(dequantizer.directions(), kDirectionCells, direction.begin());
  std::copy_n(dequantizer.colors(), kPaletteSize, color.begin());
}

bool decodeFastVectors(std::string_view payload, std::size_t count, const PositionGrid& grid,
                       const VectorTables& tables, DecodedVector* out) {
  FastSymbols s;
  if (!decodeFastSymbols(payload, count, grid, s)) return false;
  const auto& axis = s.useGrid ? tables.gridAxis : tables.cellAxis;
  const float* ax = axis[0].data();
  const float* ay = axis[1].data();
  const float* az = axis[2].data();
  const glm::vec3* direction = tables.direction.data();
  const float* magnitude = tables.magnitude.data();
  const std::uint32_t* color = tables.color.data();
  return rebuildRecords(s, grid,
                        [=](std::size_t i, std::uint32_t xyz, std::uint32_t theta,
                            std::uint32_t phi, std::uint32_t a, std::uint32_t c) {
                          DecodedVector& v = out[i];
                          v.position.x = ax[xyz >> 20];
                          v.position.y = ay[(xyz >> 10) & 1023u];
                          v.position.z = az[xyz & 1023u];
                          v.magnitude = magnitude[a];
                          const glm::vec3& n = direction[((theta & 31u) << 6) | phi];
                          v.normal.x = n.x;
                          v.normal.y = n.y;
                          v.normal.z = n.z;
                          v.rgba = color[c];
                        });
}

}  // namespace gs::qnv::detail
