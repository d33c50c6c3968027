// The JSON writer (ISO/IEC 19776-5): the XML encoding's elements (xmlDocument(),
// writer_xml.cpp) as JSON objects. An attribute is an "@name" key whose value has its JSON
// type (numbers, true / false, strings; an MF or multi-component value an array, an
// MFString an array of strings); the nodes of an MFNode field are "-field": [{"Type":
// {...}}, ...], the node of an SFNode field "-field": {"Type": {...}};
// statements and the nodes of Scene, ProtoBody, <field> and <fieldValue> are "-children";
// other child elements are keys named by the element ("field": [...], "IS": {...}); a
// Script's inline source is "#sourceCode": [lines]. What the reader
// (encodings/src/x3d_json.cpp) reads back to the same scene.
#include "writer_impl.hpp"

#include <cstdio>

namespace gs::vrml::writing {

namespace {

void jsonString(std::string& out, std::string_view s) {
  out += '"';
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (u < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", u);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

void jsonValue(std::string& out, const FieldValue& v) {
  switch (v.type()) {
    case FieldType::SFString:
      jsonString(out, v.get<FieldType::SFString>());
      return;
    case FieldType::MFString: {
      out += '[';
      bool first = true;
      for (const std::string& s : v.get<FieldType::MFString>()) {
        if (!first) out += ", ";
        first = false;
        jsonString(out, s);
      }
      out += ']';
      return;
    }
    case FieldType::SFBool:
      out += v.get<FieldType::SFBool>() ? "true" : "false";
      return;
    case FieldType::MFBool: {
      out += '[';
      bool first = true;
      for (bool b : v.get<FieldType::MFBool>()) {
        if (!first) out += ", ";
        first = false;
        out += b ? "true" : "false";
      }
      out += ']';
      return;
    }
    default:
      break;
  }
  const std::vector<std::string> numbers = numberTokens(v);
  const bool single = !isMultiValued(v.type()) && numbers.size() == 1;
  if (single) {
    out += numbers.front();
    return;
  }
  out += '[';
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    if (i > 0) out += ", ";
    out += numbers[i];
  }
  out += ']';
}

bool structural(std::string_view n) {
  return n == "Scene" || n == "ProtoBody" || n == "field" || n == "fieldValue";
}

bool singleObject(std::string_view n) {
  return n == "ProtoInterface" || n == "ProtoBody" || n == "IS" || n == "head" || n == "Scene";
}

class JsonPrinter {
 public:
  std::string out;

  // The object that is the body of element `e` (its name is the key outside).
  void body(const XElem& e, const std::string& indent) {
    const std::string in = indent + "  ";
    out += "{";
    bool first = true;
    auto key = [&](std::string_view k) {
      out += first ? "\n" : ",\n";
      first = false;
      out += in;
      jsonString(out, k);
      out += ": ";
    };
    if (e.name == "X3D") {
      key("encoding");
      out += "\"UTF-8\"";
    }
    for (const XAttr& a : e.attrs) {
      key("@" + a.name);
      if (a.value != nullptr)
        jsonValue(out, *a.value);
      else
        jsonString(out, a.text);
    }
    if (!e.source.empty()) {
      key("#sourceCode");
      out += "[";
      std::string_view s = e.source;
      bool firstLine = true;
      while (true) {
        const std::size_t nl = s.find('\n');
        out += firstLine ? "\n" : ",\n";
        firstLine = false;
        out += in + "  ";
        jsonString(out, s.substr(0, nl));
        if (nl == std::string_view::npos) break;
        s.remove_prefix(nl + 1);
      }
      out += "\n" + in + "]";
    }
    if (structural(e.name)) {
      if (!e.children.empty()) {
        key("-children");
        list(e.children, 0, e.children.size(), in);
      }
    } else {
      // Children grouped by key, in order of first appearance (a field's nodes are
      // contiguous, so no node moves across another field's).
      std::vector<bool> done(e.children.size(), false);
      for (std::size_t i = 0; i < e.children.size(); ++i) {
        if (done[i]) continue;
        const XElem& c = e.children[i];
        const std::string k = c.node ? "-" + c.containerField : c.name;
        std::vector<const XElem*> group;
        for (std::size_t j = i; j < e.children.size(); ++j) {
          const XElem& d = e.children[j];
          if (done[j] || (d.node ? "-" + d.containerField : d.name) != k) continue;
          done[j] = true;
          group.push_back(&d);
        }
        key(k);
        if (c.node && group.size() == 1 && c.sfnode) {
          // An SFNode field's value: {"Type": {...}} (ISO/IEC 19776-5 5.4).
          out += "{";
          jsonString(out, c.name);
          out += ": ";
          body(c, in);
          out += "}";
        } else if (c.node) {
          nodes(group, in);
        } else if (group.size() == 1 && singleObject(c.name)) {
          body(c, in);
        } else {
          out += "[";
          for (std::size_t g = 0; g < group.size(); ++g) {
            out += g == 0 ? "\n" : ",\n";
            out += in + "  ";
            body(*group[g], in + "  ");
          }
          out += "\n" + in + "]";
        }
      }
    }
    out += first ? "}" : "\n" + indent + "}";
  }

  // [{"Name": {...}}, ...]
  void nodes(const std::vector<const XElem*>& items, const std::string& indent) {
    out += "[";
    for (std::size_t i = 0; i < items.size(); ++i) {
      out += i == 0 ? "\n" : ",\n";
      out += indent + "  {";
      jsonString(out, items[i]->name);
      out += ": ";
      body(*items[i], indent + "  ");
      out += "}";
    }
    out += "\n" + indent + "]";
  }

  void list(const std::vector<XElem>& items, std::size_t from, std::size_t to,
            const std::string& indent) {
    std::vector<const XElem*> p;
    for (std::size_t i = from; i < to; ++i) p.push_back(&items[i]);
    nodes(p, indent);
  }
};

}  // namespace

std::string printJson(const WDocument& doc) {
  std::deque<FieldValue> owned;
  XElem x3d = xmlDocument(doc, owned);
  // The JSON encoding's own bookkeeping beside the XML's attributes.
  JsonPrinter p;
  p.out = "{ \"X3D\": ";
  p.body(x3d, "");
  p.out += "\n}\n";
  return std::move(p.out);
}

}  // namespace gs::vrml::writing
