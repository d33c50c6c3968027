// The levels LODs and GeoLODs show, as output events for the execution model
// (SceneTraversal::takeDrawnOutputs; X3D 4.0 clauses 10.4.2 and 25.4.5).
#include "scene/traversal.hpp"

#include <algorithm>
#include <array>
#include <cstddef>

namespace gs::scene {

namespace {

/// Most output events kept for takeDrawnOutputs(): a caller that never takes them (a
/// benchmark flying through LODs, `info`) keeps the newest half when this many wait.
constexpr std::size_t kMaxPendingOutputs = 65536;

}  // namespace

void SceneTraversal::noteShownLevel(const vrml::Node& n, int level,
                                    const std::vector<vrml::NodePtr>* shown) {
  const std::array<const std::vector<vrml::NodePtr>*, 1> one = {shown};
  noteShownLevel(n, level, shown != nullptr ? std::span(one) : std::span(one).first(0));
}

void SceneTraversal::noteShownLevel(const vrml::Node& n, int level,
                                    std::span<const std::vector<vrml::NodePtr>* const> shown) {
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
  if (shown.empty()) return;
  // The same nodes as last time, compared list by list without a copy (every frame).
  bool same = !added;
  std::size_t at = 0;
  for (const std::vector<vrml::NodePtr>* list : shown)
    for (const vrml::NodePtr& p : *list) {
      if (!same) break;
      same = at < last.nodes.size() && last.nodes[at] == p.get();
      ++at;
    }
  if (same && at == last.nodes.size()) return;
  last.nodes.clear();
  std::vector<vrml::NodePtr> nodes;
  for (const std::vector<vrml::NodePtr>* list : shown)
    for (const vrml::NodePtr& p : *list) {
      last.nodes.push_back(p.get());
      nodes.push_back(p);
    }
  drawnOutputs_.push_back(
      {&n, "children", vrml::FieldValue::make<vrml::FieldType::MFNode>(std::move(nodes))});
}

}  // namespace gs::scene
