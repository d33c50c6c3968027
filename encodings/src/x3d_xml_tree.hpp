// The XML reader's buffer for one statement (see x3d_xml.hpp): its elements as a small
// tree of XNode, and what it knows of the PROTOs declared in the file. Internal to
// gs_encodings.
#pragma once

#include "lexer.hpp"
#include "vrml/field.hpp"
#include "vrml/node.hpp"
#include "vrml/node_model.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

/// What an element of a statement is: a node (built-in, PROTO instance, unknown) or one of
/// the XML encoding's statements and structure elements.
enum class XKind : std::uint8_t {
  node,
  route,
  importStatement,
  exportStatement,
  protoDeclare,
  externProtoDeclare,
  is,
  connect,
  field,
  fieldValue,
  protoInterface,
  protoBody
};

/// XML white space (the S production of XML 1.0: space, tab, line feed, carriage return).
inline bool xmlSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

/// Whether element name `name` is that of a metadata node (MetadataFloat ...).
inline bool metadataName(std::string_view name) {
  return name.size() >= 8 && sameName(name.substr(0, 8), "Metadata");
}

inline XKind xkindOf(std::string_view s) {
  static constexpr std::pair<std::string_view, XKind> kKinds[] = {
      {"ROUTE", XKind::route},
      {"IMPORT", XKind::importStatement},
      {"EXPORT", XKind::exportStatement},
      {"ProtoDeclare", XKind::protoDeclare},
      {"ExternProtoDeclare", XKind::externProtoDeclare},
      {"IS", XKind::is},
      {"connect", XKind::connect},
      {"field", XKind::field},
      {"fieldValue", XKind::fieldValue},
      {"ProtoInterface", XKind::protoInterface},
      {"ProtoBody", XKind::protoBody}};
  for (const auto& [name, kind] : kKinds)
    if (s == name) return kind;
  return XKind::node;
}

/// One element of a statement being buffered. XNodes are pooled (Impl::newNode): one
/// that is used again keeps the capacity of its strings.
struct XNode {
  using Attr = std::pair<std::string, std::string>;
  std::string name;
  const NodeType* type = nullptr;    // x3dNodeType(name), looked up once
  const NodeModel* model = nullptr;  // nodeModel(name), looked up once
  bool source = false;               // takes source text (xmlTakesSource)
  bool instance = false;             // a <ProtoInstance>
  XKind kind = XKind::node;
  int line = 0;
  int column = 0;
  std::vector<Attr> attrStore;  // the first attrCount are this element's attributes
  std::size_t attrCount = 0;
  std::vector<XNode*> children;  // owned by the pool
  std::string text;              // character data (kept for the nodes that take source text)
  XNode* parent = nullptr;

  /// A number list read when the element started (x3d_numbers.hpp), for the attribute of
  /// the same index, whose text is then not kept (empty): `type` is its field's type, or
  /// none (`components` 0) for an attribute kept as text.
  struct Numbers {
    int components = 0;
    FieldType type = FieldType::MFInt32;
    std::vector<std::int32_t> ints;  // MFInt32
    std::vector<float> floats;       // the other types, flat
  };
  std::vector<Numbers> numbers;  // parallel to attrStore

  std::span<const Attr> attrs() const { return {attrStore.data(), attrCount}; }
  void addAttr(std::string_view k, const char* v) {
    if (attrCount == attrStore.size()) attrStore.emplace_back();
    if (numbers.size() < attrStore.size()) numbers.resize(attrStore.size());
    numbers[attrCount].components = 0;
    Attr& a = attrStore[attrCount++];
    a.first.assign(k);
    a.second.assign(v);
  }
  /// The slot the next attribute's numbers are read into (addNumbers() keeps them).
  Numbers& nextNumbers() {
    if (attrCount == attrStore.size()) attrStore.emplace_back();
    if (numbers.size() < attrStore.size()) numbers.resize(attrStore.size());
    return numbers[attrCount];
  }
  /// Adds attribute `k`, whose value of type `t` nextNumbers() now holds.
  void addNumbers(std::string_view k, FieldType t, int components) {
    Numbers& n = numbers[attrCount];
    n.type = t;
    n.components = components;
    Attr& a = attrStore[attrCount++];
    a.first.assign(k);
    a.second.clear();
  }
  /// The numbers of attribute `i` when it was read as numbers; null otherwise.
  const Numbers* numbersOf(std::size_t i) const {
    return i < numbers.size() && numbers[i].components > 0 ? &numbers[i] : nullptr;
  }
  const std::string* attr(std::string_view n) const {
    for (const auto& [k, v] : attrs())
      if (sameName(k, n)) return &v;
    return nullptr;
  }
  std::string attrOr(std::string_view n, std::string_view fallback = {}) const {
    const std::string* v = attr(n);
    return v != nullptr ? *v : std::string(fallback);
  }
};

