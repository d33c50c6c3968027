// Line and column of a byte offset in XML that is fed piece by piece, as expat counts them
// (ISO/IEC 19776-1 files: lines end at LF, CR LF or a lone CR; a column is a character),
// found from an index of line starts made with memchr as the bytes come: cheaper than
// expat's own count, which steps through every byte. Exact answers only: where the line
// before the offset is not all ASCII, starts in an earlier piece, or the input may be
// UTF-16, at() says it does not know. Internal to gs_encodings.
#pragma once

#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

class XmlPositions {
 public:
  /// The next piece of the input (an empty piece: the end). `piece` must stay readable
  /// until the next feed(): at() reads it.
  void feed(std::string_view piece);
  /// Line and column (1-based) of byte offset `offset` of the input (not before the
  /// offsets asked before, nor past the end of the current piece); {0, 0} when this
  /// cannot tell exactly.
  std::pair<int, int> at(std::uint64_t offset);

 private:
  std::vector<std::uint64_t> lineStarts_;  // offsets of the lines after the first
  std::uint64_t dropped_ = 0;              // line starts removed from the front
  std::size_t cursor_ = 0;                 // lineStarts_ before the last offset asked
  std::uint64_t pieceStart_ = 0;           // offset of piece_
  std::string_view piece_;
  std::uint64_t fed_ = 0;  // bytes fed
  unsigned char first_[4] = {};
  bool decided_ = false;  // whether the input is known to be no UTF-16
  bool usable_ = false;   // decided_ and it is not
  char last_ = 0;         // last byte fed
  // The line of the last offset asked: checked to be ASCII up to checked_.
  std::uint64_t lineStart_ = ~std::uint64_t{0};
  std::uint64_t checked_ = 0;
  std::uint64_t nonAscii_ = ~std::uint64_t{0};  // first non-ASCII byte on it, if seen
};

}  // namespace gs::vrml::parsing
