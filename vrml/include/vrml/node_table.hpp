// The declarative table of built-in node types: the 54 VRML97 nodes of clause 6 plus
// GhostSpace's extension nodes, as the text of PROTO interface declarations. The node
// types themselves (encodings/node_types.hpp: builtInNodeType, x3dNodeType) are read from
// it by the Classic parser; tests iterate over every entry.
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

/// Number of VRML97 (non-extension) node types in the table: 54.
std::size_t vrml97NodeTypeCount();

/// True when `name` is an entry of the table (a VRML97 node or an extension).
bool inNodeTable(std::string_view name);

}  // namespace gs::vrml
