// A small static-model rANS coder and an LSB-first bit stream, private to qnv/src, for
// the entropy packet encoding (docs/qnv-format.md, "Compact coding"). rANS after
// J. Duda, "Asymmetric numeral systems" (2013), in the 32-bit form with 16-bit
// renormalization of F. Giesen's ryg_rans: state x in [2^16, 2^32), a symbol of frequency f out of
// 2^P (P <= 12) costs log2(2^P / f) bits. The encoder runs backwards over the symbols, the decoder
// forwards. Every reader is bounds-checked: reading past the end yields zeros and sets a flag the
// caller checks, so no input makes it read out of bounds.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace gs::qnv::detail {

inline constexpr std::uint32_t kRansLow = 1u << 16;  // lower bound of the normalized state
inline constexpr int kMaxProbBits = 12;              // frequencies sum to 2^P, P <= 12

/// Appends bits LSB first; finish() flushes the last partial byte.
class BitWriter {
 public:
  explicit BitWriter(std::string& out) : out_(out) {}
  /// Writes the low `n` bits of `v` (0 <= n <= 32).
  void put(std::uint32_t v, int n) {
    if (n == 0) return;
    acc_ |= std::uint64_t{v & (n == 32 ? 0xffffffffu : ((1u << n) - 1))} << fill_;
    fill_ += n;
    while (fill_ >= 8) {
      out_.push_back(static_cast<char>(acc_ & 0xffu));
      acc_ >>= 8;
      fill_ -= 8;
    }
  }
  /// Elias gamma code of v >= 1: (bit length - 1) zeros, then v's bits from the top.
  void gamma(std::uint32_t v) {
    int n = 31 - __builtin_clz(v);
    put(0, n);
    for (int i = n; i >= 0; --i) put((v >> i) & 1u, 1);
  }
  void finish() {
    if (fill_ > 0) out_.push_back(static_cast<char>(acc_ & 0xffu));
    acc_ = 0;
    fill_ = 0;
  }

 private:
  std::string& out_;
  std::uint64_t acc_ = 0;
  int fill_ = 0;
};

/// Reads what BitWriter wrote. Past the end it reads zeros and sets overrun().
class BitReader {
 public:
  BitReader(const unsigned char* begin, const unsigned char* end)
      : begin_(begin), p_(begin), end_(end) {
    refill();
  }
  /// Reads `n` bits (0 <= n <= 32).
  std::uint32_t get(int n) {
    if (fill_ < n) refill();
    if (fill_ < n) {  // only past the end
      overrun_ = true;
      fill_ = 64;
    }
    const std::uint32_t v = static_cast<std::uint32_t>(acc_ & ((std::uint64_t{1} << n) - 1));
    acc_ >>= n;
    fill_ -= n;
    return v;
  }
  /// Elias gamma, at most 31 leading zeros; more sets the overrun flag and returns 1.
  std::uint32_t gamma() {
    if (fill_ < 63) refill();
    // Fast path: the whole code (n zeros, then n + 1 bits from the top) in the window.
    const auto window = static_cast<std::uint32_t>(acc_);
    if (window != 0) {
      const int n = std::countr_zero(window);
      if (2 * n + 1 <= fill_) {
        const auto bits = static_cast<std::uint32_t>((acc_ >> n) & ((std::uint64_t{2} << n) - 1));
        acc_ >>= 2 * n + 1;
        fill_ -= 2 * n + 1;
        return reverseBits(bits) >> (31 - n);  // the first bit read is the top one
      }
    }
    return gammaSlow();
  }
  bool overrun() const { return overrun_; }
  /// Bits handed out so far.
  std::size_t bitsConsumed() const {
    return static_cast<std::size_t>(p_ - begin_) * 8 - static_cast<std::size_t>(fill_);
  }
  /// Bytes not yet touched by the reader (whole bytes still in the accumulator excluded).
  std::size_t bytesLeft() const { return static_cast<std::size_t>(end_ - p_); }

