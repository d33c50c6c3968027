// X3D JSON encoding -> XML text -> Classic VRML text (see x3d_json.hpp). The document is
// parsed by nlohmann-json (ordered, so keys keep their order: head's COMPONENT before
// UNIT before META) after a scan that bounds its nesting and records where each object
// starts; then it is walked once, writing one XML element per JSON object that stands
// for an element:
//   {"Transform": {...}}        -> <Transform ...> (the key names the element)
//   "@translation": [0, 1, 0]   -> translation="0 1 0" (MFString arrays as "a" "b")
//   "-children": [{...}, ...]   -> child elements with containerField="children"
//   "field": [{...}], "IS": {}  -> child elements named by the key
//   "#sourceCode": "..." / [..] -> the element's text (lines joined by line ends)
//   "#comment" and other "#" keys, and non-prefixed keys with plain values -> ignored
// Locations: each Classic line is mapped back to the JSON line and column where its
// node's object starts (for a node, the '{' of the object that names its type). When the
// scan and the parsed document disagree about the objects (duplicate keys), every line
// is mapped to line 1 column 1; structural errors name their JSON path in any case.
#include "x3d_json.hpp"

#include "x3d_xml.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace gs::vrml::parsing {

namespace {

using Json = nlohmann::ordered_json;

bool jsonSpace(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// An element or attribute name XML accepts: [A-Za-z_:][A-Za-z0-9_.:-]*, other bytes as '_'.
std::string xmlName(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 1);
  for (char c : s) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '.' || c == ':' || c == '-';
    out += ok ? c : '_';
  }
  if (out.empty() || !((out[0] >= 'a' && out[0] <= 'z') || (out[0] >= 'A' && out[0] <= 'Z') ||
                       out[0] == '_' || out[0] == ':'))
    out.insert(out.begin(), '_');
  return out;
}

// Appends `s` (valid UTF-8: nlohmann checked it) as XML character data or attribute
// text. Characters XML 1.0 cannot hold (controls but tab and line ends, U+FFFE, U+FFFF)
// become '?'; in attributes, tab and line ends are written as references so that they
// survive attribute-value normalization.
void appendXmlText(std::string& out, std::string_view s, bool attribute) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    const auto u = static_cast<unsigned char>(c);
    if (u == 0xEF && i + 2 < s.size() && static_cast<unsigned char>(s[i + 1]) == 0xBF &&
        (static_cast<unsigned char>(s[i + 2]) == 0xBE ||
         static_cast<unsigned char>(s[i + 2]) == 0xBF)) {
      out += '?';
      i += 2;
      continue;
    }
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += attribute ? "&quot;" : "\"";
        break;
      case '\t':
      case '\n':
      case '\r':
        if (attribute)
          out += c == '\t' ? "&#9;" : c == '\n' ? "&#10;" : "&#13;";
        else
          out += c;
        break;
      default:
        out += (u < 0x20 || u == 0x7f) ? '?' : c;
    }
  }
}

// Elements whose children take no containerField: the XML encoding's structure.
bool structural(std::string_view n) {
  return n == "X3D" || n == "head" || n == "Scene" || n == "ProtoBody" || n == "field" ||
         n == "fieldValue" || n == "ProtoInterface" || n == "IS" || n == "connect";
}

// Elements that are statements, not nodes (no containerField of their own).
bool statementElement(std::string_view n) {
  return n == "ROUTE" || n == "IMPORT" || n == "EXPORT" || n == "ProtoDeclare" ||
         n == "ExternProtoDeclare" || n == "component" || n == "unit" || n == "meta";
}

}  // namespace

struct JsonToClassic::Impl {
  Impl(std::string& o, std::string u, int nesting)
      : out(o),
        url(std::move(u)),
        maxNesting(std::max(nesting, 1)),
        maxDepth(3 * (maxNesting + 8)) {
    origin.m = this;
  }

  std::string& out;
  std::string url;
  int maxNesting;
  int maxDepth;  // JSON arrays and objects: about three per node level
  std::unique_ptr<XmlToClassic> xml;
  std::string xmlText;
  bool failed = false;
  Diagnostic fatal;
  std::vector<Diagnostic> problems;  // structural, at JSON locations

