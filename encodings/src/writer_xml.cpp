// The XML writer (ISO/IEC 19776-1:2015): the document of writer_model.cpp as elements
// (xmlDocument(), which the JSON printer shares), printed with attribute values escaped
// (clause 5.2: &amp; &lt; &gt; &quot; and character references for tab and line ends, so
// that attribute-value normalization keeps them), MFString values quoted per clause 5.3.2
// (each string in double quotes, '"' and '\' escaped by '\'), a Script's inline source in
// CDATA (clause 5.3.9) when it reads back unchanged, PROTOs as ProtoDeclare /
// ExternProtoDeclare / ProtoInstance with fieldValue and IS / connect (clauses 5.3.6-5.3.8).
#include "writer_impl.hpp"

namespace gs::vrml::writing {

namespace {

std::string_view x3dAccess(AccessType a) {
  return x3dAccessTypeName(a);
}

class ElementBuilder {
 public:
  ElementBuilder(const WDocument& doc, std::deque<FieldValue>& owned) : doc_(doc), owned_(owned) {}

  XElem document() {
    XElem x3d;
    x3d.name = "X3D";
    if (!doc_.profile.empty()) x3d.attrs.push_back({"profile", doc_.profile, nullptr});
    x3d.attrs.push_back({"version", doc_.version, nullptr});
    x3d.attrs.push_back({"xmlns:xsd", "http://www.w3.org/2001/XMLSchema-instance", nullptr});
    x3d.attrs.push_back({"xsd:noNamespaceSchemaLocation",
                         "https://www.web3d.org/specifications/x3d-" + doc_.version + ".xsd",
                         nullptr});
    XElem head;
    head.name = "head";
    for (const auto& [name, level] : doc_.components) {
      XElem c;
      c.name = "component";
      c.attrs.push_back({"name", name, nullptr});
      c.attrs.push_back({"level", std::to_string(level), nullptr});
      head.children.push_back(std::move(c));
    }
    for (const X3dUnit& u : doc_.units) {
      XElem e;
      e.name = "unit";
      std::string factor;
      appendNumber(factor, u.conversionFactor);
      e.attrs.push_back({"category", u.category, nullptr});
      e.attrs.push_back({"name", u.name, nullptr});
      e.attrs.push_back({"conversionFactor", factor, nullptr});
      head.children.push_back(std::move(e));
    }
    for (const auto& [name, content] : doc_.meta) {
      XElem m;
      m.name = "meta";
      m.attrs.push_back({"name", name, nullptr});
      m.attrs.push_back({"content", content, nullptr});
      head.children.push_back(std::move(m));
    }
    if (!head.children.empty()) x3d.children.push_back(std::move(head));
    XElem scene;
    scene.name = "Scene";
    for (const WStatement& s : doc_.statements) scene.children.push_back(statement(s));
    x3d.children.push_back(std::move(scene));
    return x3d;
  }

 private:
  const WDocument& doc_;
  std::deque<FieldValue>& owned_;

  XElem statement(const WStatement& s) {
    XElem e;
    switch (s.kind) {
      case WStatement::Kind::node:
        return node(s.node, "", "");
      case WStatement::Kind::proto:
        return proto(*s.proto);
      case WStatement::Kind::route:
        e.name = "ROUTE";
        e.attrs = {{"fromNode", s.route.fromNode, nullptr},
                   {"fromField", s.route.fromField, nullptr},
                   {"toNode", s.route.toNode, nullptr},
                   {"toField", s.route.toField, nullptr}};
        return e;
      case WStatement::Kind::import:
        e.name = "IMPORT";
        e.attrs = {
            {"inlineDEF", s.a, nullptr}, {"importedDEF", s.b, nullptr}, {"AS", s.c, nullptr}};
        return e;
      case WStatement::Kind::exported:
        e.name = "EXPORT";
        e.attrs = {{"localDEF", s.a, nullptr}, {"AS", s.b, nullptr}};
        return e;
    }
    return e;
  }

  XElem proto(const WProto& p) {
    XElem e;
    e.name = p.external ? "ExternProtoDeclare" : "ProtoDeclare";
    e.attrs.push_back({"name", p.name, nullptr});
    if (p.external) {
      FieldValue& urls = owned_.emplace_back(FieldType::MFString);
      if (p.urls != nullptr) urls.get<FieldType::MFString>() = *p.urls;
      e.attrs.push_back({"url", {}, &urls});
      for (const WDecl& d : p.interface) e.children.push_back(fieldDecl(d));
      return e;
    }
    XElem interface;
    interface.name = "ProtoInterface";
    for (const WDecl& d : p.interface) interface.children.push_back(fieldDecl(d));
    if (!interface.children.empty()) e.children.push_back(std::move(interface));
    XElem body;
    body.name = "ProtoBody";
    for (const WStatement& s : p.body) body.children.push_back(statement(s));
    e.children.push_back(std::move(body));
    return e;
  }

  // <field accessType type name [value]> with node children for an SFNode / MFNode value.
  XElem fieldDecl(const WDecl& d) {
    XElem f;
    f.name = "field";
    f.attrs.push_back({"accessType", std::string(x3dAccess(d.access)), nullptr});
    f.attrs.push_back({"type", std::string(fieldTypeName(d.type)), nullptr});
    f.attrs.push_back({"name", d.name, nullptr});
    if (d.isMember.empty() && d.value != nullptr) {
      if (d.type == FieldType::SFNode || d.type == FieldType::MFNode) {
        for (const WNode& n : d.nodes) f.children.push_back(node(n, "", ""));
      } else {
        f.attrs.push_back({"value", {}, d.value});
      }
    }
    return f;
  }

