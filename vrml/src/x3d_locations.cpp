#include "x3d_locations.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace gs::vrml::parsing {

void LocationMapper::skipTo(const Scene& scene) {
  done_ = {scene.diagnostics.items.size(), scene.rootNodes.size(),
           scene.hiddenNodes.size(),       scene.routes.size(),
           scene.x3d.imports.size(),       scene.x3d.exports.size()};
}

bool LocationMapper::insertMapped(const Node* n) {
  if (2 * (mappedCount_ + 1) > mapped_.size()) {
    std::vector<const Node*> old(std::max<std::size_t>(64, 2 * mapped_.size()), nullptr);
    old.swap(mapped_);
    mappedCount_ = 0;
    for (const Node* o : old)
      if (o != nullptr) insertMapped(o);
  }
  const std::size_t mask = mapped_.size() - 1;
  // Nodes are heap blocks of at least 16 bytes: the low bits say little.
  auto h = reinterpret_cast<std::uintptr_t>(n) >> 4;
  h ^= h >> 17;
  h *= 0x9E3779B97F4A7C15ull;
  for (std::size_t i = (h >> 20) & mask;; i = (i + 1) & mask) {
    if (mapped_[i] == n) return false;
    if (mapped_[i] == nullptr) {
      mapped_[i] = n;
      ++mappedCount_;
      return true;
    }
  }
}

void LocationMapper::map(Scene& scene, const std::string& url, const Locate& locate) {
  auto move = [&](SourceLocation& l) {
    if (l.line <= 0 || l.file != url) return;
    const auto [line, column] = locate(l.line);
    if (line <= 0) return;
    l.line = line;
    l.column = column;
  };
  auto from = [](std::size_t& done, std::size_t size) {
    const std::size_t f = std::min(done, size);
    done = size;
    return f;
  };
  auto& items = scene.diagnostics.items;
  for (std::size_t i = from(done_.diagnostics, items.size()); i < items.size(); ++i)
    move(items[i].location);
  std::vector<Node*> todo;
  auto push = [&](const NodePtr& n) {
    if (n && insertMapped(n.get())) todo.push_back(n.get());
  };
  for (std::size_t i = from(done_.roots, scene.rootNodes.size()); i < scene.rootNodes.size(); ++i)
    push(scene.rootNodes[i]);
  for (std::size_t i = from(done_.hidden, scene.hiddenNodes.size()); i < scene.hiddenNodes.size();
       ++i)
    push(scene.hiddenNodes[i]);
  for (std::size_t i = from(done_.routes, scene.routes.size()); i < scene.routes.size(); ++i) {
    Route& r = scene.routes[i];
    move(r.location);
    push(r.fromNode);
    push(r.toNode);
  }
  auto& imports = scene.x3d.imports;
  for (std::size_t i = from(done_.imports, imports.size()); i < imports.size(); ++i)
    move(imports[i].location);
  auto& exports = scene.x3d.exports;
  for (std::size_t i = from(done_.exports, exports.size()); i < exports.size(); ++i)
    move(exports[i].location);
  while (!todo.empty()) {
    Node* n = todo.back();
    todo.pop_back();
    move(n->location);
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const FieldValue& v = n->fieldAt(i);
      if (v.type() == FieldType::SFNode)
        push(v.get<FieldType::SFNode>());
      else if (v.type() == FieldType::MFNode)
        for (const NodePtr& c : v.get<FieldType::MFNode>()) push(c);
    }
  }
}

}  // namespace gs::vrml::parsing
