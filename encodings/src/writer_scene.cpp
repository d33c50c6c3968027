// What the writers need to know of a Scene's PROTOs and names (writer_impl.hpp): which
// nodes stand for instances, which body an instance copied, which PROTO types a body uses,
// and names as the Classic encoding can write them.
#include "vrml/proto.hpp"
#include "writer_impl.hpp"

#include <unordered_set>

namespace gs::vrml::writing {

// The definition whose body an instance of `type` copied (a resolved EXTERNPROTO's target).
const ProtoDefinition* bodyOf(const NodeType* type) {
  if (type == nullptr || !type->proto) return nullptr;
  if (type->proto->external)
    return type->proto->resolved ? bodyOf(type->proto->resolved.get()) : nullptr;
  return type->proto.get();
}

// True when `n` stands for a PROTO or EXTERNPROTO instance (expanded or not).
const NodeType* instanceType(const Node& n) {
  if (const ProtoInstance* p = declaredInterface(n)) return p->type.get();
  if (n.type().proto) return &n.type();  // unresolved EXTERNPROTO instance
  return nullptr;
}

std::vector<const NodeType*> instanceTypesIn(const ProtoDefinition& d) {
  std::vector<const NodeType*> out;
  std::unordered_set<const Node*> seen;
  std::vector<const Node*> stack;
  for (const NodePtr& n : d.body) stack.push_back(n.get());
  while (!stack.empty()) {
    const Node* n = stack.back();
    stack.pop_back();
    if (n == nullptr || !seen.insert(n).second) continue;
    auto push = [&](const FieldValue& v) {
      if (v.type() == FieldType::SFNode) stack.push_back(v.get<FieldType::SFNode>().get());
      if (v.type() == FieldType::MFNode)
        for (const NodePtr& c : v.get<FieldType::MFNode>()) stack.push_back(c.get());
    };
    if (const ProtoInstance* p = declaredInterface(*n)) {
      out.push_back(p->type.get());
      for (const FieldValue& v : p->values) push(v);
      continue;
    }
    for (std::size_t i = 0; i < n->fieldCount(); ++i) push(n->fieldAt(i));
  }
  return out;
}

std::string classicIdent(std::string_view raw) {
  std::string out;
  for (char c : raw) {
    const auto u = static_cast<unsigned char>(c);
    const bool bad = u <= 0x20 || u == 0x7f || c == '"' || c == '#' || c == '\'' || c == ',' ||
                     c == '.' || c == '[' || c == '\\' || c == ']' || c == '{' || c == '}';
    out += bad ? '_' : c;
  }
  if (!out.empty() && ((out[0] >= '0' && out[0] <= '9') || out[0] == '+' || out[0] == '-'))
    out.insert(out.begin(), '_');
  static constexpr std::string_view kKeywords[] = {
      "DEF",        "USE",      "PROTO",        "EXTERNPROTO",    "ROUTE",     "TO",
      "IS",         "NULL",     "TRUE",         "FALSE",          "IMPORT",    "EXPORT",
      "AS",         "PROFILE",  "COMPONENT",    "META",           "UNIT",      "field",
      "eventIn",    "eventOut", "exposedField", "initializeOnly", "inputOnly", "outputOnly",
      "inputOutput"};
  for (std::string_view k : kKeywords)
    if (out == k) out += '_';
  return out;
}

}  // namespace gs::vrml::writing