 private:
  static std::uint32_t reverseBits(std::uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    return __builtin_bswap32(v);
  }
  // Bit by bit: codes near the end of the bits, or longer than the window.
  std::uint32_t gammaSlow() {
    int n = 0;
    while (get(1) == 0) {
      if (++n > 31 || overrun_) {
        overrun_ = true;
        return 1;
      }
    }
    std::uint32_t v = 1;
    for (int i = 0; i < n; ++i) v = (v << 1) | get(1);
    return v;
  }
  void refill() {
    if (end_ - p_ >= 8) {  // the fast path: one unaligned little-endian load
      std::uint64_t word;
      std::memcpy(&word, p_, 8);
      if constexpr (std::endian::native == std::endian::big) word = __builtin_bswap64(word);
      acc_ |= word << fill_;
      p_ += (63 - fill_) >> 3;
      fill_ |= 56;
      return;
    }
    while (fill_ <= 56) {
      if (p_ == end_) {
        if (fill_ < 0) fill_ = 0;
        return;
      }
      acc_ |= std::uint64_t{*p_++} << fill_;
      fill_ += 8;
    }
  }
  const unsigned char* begin_;
  const unsigned char* p_;
  const unsigned char* end_;
  std::uint64_t acc_ = 0;
  int fill_ = 0;
  bool overrun_ = false;
};

/// A static model: normalized frequencies over an alphabet of up to 256 symbols that sum
/// to 2^probBits, with the cumulative starts the encoder needs and the slot table the
/// decoder needs.
struct RansModel {
  int probBits = 0;
  std::vector<std::uint16_t> freq;   // per symbol
  std::vector<std::uint16_t> start;  // per symbol, cumulative
  // Decoder: for each of the 2^probBits slots, the symbol (bits 0..7), the slot's offset
  // from the symbol's start (bits 8..19) and the symbol's frequency minus one (bits 20..31,
  // on top: one shift from the multiplier on the decoder's dependency chain).
  std::vector<std::uint32_t> slots;

  /// Fills start and slots from freq (which must sum to 2^probBits).
  void build();
};

/// Appends rANS-coded symbols into a byte buffer, back to front. Two states ("lanes")
/// share the buffer, so that a decoder can work on two symbols at once.
class RansEncoder {
 public:
  /// Pushes `symbol` of `model` on `lane` (0 or 1); call for the symbols in reverse
  /// decoding order.
  void put(const RansModel& model, unsigned symbol, int lane) {
    std::uint32_t& x = x_[lane];
    const std::uint32_t f = model.freq[symbol];
    const std::uint64_t maxState = std::uint64_t{(kRansLow >> model.probBits) << 16} * f;
    if (x >= maxState) {  // at most one 16-bit word, read back little-endian
      bytes_.push_back(static_cast<unsigned char>(x >> 8));
      bytes_.push_back(static_cast<unsigned char>(x));
      x >>= 16;
    }
    x = ((x / f) << model.probBits) + (x % f) + model.start[symbol];
  }
  /// Appends the final states (4 bytes each, lane 0 first) and the reversed byte
  /// buffer to `out`.
  void finish(std::string& out);

 private:
  std::uint32_t x_[2] = {kRansLow, kRansLow};
  std::vector<unsigned char> bytes_;
};

/// Decodes what RansEncoder wrote, bounds-checked.
class RansDecoder {
 public:
  RansDecoder(const unsigned char* begin, const unsigned char* end);
  /// The next symbol of `model` on `lane` (0 or 1).
  unsigned get(const RansModel& model, int lane) {
    std::uint32_t& x = x_[lane];
    const std::uint32_t mask = (1u << model.probBits) - 1;
    const std::uint32_t e = model.slots[x & mask];
    x = ((e >> 20) + 1) * (x >> model.probBits) + ((e >> 8) & 0xfffu);
    // Renormalize without a branch: x >= 2^(16 - probBits) here, so one 16-bit word
    // always brings it back to [2^16, 2^32). Past the end, zeros are read instead.
    static constexpr unsigned char kZeros[2] = {0, 0};
    // Arithmetic rather than selects, which compilers turn into branches that the
    // coin-flip renormalizations mispredict.
    const auto need = static_cast<std::uint32_t>(x < kRansLow);
    const bool have = end_ - p_ >= 2;
    const unsigned char* src = have ? p_ : kZeros;
    const std::uint32_t word = src[0] | (std::uint32_t{src[1]} << 8);
    x = (x << (need << 4)) | (word & (0u - need));
    p_ += (need & static_cast<std::uint32_t>(have)) << 1;
    overrun_ |= need && !have;
    return e & 0xffu;
  }
  /// True when every byte was consumed and both states came back to their start value,
  /// as after a faithful decode.
  bool finishedCleanly() const {
    return !overrun_ && p_ == end_ && x_[0] == kRansLow && x_[1] == kRansLow;
  }

 private:
  const unsigned char* p_;
  const unsigned char* end_;
  std::uint32_t x_[2] = {0, 0};
  bool overrun_ = false;
};

}  // namespace gs::qnv::detail
