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

}  // namespace gs::vrml::parsing
