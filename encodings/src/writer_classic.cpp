// The Classic writers: VRML97's encoding (ISO/IEC 14772-1:1997 clause 5 and annex A,
// "#VRML V2.0 utf8") and X3D's Classic VRML encoding (ISO/IEC 19776-2:2015, "#X3D V4.0
// utf8" with PROFILE, COMPONENT, META, IMPORT and EXPORT statements); and writeScene(),
// which picks the printer.
#include "writer_impl.hpp"

#include <cctype>

namespace gs::vrml {

namespace writing {

namespace {

class ClassicPrinter {
 public:
  explicit ClassicPrinter(const WDocument& doc) : doc_(doc) {}

  std::string print() {
    if (doc_.x3d) {
      out_ += "#X3D V" + doc_.version + " utf8\n";
      if (!doc_.profile.empty()) out_ += "PROFILE " + doc_.profile + "\n";
      for (const auto& [name, level] : doc_.components)
        out_ += "COMPONENT " + name + ":" + std::to_string(level) + "\n";
      for (const X3dUnit& u : doc_.units) {
        std::string factor;
        appendNumber(factor, u.conversionFactor);
        out_ += "UNIT " + u.category + " " + u.name + " " + factor + "\n";
      }
      for (const auto& [name, content] : doc_.meta)
        out_ += "META " + quoted(name) + " " + quoted(content) + "\n";
    } else {
      out_ += "#VRML V2.0 utf8\n";
    }
    out_ += '\n';
    for (const WStatement& s : doc_.statements) statement(s, "");
    return std::move(out_);
  }

 private:
  const WDocument& doc_;
  std::string out_;

  static std::string quoted(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
      if (c == '"' || c == '\\') q += '\\';
      q += c;
    }
    return q + '"';
  }

  std::string_view access(AccessType a) const {
    return doc_.x3d ? x3dAccessTypeName(a) : accessTypeName(a);
  }

  void statement(const WStatement& s, const std::string& indent) {
    switch (s.kind) {
      case WStatement::Kind::node:
        out_ += indent;
        node(s.node, indent);
        out_ += '\n';
        break;
      case WStatement::Kind::proto:
        proto(*s.proto, indent);
        break;
      case WStatement::Kind::route:
        out_ += indent + "ROUTE " + s.route.fromNode + "." + s.route.fromField + " TO " +
                s.route.toNode + "." + s.route.toField + "\n";
        break;
      case WStatement::Kind::import:
        out_ += indent + "IMPORT " + s.a + "." + s.b + " AS " + s.c + "\n";
        break;
      case WStatement::Kind::exported:
        out_ += indent + "EXPORT " + s.a + " AS " + s.b + "\n";
        break;
    }
  }

  void proto(const WProto& p, const std::string& indent) {
    out_ += indent + (p.external ? "EXTERNPROTO " : "PROTO ") + p.name + " [";
    if (p.interface.empty()) {
      out_ += " ]";
    } else {
      out_ += '\n';
      for (const WDecl& d : p.interface) decl(d, indent + "  ");
      out_ += indent + "]";
    }
    if (p.external) {
      FieldValue urls(FieldType::MFString);
      if (p.urls != nullptr) urls.get<FieldType::MFString>() = *p.urls;
      out_ += ' ' + classicValue(urls, indent) + "\n";
      return;
    }
    out_ += "\n" + indent + "{\n";
    for (const WStatement& s : p.body) statement(s, indent + "  ");
    out_ += indent + "}\n";
  }

  void decl(const WDecl& d, const std::string& indent) {
    out_ += indent;
    out_ += access(d.access);
    out_ += ' ';
    out_ += fieldTypeName(d.type);
    out_ += ' ' + d.name;
    if (!d.isMember.empty()) {
      out_ += " IS " + d.isMember;
    } else if (d.value != nullptr) {
      out_ += ' ';
      value(d.type, d.value, d.nodes, indent);
    }
    out_ += '\n';
  }

  void value(FieldType type, const FieldValue* v, const std::vector<WNode>& nodes,
             const std::string& indent) {
    if (type == FieldType::SFNode) {
      if (nodes.empty())
        out_ += "NULL";
      else
        node(nodes.front(), indent);
    } else if (type == FieldType::MFNode) {
      if (nodes.empty()) {
        out_ += "[ ]";
        return;
      }
      out_ += "[\n";
      for (const WNode& n : nodes) {
        out_ += indent + "  ";
        node(n, indent + "  ");
        out_ += '\n';
      }
      out_ += indent + "]";
    } else if (v != nullptr) {
      out_ += classicValue(*v, indent);
    }
  }

  void node(const WNode& n, const std::string& indent) {
    if (n.use) {
      out_ += "USE " + n.def;
      return;
    }
    if (!n.def.empty()) out_ += "DEF " + n.def + " ";
    out_ += n.typeName;
    if (n.protos.empty() && n.decls.empty() && n.fields.empty()) {
      out_ += " { }";
      return;
    }
    out_ += " {\n";
    const std::string inner = indent + "  ";
    for (const auto& p : n.protos) proto(*p, inner);
    for (const WDecl& d : n.decls) decl(d, inner);
    for (const WField& f : n.fields) {
      out_ += inner + f.name;
      if (!f.isMember.empty()) {
        out_ += " IS " + f.isMember;
      } else {
        out_ += ' ';
        value(f.type, f.value, f.nodes, inner);
      }
      out_ += '\n';
    }
    out_ += indent + "}";
  }
};

}  // namespace

std::string printClassic(const WDocument& doc) {
  return ClassicPrinter(doc).print();
}

}  // namespace writing

std::optional<Encoding> encodingForPath(std::string_view path) {
  std::string lower(path);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::size_t dot = lower.rfind('.');
  const std::size_t slash = lower.find_last_of("/\\");
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return std::nullopt;
  const std::string_view ext = std::string_view(lower).substr(dot);
  if (ext == ".wrl") return Encoding::vrml97;
  if (ext == ".x3dv") return Encoding::classic;
  if (ext == ".x3d") return Encoding::xml;
  if (ext == ".x3dj" || ext == ".json") return Encoding::json;
  return std::nullopt;
}

std::string_view encodingName(Encoding e) {
  switch (e) {
    case Encoding::vrml97:
      return "VRML97";
    case Encoding::classic:
      return "X3D Classic VRML";
    case Encoding::xml:
      return "X3D XML";
    case Encoding::json:
      return "X3D JSON";
  }
  return "?";
}

WriteResult writeScene(const Scene& scene, const WriteOptions& options) {
  WriteResult r;
  const writing::WDocument doc = writing::buildDocument(scene, options, r.diagnostics);
  switch (options.encoding) {
    case Encoding::vrml97:
    case Encoding::classic:
      r.text = writing::printClassic(doc);
      break;
    case Encoding::xml:
      r.text = writing::printXml(doc);
      break;
    case Encoding::json:
      r.text = writing::printJson(doc);
      break;
  }
  return r;
}

}  // namespace gs::vrml
