// Builds the built-in NodeTypes from the declarative table (node_table_data.cpp) with the
// same code that reads PROTO interface declarations, so every default value is VRML97 text
// read by the real field-value parser.
#include "vrml/node_table.hpp"

#include "parser_impl.hpp"

#include <cstdint>
#include <stdexcept>
#include <vector>

namespace gs::vrml {

namespace {

// FNV-1a: cheap for the short names looked up once per node.
std::uint32_t nameHash(std::string_view s) {
  std::uint32_t h = 2166136261u;
  for (char c : s) h = (h ^ static_cast<unsigned char>(c)) * 16777619u;
  return h;
}

/// An open-addressing table (power-of-two size, linear probing) built once.
struct TypeMap {
  std::vector<std::shared_ptr<const NodeType>> slots;
  bool emplace(std::string_view name, std::shared_ptr<const NodeType> type) {
    const std::size_t mask = slots.size() - 1;
    for (std::size_t i = nameHash(name) & mask;; i = (i + 1) & mask) {
      if (!slots[i]) {
        slots[i] = std::move(type);
        return true;
      }
      if (slots[i]->name == name) return false;
    }
  }
  const std::shared_ptr<const NodeType>* find(std::string_view name) const {
    const std::size_t mask = slots.size() - 1;
    for (std::size_t i = nameHash(name) & mask; slots[i]; i = (i + 1) & mask)
      if (slots[i]->name == name) return &slots[i];
    return nullptr;
  }
};

TypeMap buildTypes() {
  TypeMap types;
  std::size_t size = 16;
  while (size < nodeTableEntries().size() * 4) size *= 2;
  types.slots.resize(size);
  const ParseOptions options;
  for (const NodeTableEntry& e : nodeTableEntries()) {
    parsing::Context ctx(options);
    Diagnostics diag;
    parsing::Parser parser(e.interface, "node table: " + std::string(e.name), 0, ctx, diag, 0);
    auto type = std::make_shared<NodeType>();
    type->name = e.name;
    type->builtIn = true;
    type->extension = e.extension;
    type->model = nodeModel(e.name);
    if (type->model == nullptr)
      throw std::logic_error("node table entry '" + std::string(e.name) + "' has no node model");
    type->script = type->model->id == NodeTypeId::Script;
    try {
      type->fields = parser.parseInterfaceText(e.name);
    } catch (const ParseError& err) {
      throw std::logic_error(std::string("bad node table entry: ") + err.what());
    }
    if (!types.emplace(e.name, std::move(type)))
      throw std::logic_error("node table entry '" + std::string(e.name) + "' appears twice");
  }
  return types;
}

}  // namespace

std::shared_ptr<const NodeType> builtInNodeType(std::string_view name) {
  static const TypeMap kTypes = buildTypes();  // thread-safe initialisation (C++11 6.7)
  const std::shared_ptr<const NodeType>* t = kTypes.find(name);
  return t == nullptr ? nullptr : *t;
}

}  // namespace gs::vrml
