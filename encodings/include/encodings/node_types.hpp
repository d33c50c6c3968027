// The built-in node types (NodeType: fields, access, defaults) of VRML97 and X3D 4.0, read
// once from the node model's text (vrml/node_table.hpp: the VRML97 synopses as PROTO
// interface declarations; vrml/node_model.hpp: X3DUOM's defaults in the XML encoding's
// syntax) by the encodings' own value parser, so every default is read by the code that
// reads a world's fields.
#pragma once

#include "vrml/node.hpp"

#include <memory>
#include <string_view>

namespace gs::vrml {

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

}  // namespace gs::vrml
