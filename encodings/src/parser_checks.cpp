// Which node may go where (clause 4.6.5 "Grouping and children nodes" and the SFNode
// fields of clause 6, as X3D 4.0's acceptableNodeTypes state them in the node model): a
// Material in Group.children or a Color in Text.fontStyle is read but reported as a
// warning.
#include "parser_impl.hpp"

#include <array>
#include <cstdint>
#include <string>

namespace gs::vrml::parsing {

namespace {

/// "Coordinate|CoordinateDouble" as "Coordinate or CoordinateDouble".
std::string describe(std::string_view acceptable) {
  std::string out;
  while (!acceptable.empty()) {
    const std::size_t bar = acceptable.find('|');
    if (!out.empty()) out += " or ";
    out += acceptable.substr(0, bar);
    acceptable = bar == std::string_view::npos ? std::string_view() : acceptable.substr(bar + 1);
  }
  return out;
}

/// What the root of a scene takes: children nodes (X3DChildNode), as Group.children does.
const NodeFieldModel& rootField() {
  static const NodeFieldModel* kChildren = nodeModel(NodeTypeId::Group)->findField("children");
  return *kChildren;
}

}  // namespace

bool nodeClassAllowed(const NodeType* parent, std::string_view field, const NodeType& child,
                      std::string& expected) {
  // PROTO instances of unknown body, unresolved EXTERNPROTOs and Scripts' own fields:
  // nothing to check against.
  if (child.model == nullptr) return true;
  // A LayerSet is no X3DChildNode but belongs at the root of a scene (X3D 4.0 clause
  // 35.4.2; docs/x3d.md, "Layering").
  if (parent == nullptr && child.model->id == NodeTypeId::LayerSet) return true;
  const NodeFieldModel* want = &rootField();
  if (parent != nullptr) {
    if (parent->model == nullptr || parent->script) return true;
    // Field names of built-in types live as long as the program: cache by address.
    struct Entry {
      const char* name = nullptr;
      const NodeFieldModel* model = nullptr;
    };
    thread_local std::array<Entry, 64> cache{};
    Entry& e = cache[(reinterpret_cast<std::uintptr_t>(field.data()) >> 3) & 63];
    if (e.name == field.data()) {
      want = e.model;
    } else {
      want = parent->model->findField(field);
      e = Entry{field.data(), want};
    }
    if (want == nullptr) return true;
  }
  if (acceptsNode(*want, *child.model)) return true;
  expected = describe(want->acceptableNodeTypes);
  return false;
}

}  // namespace gs::vrml::parsing
