// Walking a parsed scene in the vrml tests: every node reachable from the root nodes
// through SFNode and MFNode fields, each once (DEF/USE shares are visited once).
#pragma once

#include "vrml/scene.hpp"

#include <cstddef>
#include <map>
#include <string>
#include <unordered_set>
#include <vector>

namespace gs::test {

/// Calls `visit(const vrml::Node&)` for every node reachable from `scene`'s roots, once
/// each, depth first; stops early when `visit` returns true (then returns that node).
template <class Visit>
const vrml::Node* findNode(const vrml::Scene& scene, Visit visit) {
  std::unordered_set<const vrml::Node*> seen;
  std::vector<const vrml::Node*> todo;
  for (const vrml::NodePtr& n : scene.rootNodes) todo.push_back(n.get());
  while (!todo.empty()) {
    const vrml::Node* n = todo.back();
    todo.pop_back();
    if (n == nullptr || !seen.insert(n).second) continue;
    if (visit(*n)) return n;
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() == vrml::FieldType::SFNode)
        todo.push_back(v.get<vrml::FieldType::SFNode>().get());
      if (v.type() == vrml::FieldType::MFNode)
        for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>()) todo.push_back(c.get());
    }
  }
  return nullptr;
}

/// The first node of type `type` findNode meets, or nullptr.
inline const vrml::Node* firstOfType(const vrml::Scene& scene, std::string_view type) {
  return findNode(scene, [&](const vrml::Node& n) { return n.typeName() == type; });
}

/// How many nodes of each type are reachable from the roots.
inline std::map<std::string, int> countTypes(const vrml::Scene& scene) {
  std::map<std::string, int> counts;
  findNode(scene, [&](const vrml::Node& n) {
    ++counts[n.typeName()];
    return false;
  });
  return counts;
}

/// How many nodes are reachable from the roots.
inline std::size_t countNodes(const vrml::Scene& scene) {
  std::size_t count = 0;
  findNode(scene, [&](const vrml::Node&) {
    ++count;
    return false;
  });
  return count;
}

}  // namespace gs::test
