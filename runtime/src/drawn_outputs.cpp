// Output events that drawing computes (vrml/drawn_output.hpp), sent by their nodes: a
// LOD's level_changed (X3D 4.0 clause 10.4.2), a GeoLOD's level_changed and children
// (25.4.5), a shader's isValid and isSelected (31.4), a TextureProjector's aspectRatio
// (42.4). The levels LODs show are kept for the sensors' walks (environment_sensors.cpp,
// pick_sensors.cpp), which read a GeoLOD's shown nodes from its `children`.
#include "execution_state.hpp"

#include <string_view>

namespace gs::runtime {

using vrml::FieldType;

void ExecutionModel::sendDrawnOutputs(const vrml::DrawnOutputs& outputs) {
  State& s = *s_;
  bool any = false;
  for (const vrml::DrawnOutput& out : outputs) {
    // A node of this world is kept alive by the model; the serial tells it from a node
    // made later at the address of one that went.
    const auto it = s.nodes.find(out.node.node);
    if (it == s.nodes.end() || it->second->unloaded ||
        it->second->node->serial() != out.node.serial)
      continue;
    const vrml::Node& node = *it->second->node;
    if (node.typeId() == vrml::NodeTypeId::LOD && std::string_view(out.field) == "level_changed" &&
        out.value.type() == FieldType::SFInt32)
      s.shownLevels[&node] = out.value.get<FieldType::SFInt32>();
    const int field = node.type().findExact(out.field);
    if (field < 0) continue;
    const vrml::FieldSpec& spec = node.type().fields[static_cast<std::size_t>(field)];
    if (spec.type != out.value.type() || spec.access == vrml::AccessType::eventIn ||
        spec.access == vrml::AccessType::field)
      continue;
    if (!any) s.beginTimestamp();  // one timestamp for all of them
    any = true;
    s.emitOwn(*it->second, field, out.value);
  }
  if (!any) return;
  s.runCascade();
  s.initializeScripts();
}

std::span<const vrml::NodePtr> ExecutionModel::State::shownNodes(const vrml::Node& n) const {
  if (n.typeId() == vrml::NodeTypeId::GeoLOD) {
    const auto& children = n.mfnode("children");
    return children.empty() ? std::span(n.mfnode("rootNode")) : std::span(children);
  }
  if (n.typeId() != vrml::NodeTypeId::LOD) return {};
  const auto& level = n.mfnode("level");
  const auto it = shownLevels.find(&n);
  const int shown = it != shownLevels.end() ? it->second : 0;
  if (shown < 0 || static_cast<std::size_t>(shown) >= level.size()) return {};
  return std::span(level).subspan(static_cast<std::size_t>(shown), 1);
}

}  // namespace gs::runtime
