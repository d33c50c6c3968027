#include "rans.hpp"

#include <algorithm>

namespace gs::qnv::detail {

void RansModel::build() {
  start.assign(freq.size(), 0);
  slots.assign(std::size_t{1} << probBits, 0);
  std::uint32_t at = 0;
  for (std::size_t s = 0; s < freq.size(); ++s) {
    start[s] = static_cast<std::uint16_t>(at);
    for (std::uint32_t k = 0; k < freq[s]; ++k)
      slots[at + k] =
          static_cast<std::uint32_t>(s) | (k << 8) | ((std::uint32_t{freq[s]} - 1) << 20);
    at += freq[s];
  }
}

void RansEncoder::finish(std::string& out) {
  for (int lane = 1; lane >= 0; --lane)
    for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<unsigned char>(x_[lane] >> (8 * i)));
  // bytes_ holds the renormalization bytes first-written first, then the state's bytes
  // low first: reversed, the decoder reads the state (high byte first) and then the
  // renormalization bytes in the order it needs them.
  out.append(bytes_.rbegin(), bytes_.rend());
  bytes_.clear();
  x_[0] = x_[1] = kRansLow;
}

RansDecoder::RansDecoder(const unsigned char* begin, const unsigned char* end)
    : p_(begin), end_(end) {
  for (std::uint32_t& x : x_) {
    for (int i = 0; i < 4; ++i) {
      if (p_ == end_) {
        overrun_ = true;
        x_[0] = x_[1] = kRansLow;
        return;
      }
      x = (x << 8) | *p_++;
    }
    if (x < kRansLow) {  // a state the encoder never leaves behind
      overrun_ = true;
      x = kRansLow;
    }
  }
}

}  // namespace gs::qnv::detail
