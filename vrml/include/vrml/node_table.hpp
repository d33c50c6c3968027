// The declarative table of built-in node types: the 54 VRML97 nodes of clause 6 plus
// GhostSpace's extension nodes. The parser, default values and checks all derive from
// it; tests iterate over every entry.
#pragma once

#include "vrml/node.hpp"

#include <memory>
#include <span>
#include <string_view>

namespace gs::vrml {

/// One row of the table as written in the source: the interface of a node as text,
/// in the exact syntax of a PROTO interface declaration, e.g.
/// "exposedField SFVec3f translation 0 0 0". Default values are VRML97 text parsed once.
struct NodeTableEntry {
  std::string_view name;
  std::string_view interface;  // newline-separated declarations
  bool extension = false;
};

/// All built-in entries (54 VRML97 nodes first, in clause 6 order, then extensions).
std::span<const NodeTableEntry> nodeTableEntries();

/// The built-in type called `name`, or nullptr. Built once, on first use, thread-safe.
std::shared_ptr<const NodeType> builtInNodeType(std::string_view name);

/// The type called `name` as an X3D world sees it (ISO/IEC 19775-1:2023): for a VRML97
/// node (and the extensions) its VRML97 interface, field names and defaults unchanged,
/// followed by the fields X3D 4.0 adds to it (metadata, solid, visible, ...); for a node
/// X3D added, its X3D 4.0 interface from the node model (node_model.hpp), defaults
/// included. Switch's and LOD's X3D `children` and Collision's `enabled` are not added:
/// the parser reads them as VRML97's `choice`, `level` and `collide`. nullptr when the
/// name is no node of either. Built once, on first use, thread-safe.
std::shared_ptr<const NodeType> x3dNodeType(std::string_view name);

/// Number of VRML97 (non-extension) node types in the table: 54.
std::size_t vrml97NodeTypeCount();

}  // namespace gs::vrml
