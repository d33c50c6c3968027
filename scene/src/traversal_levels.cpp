// The levels LODs and GeoLODs show, as output events for the execution model
// (SceneTraversal::takeDrawnOutputs; X3D 4.0 clauses 10.4.2 and 25.4.5).
#include "scene/traversal.hpp"

#include <algorithm>
#include <cstddef>

namespace gs::scene {

namespace {

/// Most output events kept for takeDrawnOutputs(): a caller that never takes them (a
/// benchmark flying through LODs, `info`) keeps the newest half when this many wait.
constexpr std::size_t kMaxPendingOutputs = 65536;

}  // namespace

void SceneTraversal::noteShownLevel(const vrml::Node& n, int level,
                                    const std::vector<vrml::NodePtr>* shown) {
  if (drawnOutputs_.size() >= kMaxPendingOutputs)
    drawnOutputs_.erase(drawnOutputs_.begin(), drawnOutputs_.begin() + static_cast<std::ptrdiff_t>(
                                                                           kMaxPendingOutputs / 2));
  auto [it, added] = shownLevels_.try_emplace(&n);
  ShownLevel& last = it->second;
  if (level >= 0 && (added || last.level != level)) {
    last.level = level;
    drawnOutputs_.push_back(
        {&n, "level_changed", vrml::FieldValue::make<vrml::FieldType::SFInt32>(level)});
  }
  if (shown == nullptr) return;
  const bool same =
      !added && last.nodes.size() == shown->size() &&
      std::equal(last.nodes.begin(), last.nodes.end(), shown->begin(),
                 [](const vrml::Node* a, const vrml::NodePtr& b) { return a == b.get(); });
  if (same) return;
  last.nodes.clear();
  for (const vrml::NodePtr& p : *shown) last.nodes.push_back(p.get());
  drawnOutputs_.push_back(
      {&n, "children", vrml::FieldValue::make<vrml::FieldType::MFNode>(*shown)});
}

}  // namespace gs::scene
