// A parsed VRML97 world: root nodes, routes, PROTO declarations and diagnostics
// (clause 4.4 "Scene graph structure").
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/node.hpp"

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gs::vrml {

/// ROUTE fromNode.eventOut TO toNode.eventIn (clause 4.10.2), checked when parsed:
/// both nodes exist, the source is an eventOut or exposedField, the destination an
/// eventIn or exposedField, and the types are equal. Executed by a later stage.
/// A ROUTE to or from a PROTO instance's interface is stored once per body member that
/// member is connected to by IS (clause 4.8.3), naming that member; one whose member is
/// connected to nothing is checked and then dropped. ROUTEs inside a PROTO body are
/// stored for each instance, between the instance's copies of the body nodes.
struct Route {
  NodePtr fromNode;
  std::string fromField;  // as written in the file (or the IS-connected body member)
  NodePtr toNode;
  std::string toField;
  SourceLocation location;
};

/// A world read from one file or URL.
struct Scene {
  std::string url;                 // where it was read from, as given
  std::vector<NodePtr> rootNodes;  // in file order, PROTO instances expanded
  std::vector<Route> routes;
  std::vector<std::shared_ptr<const NodeType>> protos;  // PROTO/EXTERNPROTO of the file
  /// Nodes that belong to the world but are not rendered: the second and later nodes of
  /// each PROTO instance's body (clause 4.8.3), kept alive for ROUTEs and Scripts.
  std::vector<NodePtr> hiddenNodes;
  Diagnostics diagnostics;
};

}  // namespace gs::vrml
