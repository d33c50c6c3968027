// The VRML97 lexer (ISO/IEC 14772-1:1997 clause 5.1 and annex A.2, classic UTF-8
// encoding). Internal to gs_encodings. It works in place over a std::string_view: no per-token
// allocation, and line and column are computed only when a diagnostic asks for them.
// For StreamingParser the text may grow (extend()); the lexer then records whether it
// looked at the end of the text (hitEnd()), where more bytes could change what it read.
#pragma once

#include "vrml/diagnostic.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

/// Character classes of annex A.2 (bit set per byte value).
enum CharClass : std::uint8_t {
  kSpace = 1,    // whitespace (any byte <= 0x20) and ','
  kIdFirst = 2,  // may start an identifier
  kIdRest = 4,   // may continue an identifier
  kDigit = 8,
};
constexpr std::array<std::uint8_t, 256> makeCharClass() {
  std::array<std::uint8_t, 256> t{};
  for (int c = 0; c < 256; ++c) {
    std::uint8_t v = 0;
    if (c <= 0x20 || c == ',') v |= kSpace;
    if (c >= '0' && c <= '9') v |= kDigit;
    // IdRestChars excludes 0x0-0x20, " # ' , . [ \ ] { } and 0x7f.
    const bool rest = c > 0x20 && c != '"' && c != '#' && c != '\'' && c != ',' && c != '.' &&
                      c != '[' && c != '\\' && c != ']' && c != '{' && c != '}' && c != 0x7f;
    if (rest) v |= kIdRest;
    // IdFirstChar additionally excludes digits, + and -.
    if (rest && !(c >= '0' && c <= '9') && c != '+' && c != '-') v |= kIdFirst;
    t[static_cast<std::size_t>(c)] = v;
  }
  return t;
}
inline constexpr std::array<std::uint8_t, 256> kCharClass = makeCharClass();

inline bool isSpace(char c) {
  return (kCharClass[static_cast<unsigned char>(c)] & kSpace) != 0;
}
inline bool isIdFirst(char c) {
  return (kCharClass[static_cast<unsigned char>(c)] & kIdFirst) != 0;
}
inline bool isIdRest(char c) {
  return (kCharClass[static_cast<unsigned char>(c)] & kIdRest) != 0;
}
inline bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

/// a == b for the short names of node types and fields, without a call to memcmp.
inline bool sameName(std::string_view a, std::string_view b) {
  const std::size_t n = a.size();
  if (n != b.size()) return false;
  if (n >= 8 && n <= 16) {  // the usual length: two words, overlapping
    std::uint64_t a0, a1, b0, b1;
    std::memcpy(&a0, a.data(), 8);
    std::memcpy(&b0, b.data(), 8);
    std::memcpy(&a1, a.data() + n - 8, 8);
    std::memcpy(&b1, b.data() + n - 8, 8);
    return a0 == b0 && a1 == b1;
  }
  for (std::size_t i = 0; i < n; ++i)
    if (a[i] != b[i]) return false;
  return true;
}

enum class Tok : std::uint8_t {
  end,       // end of input
  id,        // identifier or keyword (DEF, USE, PROTO, TRUE, ...)
  number,    // starts with a digit, '+', '-', or '.' followed by a digit
  string,    // starts with '"'
  lbrace,    // {
  rbrace,    // }
  lbracket,  // [
  rbracket,  // ]
  period,    // . (only meaningful in ROUTE)
  other,     // a byte that cannot start any token
};

/// One token: where it starts and its text (for numbers and strings, the raw word).
struct Token {
  Tok kind = Tok::end;
  std::size_t offset = 0;
  std::string_view text;
  bool unterminated = false;  // a string token without its closing quote
};

/// Thrown for errors: the derived class tells the parser whether it may resynchronise.
struct RecoverableError : ParseError {
  using ParseError::ParseError;
};

/// Where the bytes of a translated text came from: X3D's XML and JSON encodings are read
/// as the Classic VRML text they are translated into (x3d_xml.hpp), and every location the
/// parser gives names the original file instead.
class TextOrigin {
 public:
  /// The original line and column (1-based) of byte `offset` of the translation; {0, 0}
  /// when unknown. Offsets are asked mostly in increasing order.
  virtual std::pair<int, int> at(std::size_t offset) = 0;

