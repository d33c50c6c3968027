// The scene graph stays a directed acyclic graph (X3D 4.0 clause 4.4.2.2, "Scene graph
// hierarchy"): an event that would make a node its own descendant (a Script's
// `g.children = new MFNode(t)` where t holds g, a ROUTE of children_changed into a child)
// is refused. Such a cycle is drawn only to the traversal's depth limit, and its nodes,
// which own one another, would never be freed. Fields that name nodes placed elsewhere may
// lead back to their node; when the world goes, those are emptied (breakReferenceCycles).
#include "execution_state.hpp"

#include <string_view>
#include <unordered_set>
#include <vector>

namespace gs::runtime {

using vrml::FieldType;

namespace {

/// Fields that name nodes placed elsewhere in the graph instead of holding them: a
/// Script's or a shader's own fields (an SFNode field is how a Script reaches a node,
/// an ancestor of its own included), TransformSensor.targetObject, the pick sensors'
/// pickTarget, LoadSensor's watched nodes (children in X3D 4, watchList in X3D 3). A node
/// may name its ancestor there; the walks do not follow them.
bool namesNodesElsewhere(const vrml::Node& node, std::size_t field) {
  if (node.type().userFields || node.typeId() == vrml::NodeTypeId::LoadSensor) return true;
  const std::string_view name = node.type().fields[field].name;
  return name == "targetObject" || name == "pickTarget" || name == "watchList";
}

/// Whether `target` is among the nodes `value` holds or leads to through node-valued fields,
/// those that name nodes elsewhere followed too when `allFields`.
bool leadsTo(const vrml::Node& target, const vrml::FieldValue& value, bool allFields) {
  std::vector<const vrml::Node*> pending;
  if (value.type() == FieldType::SFNode) {
    if (const vrml::NodePtr& n = value.get<FieldType::SFNode>()) pending.push_back(n.get());
  } else if (value.type() == FieldType::MFNode) {
    for (const vrml::NodePtr& n : value.get<FieldType::MFNode>())
      if (n) pending.push_back(n.get());
  }
  // Depth first without recursion over the nodes the value holds, each once.
  std::unordered_set<const vrml::Node*> seen;
  while (!pending.empty()) {
    const vrml::Node* n = pending.back();
    pending.pop_back();
    if (n == &target) return true;
    if (!seen.insert(n).second) continue;
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() != FieldType::SFNode && v.type() != FieldType::MFNode) continue;
      if (!allFields && namesNodesElsewhere(*n, i)) continue;
      if (v.type() == FieldType::SFNode) {
        if (const vrml::NodePtr& c = v.get<FieldType::SFNode>()) pending.push_back(c.get());
      } else {
        for (const vrml::NodePtr& c : v.get<FieldType::MFNode>())
          if (c) pending.push_back(c.get());
      }
    }
  }
  return false;
}

}  // namespace

bool wouldContainItself(const vrml::Node& target, int field, const vrml::FieldValue& value) {
  if (field < 0 || namesNodesElsewhere(target, static_cast<std::size_t>(field))) return false;
  return leadsTo(target, value, false);
}

void breakReferenceCycles(vrml::Node& node) {
  for (std::size_t i = 0; i < node.fieldCount(); ++i) {
    const vrml::FieldValue& v = node.fieldAt(i);
    if (v.type() != FieldType::SFNode && v.type() != FieldType::MFNode) continue;
    if (!namesNodesElsewhere(node, i) || !leadsTo(node, v, true)) continue;
    node.setField(i, vrml::FieldValue(v.type()));
  }
}

}  // namespace gs::runtime
