// Output events that only drawing can compute: the level a LOD shows (X3D 4.0 clause
// 10.4.2, level_changed), the level and children a GeoLOD shows (25.4.5), whether a shader
// compiled and was chosen (31.4, isValid and isSelected), the shape of a projected texture
// (42.4, aspectRatio). The renderer collects them as they change; the session hands them
// to the execution model (runtime::ExecutionModel::sendDrawnOutputs), which sends them as
// events of their nodes.
#pragma once

#include "vrml/field.hpp"
#include "vrml/node.hpp"

#include <vector>

namespace gs::vrml {

/// One output event of `node` (its address and serial, made while it lived: the node may
/// be gone when the event is sent): `field` names an outputOnly field or exposedField of
/// the node's type (a string literal, never freed); `value` has that field's type.
struct DrawnOutput {
  NodeKey node;
  const char* field = "";
  FieldValue value;
};

using DrawnOutputs = std::vector<DrawnOutput>;

}  // namespace gs::vrml
