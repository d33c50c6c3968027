// The avatar against the world (ISO/IEC 14772-1:1997 clauses 6.8 Collision and 6.29
// NavigationInfo): WALK and FLY stop at walls, WALK falls under gravity, follows the
// terrain and climbs steps. Pure computation over the CPU picking of scene/picking.hpp
// (rays against the tessellated shapes, no OpenGL), so it is testable without a window.
// Units: metres.
#pragma once

#include "scene/camera.hpp"
#include "scene/traversal.hpp"

#include <glm/glm.hpp>

#include <limits>
#include <vector>

namespace gs::scene {

/// NavigationInfo.avatarSize (6.29): the avatar's collision radius, the eye's height above
/// the ground and the highest step it climbs. Missing or negative entries take the
/// defaults 0.25, 1.6 and 0.75.
struct Avatar {
  float radius = 0.25f;
  float height = 1.6f;
  float stepHeight = 0.75f;
  static Avatar of(const NavigationSettings& navigation);
};

/// How one walkStep moves.
struct WalkOptions {
  /// WALK: walls, gravity, terrain and steps; FLY: walls only (no gravity); EXAMINE:
  /// nothing is checked (the camera moves freely).
  NavigationMode mode = NavigationMode::walk;
  /// WALK: metres the eye may fall in this step (gravity applied frame by frame); the
  /// default falls to the ground at once (deterministic steps for scripts and tests).
  float maxFall = std::numeric_limits<float>::infinity();
};

/// Where a step took the avatar.
struct WalkResult {
  Camera camera;         // the camera moved (orientation and lens unchanged)
  bool blocked = false;  // a wall (or a step higher than avatarSize[2]) cut the move
  bool grounded = true;  // WALK: the eye rests avatarSize[1] above what is below it (or
                         // nothing is below); false while it is still falling
  /// The Collision nodes (6.8) on the paths of the geometry that blocked the move,
  /// outermost first, each once: they send collideTime (runtime ExecutionModel::collided).
  std::vector<const vrml::Node*> collided;
};

/// Moves `camera` by `motion` (world metres; WALK uses only its horizontal part) against
/// the collision geometry of `traversal`'s scene (TraversalFrame::collisionGeometry:
/// Collision.collide FALSE lets the avatar through, a proxy stands in for the children).
/// Walls: rays along the motion from the eye (and, walking, from avatarSize[2] above the
/// feet and halfway up) cut the move so that no geometry comes nearer than avatarSize[0].
/// WALK then casts a ray down from the eye: the eye climbs onto ground up to
/// avatarSize[2] above the feet (higher ground blocks the move), falls (at most
/// options.maxFall) onto ground below, and stays where it is when nothing is below.
WalkResult walkStep(SceneTraversal& traversal, const Camera& camera, const glm::vec3& motion,
                    const NavigationSettings& navigation, const WalkOptions& options = {});

}  // namespace gs::scene
