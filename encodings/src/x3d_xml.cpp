// X3D XML encoding -> Classic VRML text (see x3d_xml.hpp). The element stack says where
// the parser is (outside X3D, in head, in Scene, in a buffered statement, skipping); the
// elements of one top-level statement are kept as a tree of XNode until its end tag, then
// offered to the builder (parser_xml_build.cpp), else written out: attributes converted
// by the field types of x3dNodeType() (or of the declared PROTO, or of the Script's
// <field>), child elements grouped by containerField.
#include "x3d_xml.hpp"

#include "encodings/node_types.hpp"
#include "vrml/field.hpp"
#include "vrml/node_model.hpp"
#include "vrml/node_table.hpp"
#include "x3d_numbers.hpp"
#include "x3d_positions.hpp"
#include "x3d_values.hpp"
#include "x3d_xml_tree.hpp"

#include <expat.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <iterator>
#include <optional>
#include <span>
#include <unordered_map>
#include <unordered_set>

namespace gs::vrml::parsing {

namespace {

bool blank(std::string_view s) {
  return std::all_of(s.begin(), s.end(), xmlSpace);
}

std::string_view trimLeft(std::string_view s) {
  while (!s.empty() && xmlSpace(s.front())) s.remove_prefix(1);
  return s;
}

// The XML encoding's element for a PROTO instance (ISO/IEC 19776-1 5.3.6): a statement of
// the encoding, not a node class.
constexpr std::string_view kProtoInstanceElement = "ProtoInstance";

// Nodes whose <field> children declare interface members (ISO/IEC 19776-1 5.3.7): Script
// and the X3DProgrammableShaderObject nodes (NodeType::userFields).
bool declaresFields(const NodeType* type) {
  return type != nullptr && type->userFields;
}

// Nodes whose text content is source code, added to `url`: Script, ShaderPart and the
// programmable shader nodes that carry a url (ShaderProgram, PackagedShader).
bool xmlTakesSource(const NodeType* type) {
  if (type == nullptr) return false;
  return type->script || type->id() == NodeTypeId::ShaderPart ||
         (type->userFields && type->is(AbstractType::X3DUrlObject));
}

// Script source gets the ecmascript: scheme; shader source a data: URL.
bool isScript(const NodeType* type) {
  return type != nullptr && type->script;
}

}  // namespace

struct XmlToClassic::Impl final : XmlTreeInfo {
  Impl(std::string& o, std::string u, int maxNesting)
      : out(o), url(std::move(u)), maxDepth(std::max(maxNesting, 1) + 8) {
    xp = XML_ParserCreate(nullptr);
    if (xp == nullptr) throw std::bad_alloc();
    XML_SetUserData(xp, this);
    XML_SetElementHandler(xp, &Impl::onStart, &Impl::onEnd);
    // (The character data handler is set only inside elements that take source text.)
    // No external entity handler and no parameter-entity parsing: DTDs and external
    // entities named by the document are never fetched.
    XML_SetParamEntityParsing(xp, XML_PARAM_ENTITY_PARSING_NEVER);
  }
  ~Impl() { XML_ParserFree(xp); }
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;

  enum class Frame : std::uint8_t { x3d, head, scene, item, skip, buffered };

  std::string& out;
  std::string url;
  int maxDepth;
  XML_Parser xp = nullptr;
  std::vector<Frame> stack;
  std::vector<std::unique_ptr<XNode>> pool;  // XNodes; the first poolUsed are in use
  std::size_t poolUsed = 0;
  XNode* root = nullptr;  // the statement being buffered
  XNode* cur = nullptr;   // its open element
  bool wroteHeader = false;
  bool x3d3 = false;  // version 3.x: metadata nodes go to `metadata` by default
  bool failed = false;
  Diagnostic fatal;
  std::vector<Diagnostic> warnings;
  std::unordered_map<std::string, ProtoInfo> protos;
  // Classic offset -> XML location, one entry per element start (increasing offsets).
  OffsetLocations lines;
  bool finished = false;   // the last bytes were fed
  XmlPositions positions;  // element start -> line and column (startHere)
  // Plain statements are offered to `builder` while `classicSafe`: no statement translated
  // so far can run into the text that follows it (see checkRaw).
  XmlStatementBuilder* builder = nullptr;
  bool classicSafe = true;

