#include "node_kind.hpp"

#include <string_view>
#include <unordered_map>

namespace gs::render::detail {

NodeKind nodeKind(const vrml::Node& node) {
  if (node.unresolved) return NodeKind::other;
  static const std::unordered_map<std::string_view, NodeKind> kByName = {
      {"Anchor", NodeKind::Anchor},
      {"Billboard", NodeKind::Billboard},
      {"Collision", NodeKind::Collision},
      {"Group", NodeKind::Group},
      {"Transform", NodeKind::Transform},
      {"Switch", NodeKind::Switch},
      {"LOD", NodeKind::LOD},
      {"Inline", NodeKind::Inline},
      {"Shape", NodeKind::Shape},
      {"DirectionalLight", NodeKind::DirectionalLight},
      {"PointLight", NodeKind::PointLight},
      {"SpotLight", NodeKind::SpotLight},
      {"Viewpoint", NodeKind::Viewpoint},
      {"NavigationInfo", NodeKind::NavigationInfo},
      {"Background", NodeKind::Background},
      {"Fog", NodeKind::Fog},
      {"OutlineGroup", NodeKind::OutlineGroup},
      {"QuantizedNormalVectors", NodeKind::QuantizedNormalVectors},
  };
  const auto it = kByName.find(node.typeName());
  return it == kByName.end() ? NodeKind::other : it->second;
}

}  // namespace gs::render::detail
