#include "x3d_values.hpp"

#include "base/text.hpp"
#include "lexer.hpp"

#include <algorithm>
#include <array>

namespace gs::vrml::parsing {

namespace {

std::string_view trim(std::string_view s) {
  const auto ws = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && ws(s.front())) s.remove_prefix(1);
  while (!s.empty() && ws(s.back())) s.remove_suffix(1);
  return s;
}

// true/false (any case) as TRUE/FALSE; other words as written.
void appendBooleans(std::string& out, std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const bool word = (s[i] >= 'a' && s[i] <= 'z') || (s[i] >= 'A' && s[i] <= 'Z');
    if (!word) {
      out += s[i++];
      continue;
    }
    std::size_t j = i;
    while (j < s.size() && ((s[j] >= 'a' && s[j] <= 'z') || (s[j] >= 'A' && s[j] <= 'Z'))) ++j;
    const std::string_view w = s.substr(i, j - i);
    if (base::equalsNoCase(w, "true"))
      out += "TRUE";
    else if (base::equalsNoCase(w, "false"))
      out += "FALSE";
    else
      out += w;
    i = j;
  }
}

// An MFString written with single quotes: each '...' becomes "...".
void appendSingleQuoted(std::string& out, std::string_view s) {
  bool in = false;
  for (char c : s) {
    if (c == '\'') {
      out += '"';
      in = !in;
    } else if (c == '"' && in) {
      out += "\\\"";
    } else {
      out += c;
    }
  }
  if (in) out += '"';
}

// The bytes a Classic VRML identifier cannot hold, as a table.
constexpr std::array<bool, 256> kXmlIdentBad = [] {
  std::array<bool, 256> t{};
  for (std::size_t u = 0; u < t.size(); ++u) {
    const char c = static_cast<char>(u);
    t[u] = u <= 0x20 || u == 0x7f || c == '"' || c == '#' || c == '\'' || c == ',' || c == '.' ||
           c == '[' || c == '\\' || c == ']' || c == '{' || c == '}';
  }
  return t;
}();

bool xmlIdentBad(char c) {
  return kXmlIdentBad[static_cast<unsigned char>(c)];
}

}  // namespace

void appendQuoted(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

std::string xmlValueToClassic(FieldType t, std::string_view xml, std::string& warning) {
  std::string out;
  appendXmlValueAsClassic(out, t, xml, warning);
  return out;
}

void appendXmlValueAsClassic(std::string& out, FieldType t, std::string_view xml,
                             std::string& warning) {
  warning.clear();
  switch (t) {
    case FieldType::SFString:
      appendQuoted(out, xml);
      return;
    case FieldType::MFString: {
      const std::string_view v = trim(xml);
      out += "[ ";
      if (v.empty()) {
      } else if (v.front() == '"') {
        out += v;
      } else if (v.front() == '\'') {
        warning = "MFString value written with single quotes: read as double-quoted strings";
        appendSingleQuoted(out, v);
      } else {
        warning = "MFString value without quotes: read as one string";
        appendQuoted(out, v);
      }
      out += " ]";
      return;
    }
    case FieldType::SFBool:
      appendBooleans(out, trim(xml));
      return;
    case FieldType::MFBool:
      out += "[ ";
      appendBooleans(out, trim(xml));
      out += " ]";
      return;
    case FieldType::SFNode: {
      const std::string_view v = trim(xml);
      out += v.empty() ? std::string_view("NULL") : v;
      return;
    }
    default:
      break;
  }
  if (isMultiValued(t)) {
    out += "[ ";
    out += xml;
    out += " ]";
    return;
  }
  out += xml;
}

// A DEF/PROTO name as Classic VRML can write it (clause 5.2.3 of ISO/IEC 19776-2: no
// spaces, quotes, '#', ',', '.', brackets or backslash; not starting with a digit or
// sign). XML IDs such as "Cube.001" are written "Cube_001".
void appendXmlIdent(std::string& out, std::string_view s) {
  if (s.empty() || (s[0] >= '0' && s[0] <= '9') || s[0] == '+' || s[0] == '-') out += '_';
  bool clean = true;
  for (char c : s) clean &= !xmlIdentBad(c);
  if (clean) {
    out += s;  // the usual case: one append
    return;
  }
  for (char c : s) out += xmlIdentBad(c) ? '_' : c;
}

std::string xmlIdent(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 1);
  appendXmlIdent(out, s);
  return out;
}

// The Classic text of a field type's default value (for a <field> without value).
std::string classicDefaultText(FieldType t) {
  if (isMultiValued(t)) return "[ ]";
  switch (t) {
    case FieldType::SFBool:
      return "FALSE";
    case FieldType::SFString:
      return "\"\"";
    case FieldType::SFRotation:
      return "0 0 1 0";
    case FieldType::SFImage:
      return "0 0 0";
    case FieldType::SFNode:
      return "NULL";
    case FieldType::SFMatrix3f:
    case FieldType::SFMatrix3d:
      return "1 0 0 0 1 0 0 0 1";
    case FieldType::SFMatrix4f:
    case FieldType::SFMatrix4d:
      return "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";
    case FieldType::SFVec2f:
    case FieldType::SFVec2d:
      return "0 0";
    case FieldType::SFColor:
    case FieldType::SFVec3f:
    case FieldType::SFVec3d:
      return "0 0 0";
    case FieldType::SFVec4f:
    case FieldType::SFVec4d:
    case FieldType::SFColorRGBA:
      return "0 0 0 0";
    default:
      return "0";
  }
}

bool accessTakesValue(std::string_view access) {
  return access != "inputOnly" && access != "outputOnly" && access != "eventIn" &&
         access != "eventOut";
}

namespace {

// n.find(':') != npos for short names, without a call to memchr.
bool hasColon(std::string_view n) {
  for (char c : n)
    if (c == ':') return true;
  return false;
}

}  // namespace

bool xmlIgnoredAttribute(std::string_view n) {
  if (n.empty()) return false;
  switch (n.front()) {  // (most attributes are fields: decided by their first letter)
    case 'D':
      return sameName(n, "DEF");
    case 'U':
      return sameName(n, "USE");
    case 'c':
      return sameName(n, "containerField") || sameName(n, "class") || hasColon(n);
    case 'i':
      return sameName(n, "id") || hasColon(n);
    case 's':
      return sameName(n, "style") || hasColon(n);
    case 'x':
      return n.starts_with("xmlns") || hasColon(n);
    default:
      return hasColon(n);
  }
}

// Whether `text` starts with a URL scheme ("ecmascript:", "data:", "http:").
bool hasUrlScheme(std::string_view text) {
  if (text.empty() || !((text[0] >= 'a' && text[0] <= 'z') || (text[0] >= 'A' && text[0] <= 'Z')))
    return false;
  for (std::size_t i = 1; i < text.size() && i < 40; ++i) {
    const char c = text[i];
    if (c == ':') return true;
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '+' || c == '-' || c == '.';
    if (!ok) return false;
  }
  return false;
}

}  // namespace gs::vrml::parsing
