// Pointer input for the execution model (ISO/IEC 14772-1:1997 4.6.7 "Sensor nodes",
// pointing-device sensors): plain structs the application fills from its picking (the
// renderer's ray casts), so runtime/ does not depend on render/. See
// ExecutionModel::pointer().
#pragma once

#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <vector>

namespace gs::runtime {

/// One grouping node on the path from the scene's root to the picked Shape.
struct PickedNode {
  /// The grouping node (Transform, Group, Anchor, Collision, Billboard, Inline, ...) or
  /// the Shape itself (the last entry); null for the root of a scene (the root nodes).
  vrml::Node* node = nullptr;
  /// Local-to-world matrix of the coordinate system the node's children live in (for
  /// the Shape: its own coordinate system).
  glm::mat4 localToWorld{1.0f};
  /// The children among which sensors are looked for: null means the node's `children`
  /// field; a scene's root nodes for a scene root or an Inline.
  const std::vector<vrml::NodePtr>* children = nullptr;
};

/// The geometry under the pointer.
struct PickResult {
  std::vector<PickedNode> path;        // the root first, ..., the Shape last
  glm::vec3 point{0.0f};               // world coordinates
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // world coordinates, unit
  glm::vec2 texCoord{0.0f};
};

/// The pointing device at one moment: its bearing (a ray in world coordinates, 4.6.7.1),
/// its (primary) button and what the bearing hits first, if anything.
struct PointerEvent {
  glm::vec3 rayOrigin{0.0f};
  glm::vec3 rayDirection{0.0f, 0.0f, -1.0f};
  bool buttonDown = false;
  std::optional<PickResult> hit;
};

/// What the user interface shows for the pointer's position: whether a pointing-device
/// sensor or an Anchor is under it (a hand cursor), and the Anchor's description.
struct PointerHint {
  bool clickable = false;
  std::string description;  // an Anchor's description (6.2), else empty
  bool operator==(const PointerHint&) const = default;
};

}  // namespace gs::runtime