 protected:
  TextOrigin() = default;
  ~TextOrigin() = default;
  TextOrigin(const TextOrigin&) = default;
  TextOrigin& operator=(const TextOrigin&) = default;
};

class Lexer {
 public:
  /// `text` must outlive the lexer; `file` names it in diagnostics. Lexing starts at
  /// byte `start` (after the header line).
  Lexer(std::string_view text, std::string file, std::size_t start = 0);

  /// Skips whitespace, commas and `#` comments.
  void skipSpace() {
    while (true) {
      if (p_ >= end_) {
        hitEnd_ = true;
        return;
      }
      const char c = *p_;
      if (isSpace(c)) {
        ++p_;
      } else if (c == '#') {
        skipComment();
      } else {
        break;
      }
    }
  }
  /// The next byte after skipping space; '\0' at the end of input.
  char peekChar() {
    skipSpace();
    return p_ < end_ ? *p_ : '\0';
  }
  bool atEnd() {
    skipSpace();
    return p_ >= end_;
  }
  /// Consumes `c` when it is the next byte after space; returns whether it did.
  bool accept(char c) {
    if (peekChar() == c) {
      ++p_;
      return true;
    }
    return false;
  }

  /// Consumes the identifier `word` when it is the next token; returns whether it did.
  bool acceptKeyword(std::string_view word) {
    skipSpace();
    if (static_cast<std::size_t>(end_ - p_) < word.size() ||
        std::string_view(p_, word.size()) != word ||
        (p_ + word.size() < end_ && isIdRest(p_[word.size()])))
      return false;
    p_ += word.size();
    return true;
  }
  /// The next token, not consumed.
  Token peek();
  /// The next token, consumed.
  Token next() {
    Token t = peek();
    consume(t);
    return t;
  }
  /// Moves past `t`, which must be the token peek() returned last.
  void consume(const Token& t) { p_ = text_.data() + t.offset + t.text.size(); }

  /// Reads an identifier or fails with "expected <what>, got '...'".
  std::string_view expectId(const char* what);
  /// Consumes `c` or fails with "expected 'c', got '...'".
  void expect(char c);

  /// Numbers (annex A.2 sfint32Value / sffloatValue). Each skips space first and fails
  /// with a RecoverableError naming what was expected when no number of the kind is
  /// there. Short plain decimals (the bulk of real files) take an inline fast path that
  /// gives the same correctly rounded result as the general one.
  float readFloat() {
    skipSpace();
    return floatHere();
  }
  /// Reads numbers up to the closing ']' (consumed), appending them to `out` in groups
  /// of N (a float, or a glm vector of N floats). A group cut short by ']' is an error.
  template <int N, class T>
  void readFloatsUntilBracket(std::vector<T>& out) {
    while (separatorThen() != ']') {
      if constexpr (N == 1) {
        out.push_back(floatHere());
      } else {
        T v;
        v[0] = floatHere();
        for (int i = 1; i < N; ++i) v[i] = readFloat();
        out.push_back(v);
      }
    }
    ++p_;
  }
  void readInt32sUntilBracket(std::vector<std::int32_t>& out) {
    while (separatorThen() != ']') out.push_back(int32Here());
    ++p_;
  }
  double readDouble();
  /// Decimal or 0x hexadecimal; values up to 0xFFFFFFFF wrap to negative int32 as
  /// SFImage pixels need. A float where an integer is needed is an error.
  std::int32_t readInt32() {
    skipSpace();
    return int32Here();
  }
  /// A quoted string with \" and \\ escapes (clause 5.9), appended to nothing: `out` is
  /// replaced. Fails at the opening quote when the string is not terminated.
  void readString(std::string& out);
  /// True when the next token starts a number.
  bool atNumber() {
    const char c = peekChar();
    return isDigit(c) || c == '-' || c == '+' || c == '.';
  }

  /// Skips one value or node in balanced form: a token, or a {...} / [...] group.
  void skipBalanced();