  // Where the JSON's objects start (byte offsets, in document order) and its lines.
  std::vector<std::size_t> objectStarts;
  std::vector<std::size_t> lineStarts;
  std::unordered_map<const Json*, std::size_t> objectIndex;  // -> objectStarts
  bool positionsAgree = false;
  // XML line (index; line 1 is empty) -> JSON line and column.
  std::vector<std::pair<int, int>> xmlLines{{0, 0}, {0, 0}};
  std::pair<int, int> here{1, 1};  // the JSON location of the element being written

  // The parser's locations: through the XML's onto the JSON's.
  struct Origin final : TextOrigin {
    Impl* m = nullptr;
    std::pair<int, int> at(std::size_t offset) override {
      if (!m->xml) return {0, 0};
      return m->jsonOfXml(m->xml->xmlLocationAt(offset).first);
    }
  } origin;

  std::pair<int, int> lineColumn(std::size_t offset) const {
    auto it = std::upper_bound(lineStarts.begin(), lineStarts.end(), offset);
    const std::size_t line = static_cast<std::size_t>(it - lineStarts.begin());
    const std::size_t start = line > 0 ? lineStarts[line - 1] : 0;
    return {static_cast<int>(std::min<std::size_t>(line, 1u << 30)),
            static_cast<int>(std::min<std::size_t>(offset - start + 1, 1u << 30))};
  }

  std::pair<int, int> locationOf(const Json& j) const {
    if (!positionsAgree) return {1, 1};
    auto it = objectIndex.find(&j);
    if (it == objectIndex.end()) return here;
    return lineColumn(objectStarts[it->second]);
  }

  void fail(std::pair<int, int> at, std::string message) {
    failed = true;
    fatal = Diagnostic{Severity::error, {url, at.first, at.second}, std::move(message)};
  }

  void problem(std::string_view path, std::string message) {
    problems.push_back(Diagnostic{Severity::error,
                                  {url, here.first, here.second},
                                  "X3D JSON: " + std::string(path) + " " + std::move(message)});
  }

  // One pass over the bytes: the nesting bound, the objects' starts, the line starts.
  bool scan(std::string_view s) {
    lineStarts.push_back(0);
    int depth = 0;
    bool inString = false;
    for (std::size_t i = 0; i < s.size(); ++i) {
      const char c = s[i];
      if (c == '\n') lineStarts.push_back(i + 1);
      if (inString) {
        if (c == '\\')
          ++i;  // (an escaped line end is a syntax error nlohmann reports)
        else if (c == '"')
          inString = false;
        continue;
      }
      if (c == '"') {
        inString = true;
      } else if (c == '{' || c == '[') {
        if (++depth > maxDepth) {
          fail(lineColumn(i), "JSON nested deeper than " + std::to_string(maxDepth) +
                                  " levels (ParseLimits::maxNesting)");
          return false;
        }
        if (c == '{') objectStarts.push_back(i);
      } else if ((c == '}' || c == ']') && depth > 0) {
        --depth;
      }
    }
    return true;
  }

  // Numbers the parsed document's objects in document order (as scan() saw them).
  void number(const Json& j) {
    if (j.is_object()) {
      objectIndex.emplace(&j, objectIndex.size());
      for (const auto& [k, v] : j.items()) number(v);
    } else if (j.is_array()) {
      for (const auto& v : j) number(v);
    }
  }

  // ---- XML output ----------------------------------------------------------------------

  void newLine() {
    xmlText += '\n';
    xmlLines.push_back(here);
  }

