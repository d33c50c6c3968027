// What the traversal (scene/src/traversal.cpp) computes outside its walk: a Layer's
// viewport rectangle and the OutlineGroups of a scene that have their polygons.
#include "scene/node_access.hpp"
#include "scene/node_kind.hpp"
#include "scene/traversal.hpp"

#include <algorithm>
#include <cmath>

namespace gs::scene {

glm::ivec4 layerRectangle(const glm::vec4& clipBoundary, int x, int y, int width, int height) {
  // As X_ITE's Viewport.getRectangle: floor of each edge, an empty rectangle when reversed.
  const auto edge = [](int origin, int size, float f) {
    return origin + static_cast<int>(std::floor(static_cast<float>(size) * f));
  };
  const int left = edge(x, width, clipBoundary.x);
  const int right = edge(x, width, clipBoundary.y);
  const int bottom = edge(y, height, clipBoundary.z);
  const int top = edge(y, height, clipBoundary.w);
  return {left, bottom, std::max(right - left, 0), std::max(top - bottom, 0)};
}

const std::unordered_set<std::int32_t>& SceneTraversal::filledGroups(const vrml::Scene& scene) {
  auto [it, inserted] = filledGroups_.try_emplace(&scene);
  if (!inserted) return it->second;
  // Every node reachable from the root nodes, shared (DEF/USE) nodes visited once.
  std::unordered_set<const vrml::Node*> seen;
  std::vector<const vrml::Node*> stack;
  for (const vrml::NodePtr& n : scene.rootNodes)
    if (n) stack.push_back(n.get());
  while (!stack.empty()) {
    const vrml::Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    if (nodeKind(*n) == NodeKind::OutlineGroup && !n->mfnode("children").empty()) {
      const int id = sfInt(*n, "groupId", -1);
      if (id >= 0) it->second.insert(id);
    }
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& f = n->fieldAt(i);
      if (f.type() == vrml::FieldType::SFNode) {
        if (const vrml::NodePtr& c = f.get<vrml::FieldType::SFNode>()) stack.push_back(c.get());
      } else if (f.type() == vrml::FieldType::MFNode) {
        for (const vrml::NodePtr& c : f.get<vrml::FieldType::MFNode>())
          if (c) stack.push_back(c.get());
      }
    }
  }
  return it->second;
}

}  // namespace gs::scene