  /// The text grew: `text` starts with the bytes of the old text (it may live elsewhere now,
  /// after a reallocation). Keeps the offset and the line bookkeeping. `final`: the text
  /// will not grow again (a CR at its end is then a line end of its own). While it may
  /// grow, the caller ends it where a token ends (whitespace or a bracket last), so that
  /// only a string, a comment or the wait for a next token can run into its end.
  void extend(std::string_view text, bool final);
  /// Whether the lexer looked at the end of the text since clearHitEnd(): reached it while
  /// skipping space or a comment, scanning a string, or failing for want of input.
  bool hitEnd() const { return hitEnd_; }
  void clearHitEnd() { hitEnd_ = false; }
  /// Records that a decision depended on how much text is left (see remaining()).
  void markEnd() { hitEnd_ = true; }
  /// Where lexing stands, with the line cache (restored when a statement is undone).
  struct Position {
    std::size_t offset;
    std::size_t cacheOffset;
    int cacheLine;
    std::size_t cacheLineStart;
  };
  Position position() const {
    return Position{offset(), cacheOffset_, cacheLine_, cacheLineStart_};
  }
  void restore(const Position& p) {
    setOffset(p.offset);
    cacheOffset_ = p.cacheOffset;
    cacheLine_ = p.cacheLine;
    cacheLineStart_ = p.cacheLineStart;
  }

  /// Lexes `text` (which must outlive its use) from its start instead: the X3D XML
  /// reader's attribute values, one at a time. Line cache and end flags start afresh; the
  /// file name and origin stay.
  void rebind(std::string_view text) {
    text_ = text;
    p_ = text.data();
    end_ = text.data() + text.size();
    cacheOffset_ = 0;
    cacheLine_ = 1;
    cacheLineStart_ = 0;
    marks_.clear();
    loneCr_ = false;
    crChecked_ = 0;
    growing_ = false;
    hitEnd_ = false;
  }

  /// Exchanges what the two lexers read (text, position, line cache, end flags), each
  /// keeping its file name and origin: cheaper than swapping the lexers.
  void swapText(Lexer& o) noexcept {
    std::swap(text_, o.text_);
    std::swap(p_, o.p_);
    std::swap(end_, o.end_);
    std::swap(cacheOffset_, o.cacheOffset_);
    std::swap(cacheLine_, o.cacheLine_);
    std::swap(cacheLineStart_, o.cacheLineStart_);
    marks_.swap(o.marks_);
    std::swap(loneCr_, o.loneCr_);
    std::swap(crChecked_, o.crChecked_);
    std::swap(growing_, o.growing_);
    std::swap(hitEnd_, o.hitEnd_);
  }

  std::size_t offset() const { return static_cast<std::size_t>(p_ - text_.data()); }
  std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
  void setOffset(std::size_t o) { p_ = text_.data() + o; }
  std::string_view text() const { return text_; }
  const std::string& file() const { return file_.str(); }
  /// The same name, shared (for locations: no copy of the string).
  const SourceFile& sourceFile() const { return file_; }

  /// Line and column (from 1, column in bytes) of byte `offset`; cached, so asking in
  /// increasing order costs O(distance). With an origin (setOrigin), the original file's
  /// line and column where it knows them.
  SourceLocation locationAt(std::size_t offset);
  /// The text is a translation (X3D XML or JSON): locations come from `origin` (which must
  /// outlive the lexer; null: none).
  void setOrigin(TextOrigin* origin) { origin_ = origin; }
  /// A printable excerpt of the token at `offset` for messages ("end of file" at end).
  std::string describeAt(std::size_t offset) const;

  [[noreturn]] void fatal(std::size_t offset, std::string message);
  [[noreturn]] void fail(std::size_t offset, std::string message);
  /// fail() with "expected <what>, got '<token at offset>'".
  [[noreturn]] void failExpected(std::size_t offset, std::string_view what);