  // ---- expat callbacks -----------------------------------------------------------------

  static void XMLCALL onStart(void* ud, const XML_Char* name, const XML_Char** atts) {
    static_cast<Impl*>(ud)->start(name, atts);
  }
  static void XMLCALL onEnd(void* ud, const XML_Char* /*name*/) { static_cast<Impl*>(ud)->end(); }
  static void XMLCALL onText(void* ud, const XML_Char* s, int len) {
    Impl& m = *static_cast<Impl*>(ud);
    if (m.failed || m.stack.empty() || m.stack.back() != Frame::buffered || m.cur == nullptr)
      return;
    if (m.cur->source) m.cur->text.append(s, static_cast<std::size_t>(len));
  }

  std::pair<int, int> here() const {
    return {static_cast<int>(XML_GetCurrentLineNumber(xp)),
            static_cast<int>(XML_GetCurrentColumnNumber(xp)) + 1};
  }

  void fail(int line, int column, std::string message) {
    if (failed) return;
    failed = true;
    fatal = Diagnostic{Severity::error, {url, line, column}, std::move(message)};
    XML_StopParser(xp, XML_FALSE);
  }

  void warn(const XNode& n, std::string message) {
    warnings.push_back(Diagnostic{Severity::warning, {url, n.line, n.column}, std::move(message)});
  }

  // here() at an element's start: from the byte offset and the line starts of the fed bytes
  // where that is exact and cheap, else from expat.
  std::pair<int, int> startHere() {
    const auto at = positions.at(static_cast<std::uint64_t>(XML_GetCurrentByteIndex(xp)));
    return at.first > 0 ? at : here();
  }

