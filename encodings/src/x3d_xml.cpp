// X3D XML encoding -> Classic VRML text (see x3d_xml.hpp). The element stack says where
// the parser is (outside X3D, in head, in Scene, in a buffered statement, skipping); the
// elements of one top-level statement are kept as a tree of XNode until its end tag, then
// offered to the builder (parser_xml_build.cpp), else written out: attributes converted
// by the field types of x3dNodeType() (or of the declared PROTO, or of the Script's
// <field>), child elements grouped by containerField.
#include "x3d_xml_impl.hpp"

namespace gs::vrml::parsing {

using namespace xml_reader;

void XMLCALL XmlToClassic::Impl::onStart(void* ud, const XML_Char* name, const XML_Char** atts) {
  static_cast<Impl*>(ud)->start(name, atts);
}

void XMLCALL XmlToClassic::Impl::onText(void* ud, const XML_Char* s, int len) {
  Impl& m = *static_cast<Impl*>(ud);
  if (m.failed || m.stack.empty() || m.stack.back() != Frame::buffered || m.cur == nullptr) return;
  if (m.cur->source) m.cur->text.append(s, static_cast<std::size_t>(len));
}

std::pair<int, int> XmlToClassic::Impl::here() const {
  return {static_cast<int>(XML_GetCurrentLineNumber(xp)),
          static_cast<int>(XML_GetCurrentColumnNumber(xp)) + 1};
}

void XmlToClassic::Impl::fail(int line, int column, std::string message) {
  if (failed) return;
  failed = true;
  fatal = Diagnostic{Severity::error, {url, line, column}, std::move(message)};
  XML_StopParser(xp, XML_FALSE);
}

void XmlToClassic::Impl::warn(const XNode& n, std::string message) {
  warnings.push_back(Diagnostic{Severity::warning, {url, n.line, n.column}, std::move(message)});
}

std::pair<int, int> XmlToClassic::Impl::startHere() {
  const auto at = positions.at(static_cast<std::uint64_t>(XML_GetCurrentByteIndex(xp)));
  return at.first > 0 ? at : here();
}

void XmlToClassic::Impl::start(const XML_Char* name, const XML_Char** atts) {
  if (failed) return;
  const auto [line, column] = startHere();
  const std::string_view n(name);
  if (static_cast<int>(stack.size()) >= maxDepth) {
    fail(line, column, "XML elements nested deeper than " + std::to_string(maxDepth) + " levels");
    return;
  }
  if (stack.empty()) {
    if (n != "X3D") {
      fail(line, column, "expected the root element <X3D>, got <" + std::string(n) + ">");
      return;
    }
    std::string version = "4.0", profile;
    for (const XML_Char** a = atts; *a != nullptr; a += 2) {
      if (std::string_view(a[0]) == "version") version = a[1];
      x3d3 = version.starts_with('3');
      if (std::string_view(a[0]) == "profile") profile = a[1];
    }
    beginLine(line, column);
    out += "#X3D V";
    for (char c : version) out += xmlSpace(c) ? '_' : c;
    out += " utf8\n";
    wroteHeader = true;
    if (!profile.empty()) {
      beginLine(line, column);
      out += "PROFILE " + xmlIdent(profile) + "\n";
    }
    stack.push_back(Frame::x3d);
    return;
  }
  switch (stack.back()) {
    case Frame::x3d:
      stack.push_back(n == "head" ? Frame::head : n == "Scene" ? Frame::scene : Frame::skip);
      return;
    case Frame::head:
      headItem(n, atts, line, column);
      stack.push_back(Frame::item);
      return;
    case Frame::item:
    case Frame::skip:
      stack.push_back(Frame::skip);
      return;
    case Frame::scene:
    case Frame::buffered: {
      if (stack.back() == Frame::scene) poolUsed = 0;
      XNode* node = newNode(n);
      node->line = line;
      node->column = column;
      // While statements may be built from their elements, number lists of built-in
      // nodes are read now, from expat's text: no copy of it (x3d_numbers.hpp).
      // (Not for a name that is also a PROTO's, whose fields may differ.)
      const bool numbersNow = builder != nullptr && classicSafe && node->type != nullptr &&
                              !node->instance && !node->source && !node->type->userFields &&
                              (protos.empty() || !protos.contains(std::string(n)));
      for (const XML_Char** a = atts; *a != nullptr; a += 2) {
        const std::string_view k(a[0]);
        if (!numbersNow || !readXmlNumbers(*node, k, a[1])) node->addAttr(k, a[1]);
      }
      if (stack.back() == Frame::scene) {
        root = node;
      } else {
        node->parent = cur;
        cur->children.push_back(node);
      }
      cur = node;
      stack.push_back(Frame::buffered);
      textHandler();
      return;
    }
  }
}

const XmlToClassic::Impl::TypeCacheEntry& XmlToClassic::Impl::lookupType(std::string_view n) {
  const std::size_t h = n.empty() ? 0
                                  : (n.size() * 7 + static_cast<unsigned char>(n.front()) * 3 +
                                     static_cast<unsigned char>(n[n.size() / 2]) +
                                     static_cast<unsigned char>(n.back()));
  const std::size_t slot = (h % (typeCache.size() / 2)) * 2;
  if (typeCache[slot].valid && sameName(typeCache[slot].name, n)) return typeCache[slot];
  if (typeCache[slot + 1].valid && sameName(typeCache[slot + 1].name, n))
    return typeCache[slot + 1];
  TypeCacheEntry& e = typeCache[typeCache[slot].valid ? slot + 1 : slot];
  e.name.assign(n);
  e.type = x3dNodeType(n).get();
  e.model = nodeModel(n);
  e.valid = true;
  return e;
}

XNode* XmlToClassic::Impl::newNode(std::string_view n) {
  if (poolUsed == pool.size()) pool.push_back(std::make_unique<XNode>());
  XNode* x = pool[poolUsed++].get();
  x->name.assign(n);
  const TypeCacheEntry& e = lookupType(n);
  x->type = e.type;
  x->model = e.model;
  x->source = xmlTakesSource(x->type);
  // (ProtoInstance has a node model too; the statement names are none.)
  x->kind = x->type != nullptr ? XKind::node : xkindOf(n);
  x->instance = sameName(n, kProtoInstanceElement);
  x->attrCount = 0;
  x->children.clear();
  x->text.clear();
  x->parent = nullptr;
  return x;
}

void XmlToClassic::Impl::end() {
  if (failed || stack.empty()) return;
  const Frame f = stack.back();
  stack.pop_back();
  if (f != Frame::buffered) return;
  if (cur == root) {
    if (builder == nullptr || !classicSafe || root->kind != XKind::node ||
        !builder->build(*root, *this)) {
      statement(*root);
      out += '\n';
    }
    root = nullptr;
    cur = nullptr;
    poolUsed = 0;
  } else {
    cur = cur->parent;
  }
  textHandler();
}

void XmlToClassic::Impl::textHandler() {
  const bool want = cur != nullptr && cur->source;
  if (want == textOn) return;
  textOn = want;
  XML_SetCharacterDataHandler(xp, want ? &Impl::onText : nullptr);
}

void XmlToClassic::Impl::headItem(std::string_view n, const XML_Char** atts, int line, int column) {
  auto get = [atts](std::string_view key) {
    for (const XML_Char** a = atts; *a != nullptr; a += 2)
      if (std::string_view(a[0]) == key) return std::string(a[1]);
    return std::string();
  };
  if (n == "component") {
    beginLine(line, column);
    out += "COMPONENT " + xmlIdent(get("name"));
    const std::string level = get("level");
    if (!blank(level)) {
      out += ':';
      for (char c : level) out += xmlSpace(c) ? '_' : c;
      checkRaw(level);
    }
  } else if (n == "unit") {
    beginLine(line, column);
    out += "UNIT " + xmlIdent(get("category")) + " " + xmlIdent(get("name")) + " ";
    const std::string f = get("conversionFactor");
    out += blank(f) ? std::string("1") : f;
    checkRaw(f);
  } else if (n == "meta") {
    beginLine(line, column);
    out += "META ";
    appendQuoted(out, get("name"));
    out += ' ';
    appendQuoted(out, get("content"));
  } else {
    return;
  }
  out += '\n';
}

void XmlToClassic::Impl::beginLine(int line, int column) {
  if (!out.empty() && out.back() != '\n') out += '\n';
  lines.add({out.size(), line, column});
}

std::string_view XmlToClassic::Impl::containerFieldOf(const XNode& c, const XNode* parent) const {
  if (const std::string* cf = c.attr("containerField"); cf != nullptr && !blank(*cf)) return *cf;
  std::string_view field = "children";
  const bool metadata = metadataName(c.name);
  if (c.instance) {
    auto it = protos.find(xmlIdent(c.attrOr("name")));
    if (it != protos.end()) field = it->second.containerField;
  } else if (metadata && x3d3) {
    field = "metadata";
  } else if (const NodeModel* m = c.model; m != nullptr && !m->containerField.empty()) {
    field = m->containerField;
  } else if (auto it = protos.find(c.name); it != protos.end()) {
    field = it->second.containerField;
  }
  if (parent == nullptr || !knownFields(*parent) || fieldType(*parent, field)) return field;
  if (metadata && fieldType(*parent, "metadata")) return "metadata";
  if (fieldType(*parent, "children")) return "children";
  return field;
}

std::string_view XmlToClassic::Impl::containerField(const XNode& c, const XNode& parent) const {
  return containerFieldOf(c, &parent);
}

std::optional<FieldType> XmlToClassic::Impl::fieldTypeOf(const XNode& p, std::string_view f) const {
  return fieldType(p, f);
}

bool XmlToClassic::Impl::knownFields(const XNode& p) const {
  if (p.instance) return protos.contains(xmlIdent(p.attrOr("name")));
  return p.type != nullptr || protos.contains(p.name);
}

std::optional<FieldType> XmlToClassic::Impl::fieldType(const XNode& p, std::string_view f) const {
  if (p.instance) {
    auto it = protos.find(xmlIdent(p.attrOr("name")));
    if (it == protos.end()) return std::nullopt;
    return it->second.field(f);
  }
  if (declaresFields(p.type)) {
    for (const auto& c : p.children) {
      if (c->kind != XKind::field || c->attrOr("name") != f) continue;
      FieldType t{};
      if (fieldTypeFromName(c->attrOr("type"), t)) return t;
    }
  }
  if (const NodeType* type = p.type) return builtInFieldType(*type, f);
  if (auto it = protos.find(p.name); it != protos.end()) return it->second.field(f);
  return std::nullopt;
}

std::optional<FieldType> XmlToClassic::Impl::builtInFieldType(const NodeType& type,
                                                              std::string_view f) const {
  std::size_t h = (reinterpret_cast<std::uintptr_t>(&type) >> 4) * 31 + f.size() * 7;
  if (!f.empty())
    h += static_cast<unsigned char>(f.front()) * 3u + static_cast<unsigned char>(f.back()) +
         static_cast<unsigned char>(f[f.size() / 2]) * 5u;
  FieldCacheEntry& e = fieldCache[h % fieldCache.size()];
  if (e.type == &type && e.name == f) return e.fieldType;
  e.type = &type;
  e.name.assign(f);
  e.fieldType = findBuiltInFieldType(type, f);
  return e.fieldType;
}

XmlToClassic::XmlToClassic(std::string& out, std::string url, int maxNesting)
    : impl_(std::make_unique<Impl>(out, std::move(url), maxNesting)) {}

XmlToClassic::~XmlToClassic() = default;

bool XmlToClassic::feed(std::string_view bytes, bool last) {
  Impl& m = *impl_;
  if (m.finished) return !m.failed;
  if (last && bytes.empty()) return finish();
  while (!m.failed && !bytes.empty()) {
    constexpr std::size_t kMax = 1u << 30;  // XML_Parse takes an int length
    const std::size_t n = std::min(bytes.size(), kMax);
    const bool final = last && n == bytes.size();
    m.positions.feed(bytes.substr(0, n));
    if (final) m.finished = true;
    if (XML_Parse(m.xp, bytes.data(), static_cast<int>(n), final ? XML_TRUE : XML_FALSE) ==
            XML_STATUS_ERROR &&
        !m.failed) {
      const auto [line, column] = m.here();
      m.fail(line, column,
             std::string("XML syntax error: ") + XML_ErrorString(XML_GetErrorCode(m.xp)));
    }
    bytes.remove_prefix(n);
  }
  return !m.failed;
}

bool XmlToClassic::finish() {
  Impl& m = *impl_;
  if (m.failed) return false;
  if (m.finished) return true;
  m.finished = true;
  m.positions.feed({});
  if (XML_Parse(m.xp, "", 0, XML_TRUE) == XML_STATUS_ERROR && !m.failed) {
    const auto [line, column] = m.here();
    m.fail(line, column,
           std::string("XML syntax error: ") + XML_ErrorString(XML_GetErrorCode(m.xp)));
  }
  return !m.failed;
}

void XmlToClassic::setBuilder(XmlStatementBuilder* builder) {
  impl_->builder = builder;
}

bool XmlToClassic::wroteHeader() const {
  return impl_->wroteHeader;
}

bool XmlToClassic::failed() const {
  return impl_->failed;
}

const Diagnostic& XmlToClassic::fatalError() const {
  return impl_->fatal;
}

std::pair<int, int> XmlToClassic::xmlLocationAt(std::size_t offset) {
  return impl_->lines.at(offset);
}

TextOrigin& XmlToClassic::origin() {
  return impl_->lines;
}

void XmlToClassic::addWarnings(Scene& scene, std::size_t at) {
  auto& w = impl_->warnings;
  auto& items = scene.diagnostics.items;
  items.insert(items.begin() + static_cast<std::ptrdiff_t>(std::min(at, items.size())),
               std::make_move_iterator(w.begin()), std::make_move_iterator(w.end()));
  w.clear();
}

}  // namespace gs::vrml::parsing
