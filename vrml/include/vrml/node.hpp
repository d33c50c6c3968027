// Node types and node instances (ISO/IEC 14772-1:1997, clauses 4.5 "Nodes" and 6
// "Node reference"). The built-in types come from one declarative table
// (node_table.hpp); PROTO and EXTERNPROTO declarations create further NodeTypes.
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/field.hpp"
#include "vrml/field_name.hpp"
#include "vrml/node_model.hpp"

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace gs::vrml {

/// One interface declaration of a node type: `exposedField SFVec3f translation 0 0 0`.
struct FieldSpec {
  std::string name;
  FieldType type = FieldType::SFBool;
  AccessType access = AccessType::field;
  FieldValue defaultValue;  // meaningful for field and exposedField only
};

struct ProtoDefinition;  // proto.hpp
struct ProtoInstance;    // proto.hpp

/// A node type: a built-in VRML97 node, one of our extension nodes, or a PROTO /
/// EXTERNPROTO declared in a file.
struct NodeType {
  std::string name;
  std::vector<FieldSpec> fields;  // every field, exposedField, eventIn and eventOut
  bool builtIn = false;           // from the node table
  bool extension = false;         // a GhostSpace extension node (docs/vrml-extensions.md)
  bool script = false;            // Script (clause 6.40): run by the Script host
  /// Nodes that declare fields of their own in their body: Script (clause 6.40) and X3D's
  /// X3DProgrammableShaderObject nodes (ComposedShader, ShaderProgram, PackagedShader).
  bool userFields = false;
  /// For PROTO / EXTERNPROTO types: the definition; null for built-ins.
  std::shared_ptr<const ProtoDefinition> proto;
  /// What the type is in X3D's terms (abstract types, component, level): the node model
  /// of a built-in or extension type; null for PROTO and EXTERNPROTO types.
  const NodeModel* model = nullptr;

  /// The concrete type, NodeTypeId::unknown for PROTO / EXTERNPROTO types.
  NodeTypeId id() const { return model != nullptr ? model->id : NodeTypeId::unknown; }
  /// True when the type inherits the X3D abstract type `t` (X3DGroupingNode ...);
  /// false for PROTO / EXTERNPROTO types.
  bool is(AbstractType t) const { return model != nullptr && model->is(t); }

  /// Index into `fields` of the interface member called `name`, also accepting the
  /// exposedField aliases `set_name` and `name_changed` (clause 4.10.3); -1 if none.
  int findField(std::string_view name) const;
  /// Index of the member called exactly `name` (no aliases); -1 if none.
  int findExact(std::string_view name) const;
  /// findExact(field.name()), answered from a per-type table when the name is a FieldKey
  /// (the table is filled on first use and safe to read from several threads). The type's
  /// interface must be complete before the first call (types are, before nodes of them).
  int indexOf(FieldName field) const {
    if (field.key() == FieldKey::none) return findExact(field.name());
    std::atomic<std::int16_t>& slot = keyIndex_.slots[static_cast<std::size_t>(field.key())];
    int i = slot.load(std::memory_order_relaxed);
    if (i == KeyIndexCache::kUnknown) {
      i = findExact(field.name());
      slot.store(static_cast<std::int16_t>(i), std::memory_order_relaxed);
    }
    return i;
  }

 private:
  /// FieldKey -> index, kUnknown until asked. A copy starts empty (the copy's interface may
  /// grow: a Script's per-instance type).
  struct KeyIndexCache {
    static constexpr std::int16_t kUnknown = -2;
    std::array<std::atomic<std::int16_t>, kFieldKeyCount> slots;
    KeyIndexCache() { reset(); }
    KeyIndexCache(const KeyIndexCache&) { reset(); }
    KeyIndexCache& operator=(const KeyIndexCache&) {
      reset();
      return *this;
    }
    ~KeyIndexCache() = default;
    void reset() {
      for (auto& s : slots) s.store(kUnknown, std::memory_order_relaxed);
    }
  };
  mutable KeyIndexCache keyIndex_;
};

/// One node instance in a scene graph. Field values are indexed like `type->fields`.
/// A PROTO instance is expanded when parsed: the Node in the graph is a copy of the
/// PROTO's first implementation node with IS fields substituted, and `protoInstance`
/// keeps what the instance is to the world: the PROTO as declared, the instance's
/// interface values and its IS map (clause 4.8.3), through which Scripts, ROUTEs,
/// Browser.addRoute and `info` address the declared interface. An instance of an
/// EXTERNPROTO that could not be resolved keeps its declared interface as `type` and is
/// not rendered (`unresolved` is true).
class Node {
  // First, so that the fields and the revision share the object's first cache line with
  // its type (an event cascade reads them in that order; runtime prefetches that line).
  std::shared_ptr<const NodeType> type_;
  std::vector<FieldValue> values_;
  std::uint64_t revision_ = 0;
  std::uint64_t serial_;

 public:
  explicit Node(std::shared_ptr<const NodeType> type);
  /// A copy has the same type, fields and names as `other`, and a serial() of its own.
  Node(const Node& other);
  Node& operator=(const Node& other);
  /// Moving keeps the moved-from node's serial() (the node it becomes is that node).
  Node(Node&& other) noexcept = default;
  Node& operator=(Node&& other) noexcept = default;
  /// Releases the node's SFNode and MFNode values without recursion: a child this node
  /// owns alone gives up its own node values first, and so on down, from one list. A
  /// chain of nodes deeper than the stack allows (a Script can build one, a node at a
  /// time) is freed as a flat one. (Node values held only by a PROTO instance's
  /// interface, or a Script type's defaults, are still freed by their own destructors.)
  ~Node();

  /// A number no other Node of this process had or will have (1, 2, ...; never 0): what a
  /// cache keyed by a node's address stores beside its entry, so that a node allocated at
  /// the address of a freed one does not inherit the freed one's entry.
  std::uint64_t serial() const { return serial_; }

  const NodeType& type() const { return *type_; }
  const std::shared_ptr<const NodeType>& typePtr() const { return type_; }
  /// The VRML97 type name, e.g. "Transform".
  const std::string& typeName() const { return type_->name; }
  /// The concrete type from the node model; NodeTypeId::unknown for PROTO / EXTERNPROTO
  /// types (an expanded PROTO instance has its first body node's type).
  NodeTypeId typeId() const { return type_->id(); }
  /// True when the node's type inherits the X3D abstract type `t` (node_model.hpp).
  bool is(AbstractType t) const { return type_->is(t); }

  /// Value of the field or exposedField `name`; nullptr when the type has no such field.
  /// A literal name listed in field_name.hpp costs one table load (NodeType::indexOf).
  const FieldValue* field(FieldName name) const {
    const int i = type_->indexOf(name);
    return i < 0 ? nullptr : &values_[static_cast<std::size_t>(i)];
  }
  FieldValue* field(FieldName name) {
    const int i = type_->indexOf(name);
    return i < 0 ? nullptr : &values_[static_cast<std::size_t>(i)];
  }
  /// Value at index `i` of type().fields (0 <= i < fields().size()).
  const FieldValue& fieldAt(std::size_t i) const { return values_[i]; }
  FieldValue& fieldAt(std::size_t i) { return values_[i]; }
  std::size_t fieldCount() const { return values_.size(); }

  /// Writes `value` into field `i` (0 <= i < fieldCount(); same type as the field) and
  /// bumps revision(). The execution model (runtime/) writes fields only through this, so
  /// caches keyed by node (tessellations, GPU buffers) can tell that a node changed.
  void setField(std::size_t i, FieldValue value) {
    values_[i] = std::move(value);
    ++revision_;
  }
  /// Counts the writes made through setField() (and markChanged()) since construction;
  /// 0 for a node as parsed. A cache that stored revision() r is stale iff r differs.
  std::uint64_t revision() const { return revision_; }
  /// Bumps revision() after a write made through fieldAt() (e.g. one element of an MF).
  void markChanged() { ++revision_; }

  /// Convenience typed getters for renderers: the value of field `name` when it exists
  /// and has type T, else `fallback`.
  template <FieldType T, class V>
  V get(FieldName name, V fallback) const {
    const FieldValue* f = field(name);
    if (f == nullptr || f->type() != T) return fallback;
    return f->get<T>();
  }
  /// The SFNode field `name` (nullptr when absent or NULL).
  const NodePtr& sfnode(FieldName name) const;
  /// The MFNode field `name` (empty when absent).
  const std::vector<NodePtr>& mfnode(FieldName name) const;

  /// The PROTO (or EXTERNPROTO) name when this node stands for a PROTO instance, else
  /// empty.
  const std::string& protoName() const;

  std::string defName;  // DEF name, empty when none
  /// The PROTO instance this node stands for (proto.hpp), null for plain nodes.
  std::shared_ptr<const ProtoInstance> protoInstance;
  bool unresolved = false;  // instance of an EXTERNPROTO that could not be loaded
  SourceLocation location;  // where the node's type name appeared
  /// For a node written in a file reached through EXTERNPROTO (a PROTO body there, its
  /// interface defaults, and every copy an instance makes of them): that file's URL as
  /// it was fetched (resolved against the file that named it; base/url.hpp). Null for a
  /// node of the world (or Inline) file itself, which resolves against the base its
  /// reader is given. Shared by the nodes of one file.
  std::shared_ptr<const std::string> urlBase;

  /// The base the node's url fields (textures, Inline, movies, sounds, shader parts)
  /// resolve against (X3D 4.0 clause 9.2.1 read as castle-engine does: relative to the
  /// file where the node was written, so a node of an external PROTO's body finds the
  /// files beside that PROTO's file): *urlBase when set, else `inherited` (the world or
  /// Inline file the node came with). Passing the result as a Fetcher's referrer keeps
  /// its rule: a body fetched over http(s) reads no local file. The reference is to
  /// `inherited` or to *urlBase: `inherited` must outlive its use (no temporary).
  const std::string& urlBaseOr(const std::string& inherited) const {
    return urlBase ? *urlBase : inherited;
  }
};

/// The key of a cache of per-node data (tessellations, GPU buffers, textures, decoded
/// clips): the node's address and its serial(), so an entry made for a node never serves
/// a node allocated later at the same address (node identity). Converts implicitly from a
/// node pointer, so `cache.find(&node)` reads as with an address key.
struct NodeKey {
  const Node* node = nullptr;
  std::uint64_t serial = 0;

  NodeKey() = default;
  NodeKey(const Node* n)  // NOLINT(google-explicit-constructor): a key is a node
      : node(n), serial(n != nullptr ? n->serial() : 0) {}
  bool operator==(const NodeKey&) const = default;
};

/// Hash of a NodeKey (its serial, unique per process).
struct NodeKeyHash {
  std::size_t operator()(const NodeKey& k) const noexcept {
    return std::hash<std::uint64_t>{}(k.serial);
  }
};

/// A cache of per-node data keyed by node identity (NodeKey).
template <class V>
using NodeMap = std::unordered_map<NodeKey, V, NodeKeyHash>;

/// revision() of `node` plus those of the nodes in its SFNode fields (one level) and in
/// its `attrib` field (an X3D geometry's vertex attribute nodes, clause 31.4): what a
/// cache of a geometry (its Coordinate, Normal, Color, TextureCoordinate, attributes) or
/// an Appearance (its Material, texture, TextureTransform) compares to know it is stale.
std::uint64_t revisionWithFields(const Node& node);

}  // namespace gs::vrml
