#include "lexer.hpp"

#include <fast_float/fast_float.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace gs::vrml::parsing {

Lexer::Lexer(std::string_view text, std::string file, std::size_t start)
    : text_(text),
      file_(std::move(file)),
      p_(text.data() + std::min(start, text.size())),
      end_(text.data() + text.size()) {}

void Lexer::skipComment() {
  while (p_ < end_ && *p_ != '\n' && *p_ != '\r') ++p_;
}

Token Lexer::scan(const char* p) const {
  Token t;
  t.offset = static_cast<std::size_t>(p - text_.data());
  if (p >= end_) return t;
  const char c = *p;
  const char* q = p + 1;
  switch (c) {
    case '{':
      t.kind = Tok::lbrace;
      break;
    case '}':
      t.kind = Tok::rbrace;
      break;
    case '[':
      t.kind = Tok::lbracket;
      break;
    case ']':
      t.kind = Tok::rbracket;
      break;
    case '"': {
      t.kind = Tok::string;
      while (q < end_ && *q != '"') q += (*q == '\\' && q + 1 < end_) ? 2 : 1;
      if (q < end_) {
        ++q;  // closing quote
      } else {
        t.unterminated = true;
        hitEnd_ = true;
      }
      if (q > end_) q = end_;
      break;
    }
    default:
      if (isDigit(c) || c == '+' || c == '-' || (c == '.' && q < end_ && isDigit(*q))) {
        t.kind = Tok::number;
        while (q < end_ && (isIdRest(*q) || *q == '.')) ++q;
      } else if (c == '.') {
        t.kind = Tok::period;
      } else if (isIdFirst(c)) {
        t.kind = Tok::id;
        // Four bytes a step while far from the end, then one at a time.
        while (end_ - q >= 4 && isIdRest(q[0]) && isIdRest(q[1]) && isIdRest(q[2]) &&
               isIdRest(q[3]))
          q += 4;
        while (q < end_ && isIdRest(*q)) ++q;
      } else {
        t.kind = Tok::other;
      }
  }
  t.text = std::string_view(p, static_cast<std::size_t>(q - p));
  return t;
}

Token Lexer::peek() {
  skipSpace();
  return scan(p_);
}

std::string_view Lexer::expectId(const char* what) {
  Token t = peek();
  if (t.kind != Tok::id) failExpected(t.offset, what);
  consume(t);
  return t.text;
}

void Lexer::expect(char c) {
  if (!accept(c)) failExpected(offset(), std::string("'") + c + "'");
}

void Lexer::badNumber(std::size_t off, std::string_view what) {
  failExpected(off, what);
}

float Lexer::readFloatSlow() {
  skipSpace();
  const char* s = p_;
  if (s < end_ && *s == '+') ++s;
  const char* q = (s < end_ && *s == '-') ? s + 1 : s;
  // Only digits or '.' may follow the sign: fast_float would also take "inf" and "nan".
  if (q >= end_ || !(isDigit(*q) || *q == '.')) badNumber(offset(), "a number");
  float v = 0;
  const auto r = fast_float::from_chars(s, end_, v);
  if (r.ec != std::errc()) badNumber(offset(), "a number");
  p_ = r.ptr;
  return v;
}

double Lexer::readDouble() {
  skipSpace();
  const char* s = p_;
  if (s < end_ && *s == '+') ++s;
  const char* q = (s < end_ && *s == '-') ? s + 1 : s;
  if (q >= end_ || !(isDigit(*q) || *q == '.')) badNumber(offset(), "a number");
  double v = 0;
  const auto r = fast_float::from_chars(s, end_, v);
  if (r.ec != std::errc()) badNumber(offset(), "a number");
  p_ = r.ptr;
  return v;
}

std::int32_t Lexer::readInt32Slow() {
  skipSpace();
  const char* s = p_;
  bool negative = false;
  if (s < end_ && (*s == '+' || *s == '-')) {
    negative = *s == '-';
    ++s;
  }
  std::uint64_t v = 0;
  const char* digits = s;
  if (end_ - s >= 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X')) {
    s += 2;
    digits = s;
    for (; s < end_; ++s) {
      const char c = *s;
      unsigned d;
      if (c >= '0' && c <= '9')
        d = static_cast<unsigned>(c - '0');
      else if (c >= 'a' && c <= 'f')
        d = static_cast<unsigned>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F')
        d = static_cast<unsigned>(c - 'A' + 10);
      else
        break;
      v = v * 16 + d;
      if (v > 0xFFFFFFFFull) fail(offset(), "integer " + describeAt(offset()) + " out of range");
    }
  } else {
    for (; s < end_ && isDigit(*s); ++s) {
      v = v * 10 + static_cast<unsigned>(*s - '0');
      if (v > 0xFFFFFFFFull) fail(offset(), "integer " + describeAt(offset()) + " out of range");
    }
  }
  if (s == digits) badNumber(offset(), "an integer");
  if (s < end_ && (*s == '.' || *s == 'e' || *s == 'E'))
    fail(offset(), "expected an integer, got " + describeAt(offset()));
  p_ = s;
  const auto u = static_cast<std::uint32_t>(v);
  return negative ? static_cast<std::int32_t>(0u - u) : static_cast<std::int32_t>(u);
}

void Lexer::readString(std::string& out) {
  skipSpace();
  if (p_ >= end_ || *p_ != '"') failExpected(offset(), "a string");
  const std::size_t start = offset();
  const char* q = p_ + 1;
  out.clear();
  const char* run = q;
  while (true) {
    while (q < end_ && *q != '"' && *q != '\\') ++q;
    if (q >= end_) {
      hitEnd_ = true;
      fatal(start, "unterminated string");
    }
    out.append(run, static_cast<std::size_t>(q - run));
    if (*q == '"') break;
    // Backslash: the next byte is taken literally (\" and \\ per clause 5.9).
    if (q + 1 >= end_) {
      hitEnd_ = true;
      fatal(start, "unterminated string");
    }
    out.push_back(q[1]);
    q += 2;
    run = q;
  }
  p_ = q + 1;
}

