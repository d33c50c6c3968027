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

}  // namespace gs::vrml
