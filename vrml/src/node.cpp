#include "vrml/node.hpp"

namespace gs::vrml {

int NodeType::findExact(std::string_view n) const {
  for (std::size_t i = 0; i < fields.size(); ++i)
    if (fields[i].name == n) return static_cast<int>(i);
  return -1;
}

int NodeType::findField(std::string_view n) const {
  if (int i = findExact(n); i >= 0) return i;
  // exposedField aliases: set_x is the eventIn of x, x_changed its eventOut (4.10.3).
  constexpr std::string_view kSet = "set_", kChanged = "_changed";
  std::string_view base;
  if (n.starts_with(kSet))
    base = n.substr(kSet.size());
  else if (n.ends_with(kChanged))
    base = n.substr(0, n.size() - kChanged.size());
  if (base.empty()) return -1;
  int i = findExact(base);
  return (i >= 0 && fields[static_cast<std::size_t>(i)].access == AccessType::exposedField) ? i
                                                                                            : -1;
}

Node::Node(std::shared_ptr<const NodeType> type) : type_(std::move(type)) {
  values_.reserve(type_->fields.size());
  for (const FieldSpec& f : type_->fields) values_.push_back(f.defaultValue);
}

const FieldValue* Node::field(std::string_view name) const {
  int i = type_->findExact(name);
  return i < 0 ? nullptr : &values_[static_cast<std::size_t>(i)];
}

FieldValue* Node::field(std::string_view name) {
  int i = type_->findExact(name);
  return i < 0 ? nullptr : &values_[static_cast<std::size_t>(i)];
}

NodePtr Node::sfnode(std::string_view name) const {
  const FieldValue* f = field(name);
  return (f != nullptr && f->type() == FieldType::SFNode) ? f->get<FieldType::SFNode>() : nullptr;
}

const std::vector<NodePtr>& Node::mfnode(std::string_view name) const {
  static const std::vector<NodePtr> kEmpty;
  const FieldValue* f = field(name);
  return (f != nullptr && f->type() == FieldType::MFNode) ? f->get<FieldType::MFNode>() : kEmpty;
}

std::uint64_t revisionWithFields(const Node& node) {
  std::uint64_t r = node.revision();
  for (std::size_t i = 0; i < node.fieldCount(); ++i) {
    const FieldValue& v = node.fieldAt(i);
    if (v.type() == FieldType::SFNode)
      if (const NodePtr& c = v.get<FieldType::SFNode>()) r += c->revision();
  }
  return r;
}

}  // namespace gs::vrml