 private:
  // Skips space and returns the next byte; at the end of input fails (fatal).
  char separatorThen() {
    while (true) {
      if (p_ >= end_) {
        hitEnd_ = true;
        failExpected(offset(), "a number or ']'");
      }
      const char c = *p_;
      if (static_cast<unsigned char>(c) > ',') return c;  // digits, '-', '.', ']'
      if (isSpace(c))
        ++p_;
      else if (c == '#')
        skipComment();
      else
        return c;
    }
  }
  // A float at p_ (no space skipping). Short plain decimals (the bulk of real files)
  // take this inline path, which gives the same correctly rounded result as fast_float:
  // with at most 8 digits and m < 2^24 the mantissa m is exact in a float, as is 10^k
  // for k <= 8, so m / 10^k is one correctly rounded division. Plain loops beat SWAR
  // digit tricks here (measured on the KiCad corpus: the digit counts are predictable).
  float floatHere() {
    if (end_ - p_ < 24) return readFloatSlow();  // near the end: the checked path
    const char* q = p_;  // 24 bytes remain: the loops below read at most 12 without checks
    const bool negative = *q == '-';
    q += negative ? 1 : 0;
    std::uint32_t m = 0;
    unsigned d = 0;
    int digits = 0;
    while ((d = static_cast<unsigned char>(*q) - unsigned('0')) <= 9 && digits < 9) {
      m = m * 10 + d;
      ++q;
      ++digits;
    }
    int fraction = 0;
    if (*q == '.') {
      ++q;
      while ((d = static_cast<unsigned char>(*q) - unsigned('0')) <= 9 && digits < 9) {
        m = m * 10 + d;
        ++q;
        ++digits;
        ++fraction;
      }
    }
    if (digits == 0 || digits > 8 || d <= 9 || m >= (1u << 24) || *q == 'e' || *q == 'E')
      return readFloatSlow();
    static constexpr float kPow10[] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f};
    const float v = static_cast<float>(m) / kPow10[fraction];
    p_ = q;
    return negative ? -v : v;
  }
  // An int32 at p_: short decimals inline, the rest (hex, long, errors) out of line.
  std::int32_t int32Here() {
    if (end_ - p_ < 16) return readInt32Slow();
    const char* q = p_;  // 16 bytes remain: the loop below reads at most 11 without checks
    if (q[0] == '-' && q[1] == '1' && static_cast<unsigned char>(q[2] - '0') > 9 && q[2] != 'x' &&
        q[2] != 'X' && q[2] != '.' && q[2] != 'e' && q[2] != 'E') {
      p_ = q + 2;  // -1 ends every face of an index list
      return -1;
    }
    const bool negative = *q == '-';
    q += negative ? 1 : 0;
    const char* first = q;
    std::uint32_t v = 0;
    unsigned d = 0;
    while ((d = static_cast<unsigned char>(*q) - unsigned('0')) <= 9 && q - first < 9) {
      v = v * 10 + d;
      ++q;
    }
    const char c = *q;
    if (q == first || d <= 9 || c == 'x' || c == 'X' || c == '.' || c == 'e' || c == 'E')
      return readInt32Slow();
    p_ = q;
    return negative ? -static_cast<std::int32_t>(v) : static_cast<std::int32_t>(v);
  }
  void skipComment();
  float readFloatSlow();
  std::int32_t readInt32Slow();
  Token scan(const char* p) const;
  [[noreturn]] void badNumber(std::size_t offset, std::string_view what);

  std::string_view text_;
  SourceFile file_;
  TextOrigin* origin_ = nullptr;
  const char* p_;
  const char* end_;
  // Cache of the last locationAt() answer.
  std::size_t cacheOffset_ = 0;
  int cacheLine_ = 1;
  std::size_t cacheLineStart_ = 0;
  // Positions the cache passed, every kMarkSpacing bytes or more, so that a question
  // about an earlier offset restarts close to it instead of at the start of the text.
  struct Mark {
    std::size_t offset;
    int line;
    std::size_t lineStart;
  };
  static constexpr std::size_t kMarkSpacing = 1 << 16;
  std::vector<Mark> marks_;
  // Whether the text has a CR not followed by LF; bytes before crChecked_ have been
  // looked at (a CR last in a text that may grow is left for later).
  bool loneCr_ = false;
  std::size_t crChecked_ = 0;
  void checkLoneCr();
  bool growing_ = false;         // extend() may add text
  mutable bool hitEnd_ = false;  // see hitEnd(); scan() (const) sets it too
};

}  // namespace gs::vrml::parsing
