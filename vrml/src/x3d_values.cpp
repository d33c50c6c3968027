#include "x3d_values.hpp"

#include "base/text.hpp"

namespace gs::vrml::parsing {

namespace {

std::string_view trim(std::string_view s) {
  const auto ws = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (!s.empty() && ws(s.front())) s.remove_prefix(1);
  while (!s.empty() && ws(s.back())) s.remove_suffix(1);
  return s;
}

// true/false (any case) as TRUE/FALSE; other words as written.
std::string booleans(std::string_view s) {
  std::string out;
  out.reserve(s.size());
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
  return out;
}

// An MFString written with single quotes: each '...' becomes "...".
std::string singleQuoted(std::string_view s) {
  std::string out;
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
  return out;
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
  warning.clear();
  std::string out;
  switch (t) {
    case FieldType::SFString:
      appendQuoted(out, xml);
      return out;
    case FieldType::MFString: {
      const std::string_view v = trim(xml);
      out = "[ ";
      if (v.empty()) {
      } else if (v.front() == '"') {
        out += v;
      } else if (v.front() == '\'') {
        warning = "MFString value written with single quotes: read as double-quoted strings";
        out += singleQuoted(v);
      } else {
        warning = "MFString value without quotes: read as one string";
        appendQuoted(out, v);
      }
      out += " ]";
      return out;
    }
    case FieldType::SFBool:
      return booleans(trim(xml));
    case FieldType::MFBool:
      return "[ " + booleans(trim(xml)) + " ]";
    case FieldType::SFNode: {
      const std::string_view v = trim(xml);
      return v.empty() ? std::string("NULL") : std::string(v);
    }
    default:
      break;
  }
  if (isMultiValued(t)) {
    out = "[ ";
    out += xml;
    out += " ]";
    return out;
  }
  return std::string(xml);
}

}  // namespace gs::vrml::parsing