  static XElem connect(const std::string& nodeField, const std::string& protoField) {
    XElem c;
    c.name = "connect";
    c.attrs = {{"nodeField", nodeField, nullptr}, {"protoField", protoField, nullptr}};
    return c;
  }

  // Where the Script source goes: the last url entry, when it has a scheme and reads back
  // unchanged from CDATA (the reader trims the text's ends and appends it to url; XML
  // normalizes line ends in text).
  static bool inlineSource(const std::string& s) {
    const bool scheme = s.starts_with("ecmascript:") || s.starts_with("javascript:") ||
                        s.starts_with("vrmlscript:");
    // XML turns "\r\n" and "\r" in text into "\n" (XML 1.0 clause 2.11).
    if (!scheme || s.find('\r') != std::string::npos) return false;
    const char last = s.back();
    return last != ' ' && last != '\t' && last != '\n' && last != '\r';
  }

  // `n` as the value of field `field` of a node whose X3D type is `parentType` (empty for
  // Scene, ProtoBody, <field> and <fieldValue>).
  XElem node(const WNode& n, const std::string& field, const std::string& parentType) {
    XElem e;
    e.node = true;
    e.containerField = field;
    e.name = n.instance ? "ProtoInstance" : n.typeName;
    if (!field.empty())
      e.explicitContainer = n.instance || field != n.containerDefault || parentType.empty();
    if (n.use) {
      if (n.instance) e.attrs.push_back({"name", n.typeName, nullptr});
      e.attrs.push_back({"USE", n.def, nullptr});
      return e;
    }
    if (n.instance) e.attrs.push_back({"name", n.typeName, nullptr});
    if (!n.def.empty()) e.attrs.push_back({"DEF", n.def, nullptr});
    std::vector<XElem> connects;
    std::vector<XElem> nested;
    for (const WDecl& d : n.decls) {
      e.children.push_back(fieldDecl(d));
      if (!d.isMember.empty()) connects.push_back(connect(d.name, d.isMember));
    }
    const bool script = !n.instance && n.node != nullptr && n.node->type().script;
    for (const WField& f : n.fields) {
      if (!f.isMember.empty()) {
        connects.push_back(connect(f.name, f.isMember));
        continue;
      }
      if (n.instance) {
        XElem fv;
        fv.name = "fieldValue";
        fv.attrs.push_back({"name", f.name, nullptr});
        if (f.type == FieldType::SFNode || f.type == FieldType::MFNode) {
          for (const WNode& c : f.nodes) fv.children.push_back(node(c, "", ""));
        } else {
          fv.attrs.push_back({"value", {}, f.value});
        }
        e.children.push_back(std::move(fv));
        continue;
      }
      if (f.type == FieldType::SFNode || f.type == FieldType::MFNode) {
        for (const WNode& c : f.nodes) {
          nested.push_back(node(c, f.name, n.typeName));
          nested.back().sfnode = f.type == FieldType::SFNode;
        }
        continue;
      }
      if (script && f.name == "url" && f.type == FieldType::MFString) {
        const auto& urls = f.value->get<FieldType::MFString>();
        if (!urls.empty() && inlineSource(urls.back())) {
          e.source = urls.back();
          if (urls.size() > 1) {
            FieldValue& rest = owned_.emplace_back(FieldType::MFString);
            rest.get<FieldType::MFString>().assign(urls.begin(), urls.end() - 1);
            e.attrs.push_back({f.name, {}, &rest});
          }
          continue;
        }
      }
      e.attrs.push_back({f.name, {}, f.value});
    }
    if (!connects.empty()) {
      XElem is;
      is.name = "IS";
      is.children = std::move(connects);
      e.children.push_back(std::move(is));
    }
    for (XElem& c : nested) e.children.push_back(std::move(c));
    return e;
  }
};

void escape(std::string& out, std::string_view s, bool attribute) {
  for (char c : s) {
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
      case '\n':
        out += attribute ? "&#10;" : "\n";
        break;
      case '\r':
        out += "&#13;";
        break;
      case '\t':
        out += attribute ? "&#9;" : "\t";
        break;
      default:
        out += c;
    }
  }
}

void print(std::string& out, const XElem& e, const std::string& indent) {
  out += indent + "<" + e.name;
  for (const XAttr& a : e.attrs) {
    out += ' ' + a.name + "=\"";
    escape(out, a.value != nullptr ? xmlValue(*a.value) : a.text, true);
    out += '"';
  }
  if (e.explicitContainer) {
    out += " containerField=\"";
    escape(out, e.containerField, true);
    out += '"';
  }
  if (e.children.empty() && e.source.empty()) {
    out += "/>\n";
    return;
  }
  out += ">\n";
  if (!e.source.empty()) {
    // "]]>" cannot appear in a CDATA section: split it across two.
    out += "<![CDATA[";
    std::string_view s = e.source;
    for (std::size_t p; (p = s.find("]]>")) != std::string_view::npos; s.remove_prefix(p + 2)) {
      out += s.substr(0, p + 2);
      out += "]]><![CDATA[";
    }
    out += s;
    out += "]]>\n";
  }
  for (const XElem& c : e.children) print(out, c, indent + "  ");
  out += indent + "</" + e.name + ">\n";
}

}  // namespace

XElem xmlDocument(const WDocument& doc, std::deque<FieldValue>& owned) {
  return ElementBuilder(doc, owned).document();
}

std::string printXml(const WDocument& doc) {
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<!DOCTYPE X3D PUBLIC \"ISO//Web3D//DTD X3D " + doc.version +
         "//EN\" \"https://www.web3d.org/specifications/x3d-" + doc.version + ".dtd\">\n";
  std::deque<FieldValue> owned;
  print(out, xmlDocument(doc, owned), "");
  return out;
}

}  // namespace gs::vrml::writing
