#include "vrml/node.hpp"

#include "vrml/proto.hpp"

#include <atomic>

namespace gs::vrml {

namespace {

// Serials are handed out in blocks per thread (parsers run on several threads), so a
// node costs no contended atomic operation.
std::atomic<std::uint64_t> nextSerialBlock{0};

std::uint64_t nextSerial() {
  constexpr std::uint64_t kBlock = 4096;
  thread_local std::uint64_t next = 0, end = 0;
  if (next == end) {
    next = nextSerialBlock.fetch_add(kBlock, std::memory_order_relaxed) + 1;
    end = next + kBlock;
  }
  return next++;
}

}  // namespace

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

Node::Node(std::shared_ptr<const NodeType> type) : type_(std::move(type)), serial_(nextSerial()) {
  values_.reserve(type_->fields.size());
  for (const FieldSpec& f : type_->fields) values_.push_back(f.defaultValue);
}

namespace {

/// Moves every node value of `values` to the end of `out` (the fields keep NULL / empty).
void takeNodeValues(std::vector<FieldValue>& values, std::vector<NodePtr>& out) {
  for (FieldValue& v : values) {
    if (v.type() == FieldType::SFNode) {
      if (NodePtr& n = v.get<FieldType::SFNode>()) out.push_back(std::move(n));
    } else if (v.type() == FieldType::MFNode) {
      std::vector<NodePtr>& list = v.get<FieldType::MFNode>();
      for (NodePtr& n : list)
        if (n) out.push_back(std::move(n));
      list.clear();
    }
  }
}

}  // namespace

Node::~Node() {
  // The interface first: its node values are the fields' too, mostly (an IS map), and
  // this node's references keep them alive while it goes.
  protoInstance.reset();
  std::vector<NodePtr> pending;
  takeNodeValues(values_, pending);
  while (!pending.empty()) {
    NodePtr n = std::move(pending.back());
    pending.pop_back();
    // The last owner: the node's own values join the list before it is destroyed, so its
    // destructor finds none to release. (An alias without ownership counts 0: left alone.)
    if (n.use_count() == 1) {
      n->protoInstance.reset();
      takeNodeValues(n->values_, pending);
    }
  }
}

Node::Node(const Node& other)
    : type_(other.type_),
      values_(other.values_),
      revision_(other.revision_),
      serial_(nextSerial()),
      defName(other.defName),
      protoInstance(other.protoInstance),
      unresolved(other.unresolved),
      location(other.location),
      urlBase(other.urlBase) {}

Node& Node::operator=(const Node& other) {
  if (this == &other) return *this;
  defName = other.defName;
  protoInstance = other.protoInstance;
  unresolved = other.unresolved;
  location = other.location;
  urlBase = other.urlBase;
  type_ = other.type_;
  values_ = other.values_;
  revision_ = other.revision_ + 1;
  serial_ = nextSerial();
  return *this;
}

const std::string& Node::protoName() const {
  static const std::string kNone;
  return protoInstance ? protoInstance->type->name : kNone;
}

const NodePtr& Node::sfnode(FieldName name) const {
  static const NodePtr kNull;
  const FieldValue* f = field(name);
  return (f != nullptr && f->type() == FieldType::SFNode) ? f->get<FieldType::SFNode>() : kNull;
}

const std::vector<NodePtr>& Node::mfnode(FieldName name) const {
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
  // An X3D geometry's vertex attribute nodes (X3D 4.0 clause 31.4): part of its mesh.
  for (const NodePtr& c : node.mfnode("attrib"))
    if (c) r += c->revision();
  return r;
}

}  // namespace gs::vrml