void Lexer::skipBalanced() {
  Token t = next();
  if (t.kind == Tok::string && t.unterminated) fatal(t.offset, "unterminated string");
  if (t.kind != Tok::lbrace && t.kind != Tok::lbracket) return;
  const std::size_t start = t.offset;
  std::size_t depth = 1;
  while (depth > 0) {
    t = next();
    switch (t.kind) {
      case Tok::end:
        fatal(start, "unexpected end of file: no matching close for this bracket");
      case Tok::lbrace:
      case Tok::lbracket:
        ++depth;
        break;
      case Tok::rbrace:
      case Tok::rbracket:
        --depth;
        break;
      case Tok::string:
        if (t.unterminated) fatal(t.offset, "unterminated string");
        break;
      default:
        break;
    }
  }
}

SourceLocation Lexer::locationAt(std::size_t off) {
  if (off > text_.size()) off = text_.size();
  if (origin_ != nullptr) {
    const auto [line, column] = origin_->at(off);
    if (line > 0) return SourceLocation{file_, line, column};
  }
  if (off < cacheOffset_) {
    // Back to the last mark at or before `off` (marks are in increasing order).
    auto it = std::upper_bound(marks_.begin(), marks_.end(), off,
                               [](std::size_t o, const Mark& m) { return o < m.offset; });
    if (it == marks_.begin()) {
      cacheOffset_ = 0;
      cacheLine_ = 1;
      cacheLineStart_ = 0;
    } else {
      --it;
      cacheOffset_ = it->offset;
      cacheLine_ = it->line;
      cacheLineStart_ = it->lineStart;
    }
  }
  if (!loneCr_ && crChecked_ < text_.size()) checkLoneCr();
  const char* base = text_.data();
  if (!loneCr_) {
    // LF or CR LF line ends: jump from newline to newline with memchr.
    const char* p = base + cacheOffset_;
    const char* stop = base + off;
    while (p < stop) {
      const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(stop - p));
      if (nl == nullptr) break;
      p = static_cast<const char*>(nl) + 1;
      ++cacheLine_;
      cacheLineStart_ = static_cast<std::size_t>(p - base);
    }
  } else {
    for (std::size_t i = cacheOffset_; i < off; ++i) {
      const char c = text_[i];
      if (c == '\n' || (c == '\r' && (i + 1 >= text_.size() || text_[i + 1] != '\n'))) {
        ++cacheLine_;
        cacheLineStart_ = i + 1;
      }
    }
  }
  cacheOffset_ = off;
  if (off >= (marks_.empty() ? 0 : marks_.back().offset) + kMarkSpacing)
    marks_.push_back(Mark{off, cacheLine_, cacheLineStart_});
  return SourceLocation{file_, cacheLine_, static_cast<int>(off - cacheLineStart_ + 1)};
}

void Lexer::checkLoneCr() {
  for (std::size_t i = text_.find('\r', crChecked_); i != std::string_view::npos;
       i = text_.find('\r', i + 1)) {
    if (i + 1 >= text_.size() && growing_) {
      crChecked_ = i;  // an LF may follow in the next bytes
      return;
    }
    if (i + 1 >= text_.size() || text_[i + 1] != '\n') {
      loneCr_ = true;
      return;
    }
  }
  crChecked_ = text_.size();
}

void Lexer::extend(std::string_view text, bool final) {
  const std::size_t o = offset();
  const std::size_t old = text_.size();
  text_ = text;
  p_ = text.data() + std::min(o, text.size());
  end_ = text.data() + text.size();
  growing_ = !final;
  // A line count cached at the old end may have taken a last CR for a line end of its
  // own while its LF had not arrived: go back to a mark before it.
  if (cacheOffset_ >= old && old > 0) {
    while (!marks_.empty() && marks_.back().offset >= old) marks_.pop_back();
    if (marks_.empty()) {
      cacheOffset_ = 0;
      cacheLine_ = 1;
      cacheLineStart_ = 0;
    } else {
      cacheOffset_ = marks_.back().offset;
      cacheLine_ = marks_.back().line;
      cacheLineStart_ = marks_.back().lineStart;
    }
  }
}

std::string Lexer::describeAt(std::size_t off) const {
  if (off >= text_.size()) return "end of file";
  Token t = scan(text_.data() + off);
  std::string_view s = t.text;
  if (t.kind == Tok::end) return "end of file";
  constexpr std::size_t kMax = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < s.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 || c == 0x7f) {
      static const char* hex = "0123456789abcdef";
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 15];
    } else {
      out += static_cast<char>(c);
    }
  }
  if (s.size() > kMax) out += "...";
  out += "'";
  return out;
}

void Lexer::fatal(std::size_t off, std::string message) {
  throw ParseError(Diagnostic{Severity::error, locationAt(off), std::move(message)});
}

void Lexer::fail(std::size_t off, std::string message) {
  throw RecoverableError(Diagnostic{Severity::error, locationAt(off), std::move(message)});
}

void Lexer::failExpected(std::size_t off, std::string_view what) {
  std::string msg = "expected ";
  msg += what;
  msg += ", got ";
  msg += describeAt(off);
  if (off >= text_.size()) {
    hitEnd_ = true;
    fatal(off, std::move(msg));
  }
  fail(off, std::move(msg));
}

}  // namespace gs::vrml::parsing