/// A PROTO or EXTERNPROTO declared in the file: its interface and where its instances go
/// when they name no containerField (the first node of its body's).
struct ProtoInfo {
  std::vector<std::pair<std::string, FieldType>> fields;
  std::string containerField = "children";

  std::optional<FieldType> field(std::string_view n) const {
    for (const auto& [k, t] : fields)
      if (k == n) return t;
    return std::nullopt;
  }
};

/// The type of field `f` of built-in `type` as the translation writes its value:
/// NodeType::findField (with the set_ / _changed aliases), X3D's names of Collision's
/// `collide` and of ComposedCubeMapTexture's faces, Switch's and LOD's `children`;
/// nothing when none (x3d_xml_support.cpp).
std::optional<FieldType> findBuiltInFieldType(const NodeType& type, std::string_view f);

/// Attribute `name` = `v` (expat's NUL-terminated text) of built-in node element `x` read
/// as numbers (XNode::Numbers) when it is a number list field of x's type (MFInt32,
/// MFFloat, MFVec2f, MFVec3f, MFColor), named exactly, and `v` is plain
/// (x3d_numbers.hpp); false, nothing added, otherwise (x3d_xml_support.cpp).
bool readXmlNumbers(XNode& x, std::string_view name, const char* v);

/// Whether raw XML text written into the Classic translation keeps its statement closed:
/// no '#', bracket or brace outside strings, every string ended (x3d_xml_support.cpp).
bool rawClassicSafe(std::string_view text);

/// What the translator knows of a statement's elements that the direct builder needs
/// (x3d_xml.cpp implements it).
class XmlTreeInfo {
 public:
  /// The field that child element `c` of node element `parent` goes to: its
  /// containerField, else its type's default (see x3d_xml.cpp). The view lives as long as
  /// the statement's elements and no PROTO is declared.
  virtual std::string_view containerField(const XNode& c, const XNode& parent) const = 0;
  /// The type the translator gives field `f` of node element `p` (built-in, declared
  /// PROTO or Script field); nothing when it knows none.
  virtual std::optional<FieldType> fieldTypeOf(const XNode& p, std::string_view f) const = 0;

 protected:
  XmlTreeInfo() = default;
  ~XmlTreeInfo() = default;
  XmlTreeInfo(const XmlTreeInfo&) = default;
  XmlTreeInfo& operator=(const XmlTreeInfo&) = default;
};

/// Who makes the nodes of a "plain" top-level statement straight from its elements, with
/// no Classic VRML text: the reader that parses the translation (parseInto's XML reader,
/// StreamingParser). XmlToClassic offers it each top-level node element of <Scene> as its
/// end tag arrives, while the Classic text written so far is known to hold only whole
/// statements; what it declines is translated as before.
class XmlStatementBuilder {
 public:
  /// Builds the statement whose root element is `root` after every statement before it,
  /// or returns false having changed nothing (it is then translated).
  virtual bool build(const XNode& root, const XmlTreeInfo& info) = 0;

 protected:
  XmlStatementBuilder() = default;
  ~XmlStatementBuilder() = default;
  XmlStatementBuilder(const XmlStatementBuilder&) = default;
  XmlStatementBuilder& operator=(const XmlStatementBuilder&) = default;
};

}  // namespace gs::vrml::parsing
