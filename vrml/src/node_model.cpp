// Look-ups over the generated node model (node_model_data.cpp).
#include "vrml/node_model.hpp"

#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>
#include <vector>

namespace gs::vrml {

/// The generated model's files (node_model_chunks.cpp): X3D's nodes alphabetical, then
/// the extensions, in order.
std::span<const std::span<const NodeModel>> nodeModelChunks();

namespace {

constexpr std::array<std::string_view, static_cast<std::size_t>(AbstractType::count)>
    kAbstractNames = {
#define GS_ABSTRACT_TYPE(name) #name,
#include "vrml/node_model_types.inc"
#undef GS_ABSTRACT_TYPE
};

struct Index {
  std::unordered_map<std::string_view, const NodeModel*> byName;
  std::array<const NodeModel*, static_cast<std::size_t>(NodeTypeId::count)> byId{};
};

const Index& index() {
  static const Index kIndex = [] {
    Index i;
    for (const NodeModel& m : nodeModels()) {
      i.byName.emplace(m.name, &m);
      i.byId[static_cast<std::size_t>(m.id)] = &m;
    }
    return i;
  }();
  return kIndex;
}

}  // namespace

std::span<const NodeModel> nodeModels() {
  static const std::vector<NodeModel> kModels = [] {
    std::vector<NodeModel> all;
    for (std::span<const NodeModel> chunk : nodeModelChunks())
      all.insert(all.end(), chunk.begin(), chunk.end());
    return all;
  }();
  return kModels;
}

const NodeFieldModel* NodeModel::findField(std::string_view field) const {
  for (const NodeFieldModel& f : fields)
    if (f.name == field) return &f;
  return nullptr;
}

const NodeModel* nodeModel(std::string_view name) {
  const auto& by = index().byName;
  const auto it = by.find(name);
  return it == by.end() ? nullptr : it->second;
}

const NodeModel* nodeModel(NodeTypeId id) {
  const auto i = static_cast<std::size_t>(id);
  return i < index().byId.size() ? index().byId[i] : nullptr;
}

std::string_view abstractTypeName(AbstractType t) {
  const auto i = static_cast<std::size_t>(t);
  return i < kAbstractNames.size() ? kAbstractNames[i] : std::string_view("?");
}

std::optional<AbstractType> abstractTypeNamed(std::string_view name) {
  for (std::size_t i = 0; i < kAbstractNames.size(); ++i)
    if (kAbstractNames[i] == name) return static_cast<AbstractType>(i);
  return std::nullopt;
}

bool acceptsNode(const NodeFieldModel& field, const NodeModel& child) {
  if (field.acceptTypes.empty() && field.acceptNodes.empty()) return true;
  if (field.acceptTypes.intersects(child.types)) return true;
  return std::find(field.acceptNodes.begin(), field.acceptNodes.end(), child.id) !=
         field.acceptNodes.end();
}

}  // namespace gs::vrml
