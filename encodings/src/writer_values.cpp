// Field values as text for the writers (writer_impl.hpp): the Classic encodings' syntax
// (ISO/IEC 14772-1 clause 5, ISO/IEC 19776-2 clause 5), the XML encoding's attribute
// syntax (ISO/IEC 19776-1 clause 5) and the scalars the JSON encoding writes as numbers
// (ISO/IEC 19776-5 clause 5). Numbers print with std::to_chars' shortest round trip.
#include "writer_impl.hpp"

#include <charconv>
#include <cstdio>

namespace gs::vrml::writing {

namespace {

template <class T>
void appendInt(std::string& out, T i) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, i);
  out.append(buf, r.ptr);
}

void appendHex(std::string& out, std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%X", v);
  out += buf;
}

void appendQuotedString(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

template <class V>
void appendVec(std::string& out, const V& v, int n) {
  for (int i = 0; i < n; ++i) {
    if (i > 0) out += ' ';
    appendNumber(out, v[i]);
  }
}

template <class M>
void appendMatrix(std::string& out, const M& m, int n) {
  // Row by row (X3D clause 5.3.10); glm keeps columns: m[column][row].
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) {
      if (r + c > 0) out += ' ';
      appendNumber(out, m[c][r]);
    }
}

void appendImage(std::string& out, const SFImage& im) {
  appendInt(out, im.width);
  out += ' ';
  appendInt(out, im.height);
  out += ' ';
  appendInt(out, im.components);
  for (std::uint32_t p : im.pixels) {
    out += ' ';
    appendHex(out, p);
  }
}

// The text of each element of `v` (one for an SF value). `xml`: booleans as true/false.
std::vector<std::string> elements(const FieldValue& v, bool xml) {
  std::vector<std::string> out;
  auto one = [&](auto&& f) {
    out.emplace_back();
    f(out.back());
  };
  auto boolText = [xml](bool b) { return xml ? (b ? "true" : "false") : (b ? "TRUE" : "FALSE"); };
  auto list = [&](const auto& items, auto&& f) {
    out.reserve(items.size());
    for (const auto& e : items) {
      out.emplace_back();
      f(out.back(), e);
    }
  };
  auto num = [](std::string& s, auto x) { appendNumber(s, x); };
  auto v2 = [](std::string& s, const auto& x) { appendVec(s, x, 2); };
  auto v3 = [](std::string& s, const auto& x) { appendVec(s, x, 3); };
  auto v4 = [](std::string& s, const auto& x) { appendVec(s, x, 4); };
  switch (v.type()) {
    case FieldType::SFBool:
      one([&](std::string& s) { s = boolText(v.get<FieldType::SFBool>()); });
      break;
    case FieldType::SFColor:
      one([&](std::string& s) { v3(s, v.get<FieldType::SFColor>()); });
      break;
    case FieldType::SFFloat:
      one([&](std::string& s) { num(s, v.get<FieldType::SFFloat>()); });
      break;
    case FieldType::SFImage:
      one([&](std::string& s) { appendImage(s, v.get<FieldType::SFImage>()); });
      break;
    case FieldType::SFInt32:
      one([&](std::string& s) { appendInt(s, v.get<FieldType::SFInt32>()); });
      break;
    case FieldType::SFRotation:
      one([&](std::string& s) { v4(s, v.get<FieldType::SFRotation>()); });
      break;
    case FieldType::SFString:
      one([&](std::string& s) { appendQuotedString(s, v.get<FieldType::SFString>()); });
      break;
    case FieldType::SFTime:
      one([&](std::string& s) { num(s, v.get<FieldType::SFTime>()); });
      break;
    case FieldType::SFVec2f:
      one([&](std::string& s) { v2(s, v.get<FieldType::SFVec2f>()); });
      break;
    case FieldType::SFVec3f:
      one([&](std::string& s) { v3(s, v.get<FieldType::SFVec3f>()); });
      break;
    case FieldType::MFColor:
      list(v.get<FieldType::MFColor>(), v3);
      break;
    case FieldType::MFFloat:
      list(v.get<FieldType::MFFloat>(), num);
      break;
    case FieldType::MFInt32:
      list(v.get<FieldType::MFInt32>(), [](std::string& s, std::int32_t i) { appendInt(s, i); });
      break;
    case FieldType::MFRotation:
      list(v.get<FieldType::MFRotation>(), v4);
      break;
    case FieldType::MFString:
      list(v.get<FieldType::MFString>(),
           [](std::string& s, const std::string& e) { appendQuotedString(s, e); });
      break;
    case FieldType::MFTime:
      list(v.get<FieldType::MFTime>(), num);
      break;
    case FieldType::MFVec2f:
      list(v.get<FieldType::MFVec2f>(), v2);
      break;
    case FieldType::MFVec3f:
      list(v.get<FieldType::MFVec3f>(), v3);
      break;
    case FieldType::SFDouble:
      one([&](std::string& s) { num(s, v.get<FieldType::SFDouble>()); });
      break;
    case FieldType::SFVec2d:
      one([&](std::string& s) { v2(s, v.get<FieldType::SFVec2d>()); });
      break;
    case FieldType::SFVec3d:
      one([&](std::string& s) { v3(s, v.get<FieldType::SFVec3d>()); });
      break;
    case FieldType::SFVec4f:
      one([&](std::string& s) { v4(s, v.get<FieldType::SFVec4f>()); });
      break;
    case FieldType::SFVec4d:
      one([&](std::string& s) { v4(s, v.get<FieldType::SFVec4d>()); });
      break;
    case FieldType::SFColorRGBA:
      one([&](std::string& s) { v4(s, v.get<FieldType::SFColorRGBA>()); });
      break;
    case FieldType::SFMatrix3f:
      one([&](std::string& s) { appendMatrix(s, v.get<FieldType::SFMatrix3f>(), 3); });
      break;
    case FieldType::SFMatrix3d:
      one([&](std::string& s) { appendMatrix(s, v.get<FieldType::SFMatrix3d>(), 3); });
      break;
    case FieldType::SFMatrix4f:
      one([&](std::string& s) { appendMatrix(s, v.get<FieldType::SFMatrix4f>(), 4); });
      break;
    case FieldType::SFMatrix4d:
      one([&](std::string& s) { appendMatrix(s, v.get<FieldType::SFMatrix4d>(), 4); });
      break;
    case FieldType::MFBool:
      for (bool b : v.get<FieldType::MFBool>()) out.emplace_back(boolText(b));
      break;
    case FieldType::MFDouble:
      list(v.get<FieldType::MFDouble>(), num);
      break;
    case FieldType::MFImage:
      list(v.get<FieldType::MFImage>(), appendImage);
      break;
    case FieldType::MFVec2d:
      list(v.get<FieldType::MFVec2d>(), v2);
      break;
    case FieldType::MFVec3d:
      list(v.get<FieldType::MFVec3d>(), v3);
      break;
    case FieldType::MFVec4f:
      list(v.get<FieldType::MFVec4f>(), v4);
      break;
    case FieldType::MFVec4d:
      list(v.get<FieldType::MFVec4d>(), v4);
      break;
    case FieldType::MFColorRGBA:
      list(v.get<FieldType::MFColorRGBA>(), v4);
      break;
    case FieldType::MFMatrix3f:
      list(v.get<FieldType::MFMatrix3f>(),
           [](std::string& s, const auto& m) { appendMatrix(s, m, 3); });
      break;
    case FieldType::MFMatrix3d:
      list(v.get<FieldType::MFMatrix3d>(),
           [](std::string& s, const auto& m) { appendMatrix(s, m, 3); });
      break;
    case FieldType::MFMatrix4f:
      list(v.get<FieldType::MFMatrix4f>(),
           [](std::string& s, const auto& m) { appendMatrix(s, m, 4); });
      break;
    case FieldType::MFMatrix4d:
      list(v.get<FieldType::MFMatrix4d>(),
           [](std::string& s, const auto& m) { appendMatrix(s, m, 4); });
      break;
    case FieldType::SFNode:
    case FieldType::MFNode:
      break;
  }
  return out;
}

}  // namespace

