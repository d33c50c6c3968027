// The X3D XML reader's statements written as Classic VRML text (ISO/IEC 19776-1 read as
// 19776-2): nodes with their attributes converted by their field types, ROUTEs, IMPORT and
// EXPORT, PROTO and EXTERNPROTO declarations, ProtoInstances and their fieldValues, child
// elements grouped by containerField; each with its XML location (x3d_xml_impl.hpp).
#include "x3d_xml_impl.hpp"

namespace gs::vrml::parsing {

using namespace xml_reader;

void XmlToClassic::Impl::statement(const XNode& n) {
  if (n.kind == XKind::route) {
    route(n);
  } else if (n.kind == XKind::importStatement) {
    beginLine(n);
    const std::string imported = n.attrOr("importedDEF");
    out += "IMPORT " + xmlIdent(n.attrOr("inlineDEF")) + "." + xmlIdent(imported) + " AS " +
           xmlIdent(n.attrOr("AS", imported));
  } else if (n.kind == XKind::exportStatement) {
    beginLine(n);
    const std::string local = n.attrOr("localDEF");
    out += "EXPORT " + xmlIdent(local) + " AS " + xmlIdent(n.attrOr("AS", local));
  } else if (n.kind == XKind::protoDeclare) {
    protoDeclare(n);
  } else if (n.kind == XKind::externProtoDeclare) {
    externProtoDeclare(n);
  } else {
    node(n);
  }
}

void XmlToClassic::Impl::route(const XNode& n) {
  beginLine(n);
  out += "ROUTE " + xmlIdent(n.attrOr("fromNode")) + "." + xmlIdent(n.attrOr("fromField")) +
         " TO " + xmlIdent(n.attrOr("toNode")) + "." + xmlIdent(n.attrOr("toField"));
}

std::optional<FieldType> XmlToClassic::Impl::fieldDeclaration(const XNode& f, bool withValue) {
  beginLine(f);
  const std::string access = f.attrOr("accessType", "initializeOnly");
  const std::string typeName = f.attrOr("type");
  out += xmlIdent(access) + " " + xmlIdent(typeName) + " " + xmlIdent(f.attrOr("name")) + " ";
  FieldType t{};
  const bool known = fieldTypeFromName(typeName, t);
  if (!withValue || !accessTakesValue(access)) return known ? std::optional(t) : std::nullopt;
  const std::string* value = f.attr("value");
  if (!known) {
    if (value != nullptr) {
      out += *value;
      checkRaw(*value);
    }
    return std::nullopt;
  }
  if (t == FieldType::SFNode || t == FieldType::MFNode) {
    std::vector<const XNode*> nodes;
    for (const auto& c : f.children)
      if (isNodeElement(*c)) nodes.push_back(c);
    if (!nodes.empty()) {
      nodeValue(t == FieldType::MFNode, nodes);
      return t;
    }
  }
  if (value != nullptr)
    convertedValue(f, t, *value);
  else
    out += classicDefaultText(t);
  return t;
}

void XmlToClassic::Impl::checkRaw(std::string_view text) {
  if (builder != nullptr && classicSafe && !rawClassicSafe(text)) classicSafe = false;
}

void XmlToClassic::Impl::convertedValue(const XNode& n, FieldType t, std::string_view value) {
  std::string warning;
  const std::size_t at = out.size();
  appendXmlValueAsClassic(out, t, value, warning);
  if (builder != nullptr && classicSafe) {
    std::string_view written = std::string_view(out).substr(at);
    if (t == FieldType::SFImage || t == FieldType::MFImage || t == FieldType::MFNode ||
        (t == FieldType::SFNode && written != "NULL")) {
      classicSafe = false;  // looks ahead (SFImage's size check) or holds nodes
    } else {
      if (isMultiValued(t) && written.size() >= 4) written = written.substr(2, written.size() - 4);
      checkRaw(written);
    }
  }
  if (!warning.empty()) {
    warn(n, std::move(warning));
  } else if (t == FieldType::MFString) {
    // In a double-quoted MFString only \" and \\ are escapes (ISO/IEC 19776-1 5.3.2).
    for (std::size_t i = 0; i + 1 < value.size(); ++i) {
      if (value[i] != '\\') continue;
      const char next = value[i + 1];
      if (next != '"' && next != '\\') {
        warn(n, std::string("backslash before '") + next +
                    "' in an MFString value escapes nothing: read as '" + next + "'");
        break;
      }
      ++i;
    }
  }
}

void XmlToClassic::Impl::nodeValue(bool list, const std::vector<const XNode*>& nodes) {
  if (list) out += "[";
  for (const XNode* c : nodes) {
    if (!list && c != nodes.front()) out += " ";
    node(*c);
  }
  if (list) out += " ]";
}

void XmlToClassic::Impl::protoDeclare(const XNode& n) {
  const std::string name = xmlIdent(n.attrOr("name"));
  ProtoInfo info;
  beginLine(n);
  out += "PROTO " + name + " [";
  const XNode* body = nullptr;
  for (const auto& c : n.children) {
    if (c->kind == XKind::protoInterface) {
      for (const auto& f : c->children) {
        if (f->kind != XKind::field) continue;
        if (auto t = fieldDeclaration(*f, true)) info.fields.emplace_back(f->attrOr("name"), *t);
      }
    } else if (c->kind == XKind::protoBody && body == nullptr) {
      body = c;
    }
  }
  out += " ]\n{";
  if (body != nullptr) {
    for (const auto& c : body->children) {
      if (!isNodeElement(*c)) continue;
      info.containerField = containerFieldOf(*c, nullptr);
      break;
    }
  }
  // Declared before the body: an instance in the body is a (diagnosed) recursion.
  protos[name] = info;
  if (body != nullptr)
    for (const auto& c : body->children) statement(*c);
  out += "\n}";
}

void XmlToClassic::Impl::externProtoDeclare(const XNode& n) {
  const std::string name = xmlIdent(n.attrOr("name"));
  ProtoInfo info;
  beginLine(n);
  out += "EXTERNPROTO " + name + " [";
  for (const auto& f : n.children) {
    if (f->kind != XKind::field) continue;
    if (auto t = fieldDeclaration(*f, false)) info.fields.emplace_back(f->attrOr("name"), *t);
  }
  out += " ] ";
  convertedValue(n, FieldType::MFString, n.attrOr("url"));
  protos[name] = info;
}

void XmlToClassic::Impl::node(const XNode& n) {
  beginLine(n);
  if (const std::string* use = n.attr("USE")) {
    out += "USE ";
    appendXmlIdent(out, *use);
    return;
  }
  if (const std::string* def = n.attr("DEF"); def != nullptr && !blank(*def)) {
    out += "DEF ";
    appendXmlIdent(out, *def);
    out += ' ';
  }
  const bool instance = n.instance;
  if (instance) {
    const std::string* name = n.attr("name");
    appendXmlIdent(out, name != nullptr ? std::string_view(*name) : std::string_view());
  } else {
    appendXmlIdent(out, n.name);
  }
  out += " {";
  // Source text of Scripts and shaders: one more url entry.
  std::string source;
  if (n.source && !blank(n.text)) {
    std::string_view text = trimLeft(n.text);
    while (!text.empty() && xmlSpace(text.back())) text.remove_suffix(1);
    if (!hasUrlScheme(text)) source = isScript(n.type) ? "ecmascript:" : "data:text/plain,";
    source += text;
  }
  bool urlDone = false;
  if (!instance) {
    for (std::size_t i = 0; i < n.attrCount; ++i) {
      const auto& [k, v] = n.attrStore[i];
      if (const XNode::Numbers* numbers = n.numbersOf(i)) {
        // Read when the element started: written back as numbers that read the same.
        out += ' ';
        out += k;
        out += ' ';
        appendPlainListAsClassic(out, numbers->type, numbers->ints, numbers->floats);
        continue;
      }
      // HTML's class, id and style, unless the node has a field of that name
      // (FontStyle.style, ScreenFontStyle.style).
      const bool ignored = xmlIgnoredAttribute(k);
      if (ignored && k != "class" && k != "id" && k != "style") continue;
      const auto t = fieldType(n, k);
      if (ignored && !t) continue;
      out += ' ';
      out += k;
      out += ' ';
      if (!t) {
        appendQuoted(out, v);
        continue;
      }
      convertedValue(n, *t, v);
      if (k == "url" && *t == FieldType::MFString && !source.empty()) {
        // "[ ... ]": the source goes before the closing bracket.
        out.resize(out.size() - 1);
        appendQuoted(out, source);
        out += " ]";
        urlDone = true;
      }
    }
  }
  if (!source.empty() && !urlDone) {
    out += " url [ ";
    appendQuoted(out, source);
    out += " ]";
  }
  // Field declarations (Script, shaders), values of a PROTO instance, IS.
  if (scratchDepth == scratch.size()) scratch.push_back(std::make_unique<NodeScratch>());
  NodeScratch& sc = *scratch[scratchDepth];
  const ScratchLevel level(scratchDepth);
  sc.groups = 0;
  sc.routes.clear();
  for (const auto& cp : n.children) {
    const XNode& c = *cp;
    if (c.kind == XKind::field) {
      if (declaresFields(n.type))
        fieldDeclaration(c, true);
      else
        warn(c, "<field> is only allowed in Script, shader nodes and PROTO interfaces: ignored");
    } else if (c.kind == XKind::fieldValue) {
      if (instance)
        fieldValue(n, c);
      else
        warn(c, "<fieldValue> is only allowed in a ProtoInstance: ignored");
    } else if (c.kind == XKind::is) {
      for (const auto& k : c.children) {
        if (k->kind != XKind::connect) continue;
        beginLine(*k);
        out += xmlIdent(k->attrOr("nodeField")) + " IS " + xmlIdent(k->attrOr("protoField"));
      }
    } else if (c.kind == XKind::route || c.kind == XKind::protoDeclare ||
               c.kind == XKind::externProtoDeclare) {
      sc.routes.push_back(&c);
    } else if (!isNodeElement(c)) {
      warn(c, "<" + c.name + "> is not allowed in a node: ignored");
    } else {
      const std::string_view field = containerFieldOf(c, &n);
      std::size_t g = 0;
      while (g < sc.groups && sc.group[g].first != field) ++g;
      if (g == sc.groups) {
        if (g == sc.group.size()) sc.group.emplace_back();
        sc.group[g].first = field;
        sc.group[g].second.clear();
        ++sc.groups;
      }
      sc.group[g].second.push_back(&c);
    }
  }
  for (std::size_t g = 0; g < sc.groups; ++g) {
    const auto& [field, nodes] = sc.group[g];
    beginLine(*nodes.front());
    appendXmlIdent(out, field);
    out += ' ';
    const auto t = fieldType(n, field);
    nodeValue(!t || *t == FieldType::MFNode || nodes.size() > 1, nodes);
  }
  // ROUTEs and PROTOs last, after the DEFs of the children they may name.
  for (const XNode* r : sc.routes) statement(*r);
  out += " }";
}

void XmlToClassic::Impl::fieldValue(const XNode& inst, const XNode& fv) {
  beginLine(fv);
  const std::string name = fv.attrOr("name");
  out += xmlIdent(name) + " ";
  const auto t = fieldType(inst, name);
  std::vector<const XNode*> nodes;
  for (const auto& c : fv.children)
    if (isNodeElement(*c)) nodes.push_back(c);
  if (!nodes.empty()) {
    nodeValue(!t || *t == FieldType::MFNode || nodes.size() > 1, nodes);
    return;
  }
  const std::string* value = fv.attr("value");
  if (t)
    convertedValue(fv, *t, value != nullptr ? std::string_view(*value) : std::string_view());
  else if (value != nullptr) {
    out += *value;  // an undeclared PROTO: the parser reports it
    checkRaw(*value);
  }
}

}  // namespace gs::vrml::parsing
