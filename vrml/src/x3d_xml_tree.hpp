// The XML reader's buffer for one statement (see x3d_xml.hpp): its elements as a small
// tree of XNode, and what it knows of the PROTOs declared in the file. Internal to
// gs_vrml.
#pragma once

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

  std::span<const Attr> attrs() const { return {attrStore.data(), attrCount}; }
  void addAttr(const char* k, const char* v) {
    if (attrCount == attrStore.size()) attrStore.emplace_back();
    Attr& a = attrStore[attrCount++];
    a.first.assign(k);
    a.second.assign(v);
  }
  const std::string* attr(std::string_view n) const {
    for (const auto& [k, v] : attrs())
      if (k == n) return &v;
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

}  // namespace gs::vrml::parsing
