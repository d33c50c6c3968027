// PROTO instances as the node model keeps them (clause 4.8.3): the links from an instance's
// interface fields to the fields of its body, and the values its interface holds.
#include "vrml/proto.hpp"

#include <algorithm>

namespace gs::vrml {

namespace {

struct LinkOrder {
  bool operator()(const InstanceLink& a, int m) const { return a.protoField < m; }
  bool operator()(int m, const InstanceLink& a) const { return m < a.protoField; }
};

}  // namespace

std::span<const InstanceLink> ProtoInstance::linksOf(int member) const {
  auto range = std::equal_range(links.begin(), links.end(), member, LinkOrder{});
  return {range.first, range.second};
}

const ProtoInstance* declaredInterface(const Node& node) {
  const ProtoInstance* p = node.protoInstance.get();
  return (p != nullptr && p->type.get() != &node.type()) ? p : nullptr;
}

const FieldValue* ProtoInstance::value(int member) const {
  if (member < 0 || static_cast<std::size_t>(member) >= type->fields.size()) return nullptr;
  for (const InstanceLink& k : linksOf(member)) {
    if (k.nodeAccess != AccessType::field && k.nodeAccess != AccessType::exposedField) continue;
    if (const NodePtr n = k.node.lock()) return &n->fieldAt(static_cast<std::size_t>(k.nodeField));
  }
  const auto i = static_cast<std::size_t>(member);
  return i < values.size() ? &values[i] : nullptr;
}

}  // namespace gs::vrml
