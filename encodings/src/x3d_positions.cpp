#include "x3d_positions.hpp"

#include <algorithm>
#include <cstring>

namespace gs::vrml::parsing {

void XmlPositions::feed(std::string_view piece) {
  pieceStart_ = fed_;
  piece_ = piece;
  // UTF-16 (a byte order mark, or a zero byte among the first four): expat's counts.
  for (std::size_t i = 0; !decided_ && i < piece.size(); ++i) {
    first_[fed_ + i] = static_cast<unsigned char>(piece[i]);
    if (fed_ + i == 3 || first_[fed_ + i] == 0) {
      decided_ = true;
      usable_ =
          !((first_[0] == 0xFE && first_[1] == 0xFF) || (first_[0] == 0xFF && first_[1] == 0xFE) ||
            first_[0] == 0 || first_[1] == 0 || first_[2] == 0 || first_[3] == 0);
    }
  }
  const char* const b = piece.data();
  const std::size_t n = piece.size();
  if (n == 0) return;
  if (last_ != '\r' && std::memchr(b, '\r', n) == nullptr) {
    for (const char* p = b;;) {
      const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(b + n - p));
      if (nl == nullptr) break;
      p = static_cast<const char*>(nl) + 1;
      lineStarts_.push_back(fed_ + static_cast<std::uint64_t>(p - b));
    }
  } else {
    char prev = last_;
    for (std::size_t i = 0; i < n; ++i) {
      const char c = b[i];
      if (c == '\n' && prev == '\r')
        ++lineStarts_.back();  // CR LF: the line starts after the LF
      else if (c == '\n' || c == '\r')
        lineStarts_.push_back(fed_ + i + 1);
      prev = c;
    }
  }
  last_ = b[n - 1];
  fed_ += n;
}

std::pair<int, int> XmlPositions::at(std::uint64_t offset) {
  if (!usable_ || offset < pieceStart_ || offset > fed_) return {0, 0};
  // Offsets only grow: drop the line starts before the cursor now and then.
  if (cursor_ > 4096 && cursor_ * 2 > lineStarts_.size()) {
    const std::size_t drop = cursor_ - 1;
    lineStarts_.erase(lineStarts_.begin(), lineStarts_.begin() + static_cast<std::ptrdiff_t>(drop));
    dropped_ += drop;
    cursor_ -= drop;
  }
  if (cursor_ > 0 && lineStarts_[cursor_ - 1] > offset) return {0, 0};  // went back
  // The next element is most often a line or a few further: step there, and search
  // only when it is far.
  const std::size_t n = lineStarts_.size();
  std::size_t c = cursor_;
  for (int steps = 0; steps < 8 && c < n && lineStarts_[c] <= offset; ++steps) ++c;
  if (c < n && lineStarts_[c] <= offset)
    c = static_cast<std::size_t>(
        std::upper_bound(lineStarts_.begin() + static_cast<std::ptrdiff_t>(c), lineStarts_.end(),
                         offset) -
        lineStarts_.begin());
  cursor_ = c;
  const std::uint64_t start = cursor_ == 0 ? 0 : lineStarts_[cursor_ - 1];
  const std::uint64_t line = dropped_ + cursor_ + 1;
  if (start < pieceStart_ || line > 0x7fffffff || offset - start > 0x7ffffffe) return {0, 0};
  if (start != lineStart_) {
    lineStart_ = start;
    checked_ = start;
    nonAscii_ = ~std::uint64_t{0};
  }
  if (nonAscii_ < offset) return {0, 0};
  for (; checked_ < offset; ++checked_) {
    if (static_cast<unsigned char>(piece_[checked_ - pieceStart_]) >= 0x80) {
      nonAscii_ = checked_;
      return {0, 0};
    }
  }
  return {static_cast<int>(line), static_cast<int>(offset - start + 1)};
}

}  // namespace gs::vrml::parsing
