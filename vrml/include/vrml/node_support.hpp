// What GhostSpace does with each X3D node type: every one is read (its X3D 4.0 interface,
// node_table.hpp x3dNodeType), and some are also implemented: given their behaviour as
// ISO/IEC 19775-1 says (drawn, animated or sensing). docs/x3d.md's status table is
// generated from this list (docs/gen/gen_x3d_status.py reads node_support.cpp).
#pragma once

#include "vrml/node_model.hpp"

#include <string_view>
#include <vector>

namespace gs::vrml {

/// True when node type `id` is implemented, not only read: VRML97's 54 nodes, the
/// GhostSpace extensions and the X3D nodes listed in node_support.cpp. False for
/// NodeTypeId::unknown.
bool nodeImplemented(NodeTypeId id);

/// The nodes of X3D component `component` (e.g. "Rendering") introduced at levels 1 to
/// `level` that are read but not implemented, in the node model's order; empty when the
/// component is fully implemented up to that level or unknown (see knownComponent).
std::vector<std::string_view> unimplementedNodes(std::string_view component, int level);

/// True when some X3D 4.0 node (or a GhostSpace extension) belongs to `component`.
bool knownComponent(std::string_view component);

}  // namespace gs::vrml
