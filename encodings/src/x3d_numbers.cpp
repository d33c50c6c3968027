// The XML encoding's plain number lists (x3d_numbers.hpp). The inline paths follow
// Lexer::floatHere and Lexer::int32Here step by step, so that every value is the one the
// Classic parse of the translation gives.
#include "x3d_numbers.hpp"

#include "lexer.hpp"

#include <fast_float/fast_float.h>

#include <charconv>
#include <cstring>
#include <system_error>

namespace gs::vrml::parsing {

namespace {

// Appends the decimal digits at q to m (m * 10 + digit each), two a step; returns the
// first byte that is no digit. The text ends with a NUL byte, which is no digit.
inline const char* digitsInto(const char* q, std::uint32_t& m) {
  while (true) {
    const unsigned d0 = static_cast<unsigned char>(q[0]) - unsigned('0');
    if (d0 > 9) return q;
    const unsigned d1 = static_cast<unsigned char>(q[1]) - unsigned('0');
    if (d1 > 9) {
      m = m * 10 + d0;
      return q + 1;
    }
    m = m * 100 + d0 * 10 + d1;
    q += 2;
  }
}

template <FieldType T, class V>
void emplaceFlat(FieldValue& out, const float* data, std::size_t n) {
  auto& v = out.storage().emplace<static_cast<std::size_t>(T)>(n);
  if (n > 0) std::memcpy(static_cast<void*>(v.data()), data, n * sizeof(V));
}

// A float at p (no space before it); p moves past it. isSpace('\0') holds: the NUL after
// the text ends every number.
bool plainFloat(const char*& p, float& out) {
  const char* q = p;
  const bool negative = *q == '-';
  q += negative ? 1 : 0;
  const char* const first = q;
  std::uint32_t m = 0;
  // (A NUL ends every run of digits; more than 8 are not read here, and m then does not
  // matter.)
  q = digitsInto(q, m);
  std::ptrdiff_t digits = q - first;
  std::ptrdiff_t fraction = 0;
  if (*q == '.') {
    const char* const dot = ++q;
    q = digitsInto(q, m);
    fraction = q - dot;
    digits += fraction;
  }
  if (digits == 0 || digits > 8 || m >= (1u << 24) || *q == 'e' || *q == 'E') {
    // Longer or with an exponent ("1e-05", as std::to_chars writes small numbers): what
    // Lexer::readFloatSlow reads, through fast_float, after a digit or '.'. (The number
    // ends before the next separator, so that is as far as fast_float needs to see.)
    if (!(isDigit(*first) || *first == '.')) return false;
    const char* end = q;
    while (!isSpace(*end)) ++end;
    const auto r = fast_float::from_chars(p, end, out);
    if (r.ec != std::errc() || r.ptr != end) return false;
    p = r.ptr;
    return true;
  }
  if (!isSpace(*q)) return false;
  static constexpr float kPow10[] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f};
  const float v = static_cast<float>(m) / kPow10[fraction];
  out = negative ? -v : v;
  p = q;
  return true;
}

void appendNumber(std::string& out, auto v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, static_cast<std::size_t>(r.ptr - buf));
  out += ' ';
}

}  // namespace

int plainListComponents(FieldType t) {
  switch (t) {
    case FieldType::MFInt32:
    case FieldType::MFFloat:
      return 1;
    case FieldType::MFVec2f:
      return 2;
    case FieldType::MFVec3f:
    case FieldType::MFColor:
      return 3;
    default:
      return 0;
  }
}

bool readPlainInts(const char* p, std::vector<std::int32_t>& out) {
  out.clear();
  while (true) {
    while (*p != '\0' && isSpace(*p)) ++p;
    if (*p == '\0') return true;
    const bool negative = *p == '-';
    const char* first = p + (negative ? 1 : 0);
    std::uint32_t v = 0;
    const char* q = digitsInto(first, v);
    if (q == first || q - first > 9 || !isSpace(*q)) return false;
    out.push_back(negative ? -static_cast<std::int32_t>(v) : static_cast<std::int32_t>(v));
    p = q;
  }
}

bool readPlainFloats(const char* p, int components, std::vector<float>& out) {
  out.clear();
  while (true) {
    while (*p != '\0' && isSpace(*p)) ++p;
    if (*p == '\0') return out.size() % static_cast<std::size_t>(components) == 0;
    float f = 0;
    if (!plainFloat(p, f)) return false;
    out.push_back(f);
  }
}

void assignPlainList(FieldValue& out, FieldType t, const std::vector<std::int32_t>& ints,
                     const std::vector<float>& floats) {
  switch (t) {
    case FieldType::MFInt32:
      out.storage().emplace<static_cast<std::size_t>(FieldType::MFInt32)>(ints.begin(), ints.end());
      return;
    case FieldType::MFFloat:
      out.storage().emplace<static_cast<std::size_t>(FieldType::MFFloat)>(floats.begin(),
                                                                          floats.end());
      return;
    case FieldType::MFVec2f:
      emplaceFlat<FieldType::MFVec2f, glm::vec2>(out, floats.data(), floats.size() / 2);
      return;
    case FieldType::MFVec3f:
      emplaceFlat<FieldType::MFVec3f, glm::vec3>(out, floats.data(), floats.size() / 3);
      return;
    case FieldType::MFColor:
      emplaceFlat<FieldType::MFColor, glm::vec3>(out, floats.data(), floats.size() / 3);
      return;
    default:
      return;
  }
}

void appendPlainListAsClassic(std::string& out, FieldType t, const std::vector<std::int32_t>& ints,
                              const std::vector<float>& floats) {
  out += "[ ";
  if (t == FieldType::MFInt32)
    for (std::int32_t i : ints) appendNumber(out, i);
  else
    for (float f : floats) appendNumber(out, f);
  out += ']';
}

}  // namespace gs::vrml::parsing
