// PROTO and EXTERNPROTO definitions (ISO/IEC 14772-1:1997 clauses 4.8 "Prototype
// semantics" and 4.9 "External prototype semantics"). A NodeType declared by a PROTO or
// EXTERNPROTO statement points to one of these through NodeType::proto. The parser
// expands every instance when it reads it (see Node), so renderers rarely need this
// header; it is for tools that inspect or re-instantiate prototypes.
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <memory>
#include <span>
#include <string>
#include <vector>

namespace gs::vrml {

/// One IS statement of a PROTO body, `nodeField IS protoField` (clause 4.8.3): the
/// member `node->type().fields[nodeField]` of a body node is connected to the interface
/// member `fields[protoField]` of the PROTO's NodeType. IS statements on nested PROTO
/// instances are flattened when the body is parsed, so `node` is always a node of a
/// built-in type, a Script, or an unresolved EXTERNPROTO instance.
struct IsConnection {
  NodePtr node;        // a node of ProtoDefinition::body (or hidden)
  int nodeField = -1;  // index into node->type().fields
  AccessType nodeAccess =
      AccessType::field;  // as named: `set_x` is an eventIn, `x_changed` an eventOut
  int protoField = -1;    // index into the PROTO NodeType's fields
};

/// The implementation of a PROTO, or the declaration of an EXTERNPROTO.
///
/// PROTO: `body` holds the implementation nodes as parsed (the template); an instance is
/// a deep copy of them (DEF/USE sharing kept) in which every field connected by IS gets
/// the instance's value or the interface default. The first body node's copy becomes the
/// instance in the scene graph; copies of the others go to Scene::hiddenNodes.
///
/// EXTERNPROTO: `external` is true, `urls` lists the URLs as written, and `resolved` is
/// the PROTO they named once loaded (instances then expand that PROTO), or null when none
/// could be loaded (instances are then Nodes of the declared interface, `unresolved`).
struct ProtoDefinition {
  std::string name;             // as declared
  SourceLocation location;      // of the PROTO / EXTERNPROTO keyword
  std::vector<NodePtr> body;    // implementation nodes, in order (PROTO only)
  std::vector<NodePtr> hidden;  // non-first body nodes of PROTO instances inside the body
  std::vector<IsConnection> connections;
  std::vector<Route> routes;  // ROUTEs of the body, between body nodes
  int height = 0;             // nesting levels of the deepest body node tree

  bool external = false;
  std::vector<std::string> urls;             // EXTERNPROTO URL list as written
  std::shared_ptr<const NodeType> resolved;  // EXTERNPROTO target PROTO, or null
  std::string resolvedUrl;                   // the URL that resolved, empty if none
  /// For a resolved EXTERNPROTO: for each declared member, the index of the member of the
  /// same name, type and access in `resolved`, or -1 (values given to it are ignored).
  std::vector<int> memberMap;
};

/// One IS link of a PROTO instance (clause 4.8.3): interface member `protoField` of the
/// instance is the member `nodeField` of the body node `node` (a copy made for this
/// instance). Weak, because the first body node is the instance's own node.
struct InstanceLink {
  std::weak_ptr<Node> node;
  int nodeField = -1;                         // index into node->type().fields
  AccessType nodeAccess = AccessType::field;  // as named in the IS statement
  int protoField = -1;                        // index into ProtoInstance::type->fields
};

/// What a PROTO instance is to the world (OpenVRML's proto_node, castle's kept source
/// instance): the type as declared, the values the instance gave its interface, and where
/// each interface member lives in the instance's copy of the body. The Node that stands
/// for the instance in the graph (the copy of the first body node) points to it through
/// Node::protoInstance. Scripts (SFNode fields), Browser.addRoute / deleteRoute and
/// `info` address the declared interface through it; ROUTE statements are resolved
/// through the same links by the parser.
struct ProtoInstance {
  std::shared_ptr<const NodeType> type;  // the PROTO or EXTERNPROTO as declared
  /// The instance's interface values as parsed (given, else the declared default),
  /// indexed like type->fields; meaningful for field and exposedField members.
  std::vector<FieldValue> values;
  std::vector<InstanceLink> links;  // sorted by protoField

  /// The links of interface member `member` (0 <= member < type->fields.size()); empty
  /// when the body connects nothing to it.
  std::span<const InstanceLink> linksOf(int member) const;
  /// The current value of field or exposedField `member`: that of the first linked body
  /// member that carries a value (field or exposedField), so an exposedField IS reads what
  /// events set in the body; else values[member]. Null when `member` is out of range.
  const FieldValue* value(int member) const;
};

/// The declared interface of the PROTO instance `node` stands for, or null when `node` is
/// a plain node or its own type already is that interface (an unresolved EXTERNPROTO
/// instance). What Scripts and Browser.addRoute address instead of the body node's fields.
const ProtoInstance* declaredInterface(const Node& node);

}  // namespace gs::vrml