void appendNumber(std::string& out, float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  out.append(buf, r.ptr);
}

void appendNumber(std::string& out, double d) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, d);
  out.append(buf, r.ptr);
}

std::string classicValue(const FieldValue& v, const std::string& indent) {
  std::vector<std::string> e = elements(v, false);
  if (!isMultiValued(v.type())) return e.empty() ? std::string() : std::move(e.front());
  if (e.empty()) return "[ ]";
  std::size_t total = 0;
  for (const std::string& x : e) total += x.size() + 2;
  if (total < 60) {
    std::string out = "[ ";
    for (std::size_t i = 0; i < e.size(); ++i) out += (i > 0 ? ", " : "") + e[i];
    return out + " ]";
  }
  std::string out = "[";
  std::size_t lineLength = 0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    // About 100 columns a line for long lists; short ones stay on one line.
    if (i == 0 || lineLength + e[i].size() > 90) {
      out += '\n';
      out += indent;
      out += "  ";
      lineLength = indent.size() + 2;
    } else {
      out += ' ';
      ++lineLength;
    }
    out += e[i];
    lineLength += e[i].size() + 1;
    if (i + 1 < e.size()) out += ',';
  }
  out += '\n';
  out += indent;
  out += ']';
  return out;
}

std::string xmlValue(const FieldValue& v) {
  if (v.type() == FieldType::SFString) return v.get<FieldType::SFString>();
  std::vector<std::string> e = elements(v, true);
  std::string out;
  const bool commas =
      isMultiValued(v.type()) && v.type() != FieldType::MFString && v.type() != FieldType::MFBool &&
      elementType(v.type()) != FieldType::SFFloat && elementType(v.type()) != FieldType::SFInt32 &&
      elementType(v.type()) != FieldType::SFTime && elementType(v.type()) != FieldType::SFDouble;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (i > 0) out += commas ? ", " : " ";
    out += e[i];
  }
  return out;
}

std::vector<std::string> numberTokens(const FieldValue& v) {
  std::vector<std::string> out;
  for (const std::string& text : elements(v, true)) {
    std::size_t p = 0;
    while (p < text.size()) {
      while (p < text.size() && (text[p] == ' ' || text[p] == ',')) ++p;
      if (p >= text.size()) break;
      std::size_t q = p;
      while (q < text.size() && text[q] != ' ' && text[q] != ',') ++q;
      std::string token = text.substr(p, q - p);
      if (token.size() > 2 && token[0] == '0' && (token[1] == 'x' || token[1] == 'X')) {
        std::uint32_t h = 0;
        std::from_chars(token.data() + 2, token.data() + token.size(), h, 16);
        token.clear();
        appendInt(token, h);
      }
      out.push_back(std::move(token));
      p = q;
    }
  }
  return out;
}

}  // namespace gs::vrml::writing