  // The attribute text of a JSON value: arrays flattened, strings in arrays quoted as an
  // MFString, numbers as nlohmann writes them (shortest round trip).
  bool appendValue(std::string& text, const Json& v, bool inArray) {
    switch (v.type()) {
      case Json::value_t::string: {
        const auto& s = v.get_ref<const std::string&>();
        if (!inArray) {
          text += s;
          return true;
        }
        text += '"';
        for (char c : s) {
          if (c == '"' || c == '\\') text += '\\';
          text += c;
        }
        text += '"';
        return true;
      }
      case Json::value_t::boolean:
        text += v.get<bool>() ? "true" : "false";
        return true;
      case Json::value_t::null:
        return true;
      case Json::value_t::array: {
        bool first = true;
        for (const auto& e : v) {
          if (!first) text += ' ';
          first = false;
          if (!appendValue(text, e, true)) return false;
        }
        return true;
      }
      case Json::value_t::object:
      case Json::value_t::binary:
      case Json::value_t::discarded:
        return false;
      default:
        text += v.dump();
        return true;
    }
  }

  // Element `name` from the object `body`; `container` is the containerField it is given
  // (empty: none). `at` is the object that names it (its location).
  void element(std::string_view name, const Json& body, const std::string& container,
               const Json& at, std::string& path) {
    if (!body.is_object()) {
      problem(path, "is not an object: ignored");
      return;
    }
    const auto saved = here;
    here = locationOf(at);
    const std::string tag = xmlName(name);
    newLine();
    xmlText += '<' + tag;
    std::unordered_set<std::string> names;
    const bool takesContainer = !container.empty() && !statementElement(tag);
    for (const auto& [k, v] : body.items()) {
      if (k.size() < 2 || k[0] != '@') continue;
      const std::string attr = xmlName(std::string_view(k).substr(1));
      if (takesContainer && attr == "containerField") continue;
      if (!names.insert(attr).second) continue;
      std::string text;
      if (!appendValue(text, v, false)) {
        const std::size_t n = path.size();
        path += "." + k;
        problem(path, "holds an object, not a field value: ignored");
        path.resize(n);
        continue;
      }
      xmlText += ' ' + attr + "=\"";
      appendXmlText(xmlText, text, true);
      xmlText += '"';
    }
    if (takesContainer) {
      xmlText += " containerField=\"";
      appendXmlText(xmlText, container, true);
      xmlText += '"';
    }
    xmlText += '>';
    const bool childStructure = structural(tag);
    for (const auto& [k, v] : body.items()) {
      if (k.empty() || k[0] == '@') continue;
      const std::size_t n = path.size();
      path += "." + k;
      if (k[0] == '#') {
        if (k == "#sourceCode") sourceCode(v, path);
      } else if (k[0] == '-') {
        nodes(v, childStructure ? std::string() : k.substr(1), path);
      } else if (v.is_object()) {
        element(k, v, {}, v, path);
      } else if (v.is_array()) {
        for (std::size_t i = 0; i < v.size(); ++i) {
          const std::size_t m = path.size();
          path += "[" + std::to_string(i) + "]";
          element(k, v[i], {}, v[i], path);
          path.resize(m);
        }
      }  // else: bookkeeping such as "encoding" or "JSON schema"
      path.resize(n);
    }
    xmlText += "</" + tag + '>';
    here = saved;
  }

  // The value of a "-field" key: one object or an array of objects, each naming nodes.
  void nodes(const Json& v, const std::string& container, std::string& path) {
    auto one = [&](const Json& item) {
      if (!item.is_object()) {
        problem(path, "is not an object: ignored");
        return;
      }
      for (const auto& [k, body] : item.items()) {
        if (k.starts_with('#')) continue;  // {"#comment": "..."}
        const std::size_t n = path.size();
        path += "." + k;
        element(k, body, container, item, path);
        path.resize(n);
      }
    };
    if (!v.is_array()) {
      one(v);
      return;
    }
    for (std::size_t i = 0; i < v.size(); ++i) {
      const std::size_t n = path.size();
      path += "[" + std::to_string(i) + "]";
      one(v[i]);
      path.resize(n);
    }
  }

  void sourceCode(const Json& v, std::string_view path) {
    std::string text;
    if (v.is_string()) {
      text = v.get_ref<const std::string&>();
    } else if (v.is_array()) {
      for (const auto& line : v) {
        if (!line.is_string()) {
          problem(path, "holds a line that is not a string: ignored");
          return;
        }
        if (!text.empty()) text += '\n';
        text += line.get_ref<const std::string&>();
      }
    } else {
      problem(path, "is neither a string nor an array of strings: ignored");
      return;
    }
    const std::size_t from = xmlText.size();
    appendXmlText(xmlText, text, false);
    for (std::size_t i = from; i < xmlText.size(); ++i)
      if (xmlText[i] == '\n') xmlLines.push_back(here);
  }

