// Builds the built-in NodeTypes from the declarative table (node_table_data.cpp) with the
// same code that reads PROTO interface declarations, so every default value is VRML97 text
// read by the real field-value parser.
#include "encodings/node_types.hpp"
#include "vrml/node_table.hpp"

#include "parser_impl.hpp"
#include "x3d_values.hpp"

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
    type->userFields = type->script;
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

// X3D's name for a VRML97 field that the parser maps back (Parser::x3dFieldAlias).
bool aliasedInX3d(NodeTypeId node, std::string_view field) {
  switch (node) {
    case NodeTypeId::Switch:
    case NodeTypeId::LOD:
      return field == "children" || field == "addChildren" || field == "removeChildren";
    case NodeTypeId::Collision:
      return field == "enabled";
    default:
      return false;
  }
}

// One field of the node model as a FieldSpec, its default read from X3DUOM's XML syntax.
FieldSpec specOf(const NodeFieldModel& f, const std::string& node) {
  FieldSpec spec;
  spec.name = f.name;
  if (f.type.starts_with("xs:"))  // X3DUOM's XML Schema types (xs:NMTOKEN names) are strings
    spec.type = FieldType::SFString;
  else if (!fieldTypeFromName(f.type, spec.type))
    throw std::logic_error("node model: " + node + "." + spec.name + " has unknown type " +
                           std::string(f.type));
  if (!accessTypeFromName(f.access, spec.access))
    throw std::logic_error("node model: " + node + "." + spec.name + " has unknown access " +
                           std::string(f.access));
  spec.defaultValue = FieldValue(spec.type);
  const bool carries = spec.access == AccessType::field || spec.access == AccessType::exposedField;
  if (!carries || f.defaultValue.empty() || spec.type == FieldType::SFNode ||
      spec.type == FieldType::MFNode)
    return spec;
  std::string warning;
  const std::string text = parsing::xmlValueToClassic(spec.type, f.defaultValue, warning);
  const ParseOptions options;
  parsing::Context ctx(options);
  Diagnostics diag;
  parsing::Parser parser(text, "node model: " + node + "." + spec.name, 0, ctx, diag, 0);
  try {
    spec.defaultValue = parser.parseValueText(spec.type);
  } catch (const ParseError&) {
    // X3DUOM writes a few defaults no value syntax reads ("-1 -1 -1" for an SFVec2f ...):
    // the type's own default stands.
  }
  return spec;
}

TypeMap buildX3dTypes() {
  TypeMap types;
  std::size_t size = 16;
  while (size < nodeModels().size() * 4) size *= 2;
  types.slots.resize(size);
  for (const NodeModel& m : nodeModels()) {
    const std::string name(m.name);
    auto type = std::make_shared<NodeType>();
    type->name = name;
    type->builtIn = true;
    type->extension = m.extension;
    type->model = &m;
    type->script = m.id == NodeTypeId::Script;
    type->userFields = type->script || m.is(AbstractType::X3DProgrammableShaderObject);
    if (std::shared_ptr<const NodeType> vrml97 = builtInNodeType(m.name)) {
      type->fields = vrml97->fields;
      // X3D made some VRML97 fields inputOutput (FontStyle.justify, ...): what X3D
      // worlds route to and connect by IS.
      for (FieldSpec& spec : type->fields)
        if (const NodeFieldModel* f = m.findField(spec.name); f != nullptr) {
          AccessType a;
          if (accessTypeFromName(f->access, a) && a == AccessType::exposedField &&
              spec.access == AccessType::field)
            spec.access = a;
        }
      for (const NodeFieldModel& f : m.fields)
        if (vrml97->findExact(f.name) < 0 && !aliasedInX3d(m.id, f.name))
          type->fields.push_back(specOf(f, name));
    } else {
      for (const NodeFieldModel& f : m.fields) type->fields.push_back(specOf(f, name));
    }
    types.emplace(m.name, std::move(type));
  }
  return types;
}

}  // namespace

std::shared_ptr<const NodeType> builtInNodeType(std::string_view name) {
  static const TypeMap kTypes = buildTypes();  // thread-safe initialisation (C++11 6.7)
  const std::shared_ptr<const NodeType>* t = kTypes.find(name);
  return t == nullptr ? nullptr : *t;
}

std::shared_ptr<const NodeType> x3dNodeType(std::string_view name) {
  static const TypeMap kTypes = buildX3dTypes();
  const std::shared_ptr<const NodeType>* t = kTypes.find(name);
  return t == nullptr ? nullptr : *t;
}

}  // namespace gs::vrml
