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

/// UNIT category name conversionFactor (X3D clause 4.3.6): the file's values of that
/// category are in units of `conversionFactor` base units (metres, radians, kilograms,
/// newtons).
struct X3dUnit {
  std::string category;  // "length", "angle", "mass" or "force"
  std::string name;
  double conversionFactor = 1.0;
};

/// IMPORT inlineDEF.exportedDEF AS localDEF / EXPORT localDEF AS exportedDEF (X3D clause
/// 4.4.6).
struct X3dImport {
  std::string inlineDef, exportedName, localName;
  NodePtr inlineNode;  // the Inline DEFed inlineDef; null when there is none
  SourceLocation location;
};
struct X3dExport {
  std::string localDef, exportedName;
  NodePtr node;  // the node DEFed localDef
  SourceLocation location;
};

/// A ROUTE with an end that names an IMPORTed node (X3D clause 4.4.6): it cannot be
/// checked or stored as a Route until the Inline's world has arrived and says what it
/// exports; the session resolves it then (session::WorldRuntimes) through the execution
/// model's addRoute, which reports a mismatch. An end that is no import has its node set.
struct X3dImportedRoute {
  NodePtr fromNode;        // null when `fromImport` names the source
  std::string fromImport;  // local name of an X3dImport, or empty
  std::string fromField;
  NodePtr toNode;
  std::string toImport;
  std::string toField;
  SourceLocation location;
};

/// What an X3D world declares about itself (ISO/IEC 19775-1 clause 7.2.5, the header
/// statements of the Classic VRML encoding and the XML encoding's <X3D> and <head>).
/// Empty (`version` "") for a VRML97 world.
struct X3dInfo {
  std::string version;   // "3.3", "4.0" ...: from the header; empty for VRML97
  std::string encoding;  // "Classic VRML", "XML" or "JSON"
  std::string profile;   // "Immersive", "Interchange" ...; empty when none was given
  std::vector<std::pair<std::string, int>> components;  // COMPONENT name:level
  std::vector<X3dUnit> units;
  std::vector<std::pair<std::string, std::string>> meta;  // META name content
  std::vector<X3dImport> imports;
  std::vector<X3dExport> exports;
  std::vector<X3dImportedRoute> importedRoutes;
  /// Names a Script gave with X3DExecutionContext.addNamedNode / updateNamedNode (ISO/IEC
  /// 19777-1 clause 7.4.11), in the order given: getNamedNode finds them first, whether
  /// or not the node is in the scene graph. Not written by the writer (the node's own
  /// defName is).
  std::vector<std::pair<std::string, NodePtr>> namedNodes;
  /// ROUTEs a Script's X3DExecutionContext.addRoute made, in order: X3DScene.routes lists
  /// them after the file's. Kept apart from Scene::routes, which the execution model reads
  /// as the file arrives (the route itself is made when it is added).
  std::vector<Route> scriptRoutes;
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
  X3dInfo x3d;  // X3D worlds only (x3d.version empty for VRML97)
};

}  // namespace gs::vrml
