// The avatar against the world: walls, gravity, terrain and steps (scene/collision.hpp).
#include "scene/collision.hpp"

#include "scene/picking.hpp"

#include <algorithm>
#include <cmath>

namespace gs::scene {

namespace {

/// Below this (metres) the eye is where it should be: no fall, no climb.
constexpr float kRestTolerance = 1e-4f;

void addCollisionNodes(const PickHit& hit, std::vector<const vrml::Node*>& out) {
  for (const PathStep& step : hit.path)
    if (step.node != nullptr && step.node->typeId() == vrml::NodeTypeId::Collision &&
        std::find(out.begin(), out.end(), step.node) == out.end())
      out.push_back(step.node);
}

}  // namespace

Avatar Avatar::of(const NavigationSettings& navigation) {
  Avatar a;
  const std::vector<float>& s = navigation.avatarSize;
  if (!s.empty() && s[0] >= 0.0f) a.radius = s[0];
  if (s.size() > 1 && s[1] >= 0.0f) a.height = s[1];
  if (s.size() > 2 && s[2] >= 0.0f) a.stepHeight = s[2];
  return a;
}

WalkResult walkStep(SceneTraversal& traversal, const Camera& camera, const glm::vec3& motion,
                    const NavigationSettings& navigation, const WalkOptions& options) {
  WalkResult result;
  result.camera = camera;
  const bool walking = options.mode == NavigationMode::walk;
  if (options.mode == NavigationMode::examine) {
    result.camera.position += motion;
    return result;
  }
  const Avatar avatar = Avatar::of(navigation);
  TraversalFrame frame;
  frame.recordPaths = true;
  frame.collisionGeometry = true;
  traversal.collect(camera, frame);

  // Walls: the move stops avatarSize[0] short of the nearest geometry ahead.
  glm::vec3 move = motion;
  if (walking) move.y = 0.0f;
  const float length = glm::length(move);
  glm::vec3 eye = camera.position;
  if (length > 0.0f) {
    const glm::vec3 direction = move / length;
    std::vector<glm::vec3> origins{eye};
    const float feet = eye.y - avatar.height;
    if (walking && avatar.stepHeight < avatar.height) {
      origins.push_back({eye.x, feet + avatar.stepHeight, eye.z});  // knees: steps above block
      origins.push_back({eye.x, feet + 0.5f * (avatar.stepHeight + avatar.height), eye.z});
    }
    float allowed = length;
    for (const glm::vec3& origin : origins) {
      const auto hit = pickInFrame(traversal, frame, {origin, direction}, length + avatar.radius);
      if (!hit) continue;
      const float free = std::max(0.0f, hit->distance - avatar.radius);
      if (free < length) {
        result.blocked = true;
        addCollisionNodes(*hit, result.collided);
      }
      allowed = std::min(allowed, free);
    }
    eye += direction * allowed;
  }

  if (walking) {
    // Gravity and terrain: the eye at avatarSize[1] above the geometry below it.
    const auto ground = pickInFrame(traversal, frame, {eye, glm::vec3(0.0f, -1.0f, 0.0f)});
    if (ground) {
      const float drop = ground->distance - avatar.height;  // > 0: fall, < 0: climb
      if (drop < -kRestTolerance) {
        if (-drop <= avatar.stepHeight + kRestTolerance || length == 0.0f) {
          eye.y -= drop;  // a step low enough, or ground that rose under a still avatar
        } else {
          eye = camera.position;  // a step too high: the move is refused
          result.blocked = true;
          addCollisionNodes(*ground, result.collided);
        }
      } else if (drop > kRestTolerance) {
        const float fall = std::min(drop, std::max(options.maxFall, 0.0f));
        eye.y -= fall;
        result.grounded = fall >= drop;
      }
    }
  }
  result.camera.position = eye;
  return result;
}

}  // namespace gs::scene