  void start(const XML_Char* name, const XML_Char** atts) {
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

  // x3dNodeType(n) through a small cache of the names met (a file uses few): no hash of
  // the whole name, no reference count. The table lives as long as the program.
  struct TypeCacheEntry {
    std::string name;
    const NodeType* type = nullptr;
    const NodeModel* model = nullptr;  // nodeModel(name)
    bool valid = false;
  };
  // (Two entries per hash: Material and Coordinate, which alternate in many worlds, share
  // one. A name in neither replaces the second, or the first while it is empty.)
  std::array<TypeCacheEntry, 64> typeCache;
  const TypeCacheEntry& lookupType(std::string_view n) {
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

  // A pooled XNode for element `n`, reset.
  XNode* newNode(std::string_view n) {
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

  // node()'s lists, one per nesting level of node(), kept for their capacity.
  struct NodeScratch {
    std::vector<std::pair<std::string, std::vector<const XNode*>>> group;  // by field
    std::size_t groups = 0;                                                // in use
    std::vector<const XNode*> routes;
  };
  std::vector<std::unique_ptr<NodeScratch>> scratch;
  std::size_t scratchDepth = 0;
  struct ScratchLevel {
    std::size_t& depth;
    explicit ScratchLevel(std::size_t& d) : depth(d) { ++depth; }
    ~ScratchLevel() { --depth; }
    ScratchLevel(const ScratchLevel&) = delete;
    ScratchLevel& operator=(const ScratchLevel&) = delete;
  };

  void end() {
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

  // Character data matters only in an element that takes source text: expat reports it
  // only there (fewer calls for the white space between elements).
  bool textOn = false;
  void textHandler() {
    const bool want = cur != nullptr && cur->source;
    if (want == textOn) return;
    textOn = want;
    XML_SetCharacterDataHandler(xp, want ? &Impl::onText : nullptr);
  }

  // <component>, <unit>, <meta> of <head>.
  void headItem(std::string_view n, const XML_Char** atts, int line, int column) {
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

  // ---- output with line map ------------------------------------------------------------

  // An element's translation begins: on a line of its own (for a reader of the text),
  // its first byte recorded with the element's XML location.
  void beginLine(int line, int column) {
    if (!out.empty() && out.back() != '\n') out += '\n';
    lines.add({out.size(), line, column});
  }
  void beginLine(const XNode& n) { beginLine(n.line, n.column); }

  // ---- statements ----------------------------------------------------------------------

  void statement(const XNode& n) {
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

  void route(const XNode& n) {
    beginLine(n);
    out += "ROUTE " + xmlIdent(n.attrOr("fromNode")) + "." + xmlIdent(n.attrOr("fromField")) +
           " TO " + xmlIdent(n.attrOr("toNode")) + "." + xmlIdent(n.attrOr("toField"));
  }

  // `accessType type name [value]` of a <field> in a ProtoInterface, ExternProtoDeclare,
  // Script or shader. Returns the field's type when it names one.
  std::optional<FieldType> fieldDeclaration(const XNode& f, bool withValue) {
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

  // Raw XML text written into the Classic text (numbers, MFString lists, words): once
  // some could open a string, a comment or a bracket that the parse of its statement would
  // not close, the statements after it may be read as part of it, so none is built
  // straight from its elements any more (classicSafe).
  void checkRaw(std::string_view text) {
    if (builder != nullptr && classicSafe && !rawClassicSafe(text)) classicSafe = false;
  }

  void convertedValue(const XNode& n, FieldType t, std::string_view value) {
    std::string warning;
    const std::size_t at = out.size();
    appendXmlValueAsClassic(out, t, value, warning);
    if (builder != nullptr && classicSafe) {
      std::string_view written = std::string_view(out).substr(at);
      if (t == FieldType::SFImage || t == FieldType::MFImage || t == FieldType::MFNode ||
          (t == FieldType::SFNode && written != "NULL")) {
        classicSafe = false;  // looks ahead (SFImage's size check) or holds nodes
      } else {
        if (isMultiValued(t) && written.size() >= 4)
          written = written.substr(2, written.size() - 4);
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

  // One node or a list of nodes as the value of an SFNode / MFNode field.
  void nodeValue(bool list, const std::vector<const XNode*>& nodes) {
    if (list) out += "[";
    for (const XNode* c : nodes) {
      if (!list && c != nodes.front()) out += " ";
      node(*c);
    }
    if (list) out += " ]";
  }

  void protoDeclare(const XNode& n) {
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

  void externProtoDeclare(const XNode& n) {
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

  // Elements that are nodes (not statements or the XML encoding's structure).
  static bool isNodeElement(const XNode& n) { return n.kind == XKind::node; }

  // Where child `c` of `parent` goes: its containerField, else its type's default (X3D
  // 3's `metadata` for metadata nodes in a 3.x file). A default the parent (of a known
  // type) has no field for falls back to `metadata` for metadata nodes, else to
  // `children` where the parent has it, as castle-model-viewer does (HAnimMotion in a
  // Group, a 3.x MetadataSet in a 4.0 world). The view is into `c`, the node model, the
  // PROTOs declared or a literal.
  std::string_view containerFieldOf(const XNode& c, const XNode* parent) const {
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
  std::string_view containerField(const XNode& c, const XNode& parent) const override {
    return containerFieldOf(c, &parent);
  }
  std::optional<FieldType> fieldTypeOf(const XNode& p, std::string_view f) const override {
    return fieldType(p, f);
  }

  // Whether the fields of node element `p` are all known here.
  bool knownFields(const XNode& p) const {
    if (p.instance) return protos.contains(xmlIdent(p.attrOr("name")));
    return p.type != nullptr || protos.contains(p.name);
  }

  // The type of field `f` of node element `p`; nothing when unknown.
  std::optional<FieldType> fieldType(const XNode& p, std::string_view f) const {
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

  // The type of field `f` of built-in `type`, through a small cache of the pairs met (a
  // file uses few; the table lives as long as the program).
  struct FieldCacheEntry {
    const NodeType* type = nullptr;
    std::string name;
    std::optional<FieldType> fieldType;
  };
  mutable std::array<FieldCacheEntry, 256> fieldCache;
  std::optional<FieldType> builtInFieldType(const NodeType& type, std::string_view f) const {
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
  void node(const XNode& n) {
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

  // <fieldValue name value> or with node children, in a ProtoInstance.
  void fieldValue(const XNode& inst, const XNode& fv) {
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
};

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