  std::pair<int, int> jsonOfXml(int xmlLine) const {
    if (xmlLine <= 0 || static_cast<std::size_t>(xmlLine) >= xmlLines.size()) return {0, 0};
    return xmlLines[static_cast<std::size_t>(xmlLine)];
  }

  bool translate(std::string_view json, Scene& scene) {
    if (!scan(json)) return false;
    Json doc;
    try {
      doc = Json::parse(json.begin(), json.end());
    } catch (const Json::parse_error& e) {
      std::string what = e.what();
      // "[json.exception.parse_error.101] parse error at line 1, column 5: syntax ..."
      if (const std::size_t p = what.find("] "); p != std::string::npos) what.erase(0, p + 2);
      if (what.starts_with("parse error at line"))
        if (const std::size_t p = what.find(": "); p != std::string::npos) what.erase(0, p + 2);
      const std::size_t offset = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, json.size());
      fail(lineColumn(offset), "JSON syntax error: " + what);
      return false;
    } catch (const Json::exception& e) {
      std::string what = e.what();
      if (const std::size_t p = what.find("] "); p != std::string::npos) what.erase(0, p + 2);
      fail({1, 1}, "JSON error: " + what);
      return false;
    }
    number(doc);
    positionsAgree = objectIndex.size() == objectStarts.size();
    if (!doc.is_object() || !doc.contains("X3D") || !doc["X3D"].is_object()) {
      fail({1, 1}, "X3D JSON: the document is no object holding an \"X3D\" object");
      return false;
    }
    std::string path = "X3D";
    element("X3D", doc["X3D"], {}, doc, path);
    doc = Json();  // the XML text is all that is needed now
    xmlText += '\n';
    xml = std::make_unique<XmlToClassic>(out, url, maxNesting);
    xml->feed(xmlText);
    xml->finish();
    const std::size_t from = scene.diagnostics.items.size();
    xml->addWarnings(scene);  // at XML locations
    auto& items = scene.diagnostics.items;
    for (std::size_t i = from; i < items.size(); ++i) {
      SourceLocation& l = items[i].location;
      if (l.file != url) continue;
      const auto [line, column] = jsonOfXml(l.line);
      l.line = line;
      l.column = column;
    }
    for (Diagnostic& d : problems) items.push_back(std::move(d));
    problems.clear();
    if (xml->failed()) {
      Diagnostic d = xml->fatalError();
      const auto [line, column] = jsonOfXml(d.location.line);
      d.location.line = line;
      d.location.column = column;
      fail({line, column}, d.message);
      return false;
    }
    return true;
  }
};

bool looksLikeJson(std::string_view text, bool& decided) {
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (jsonSpace(c) || c == 0xEF || c == 0xBB || c == 0xBF) continue;
    decided = true;
    return c == '{';
  }
  decided = false;
  return false;
}

JsonToClassic::JsonToClassic(std::string& out, std::string url, int maxNesting)
    : impl_(std::make_unique<Impl>(out, std::move(url), maxNesting)) {}

JsonToClassic::~JsonToClassic() = default;

bool JsonToClassic::translate(std::string_view json, Scene& scene) {
  return impl_->translate(json, scene);
}

bool JsonToClassic::wroteHeader() const {
  return impl_->xml && impl_->xml->wroteHeader();
}

bool JsonToClassic::failed() const {
  return impl_->failed;
}

const Diagnostic& JsonToClassic::fatalError() const {
  return impl_->fatal;
}

std::pair<int, int> JsonToClassic::jsonLocationAt(std::size_t offset) {
  return impl_->origin.at(offset);
}

TextOrigin& JsonToClassic::origin() {
  return impl_->origin;
}

}  // namespace gs::vrml::parsing
