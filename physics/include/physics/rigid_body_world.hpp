// X3D rigid body physics (ISO/IEC 19775-1:2023, X3D 4.0 clause 37 "Rigid body physics"):
// the Bullet world of one RigidBodyCollection, stepped as X_ITE 15 steps its own (ammo.js,
// Bullet's port; docs/x3d.md "Rigid body physics" says where and why we differ). Pure
// computation in the collection's coordinates (metres, seconds, kilograms, radians); no
// clock of its own: the execution model steps it once per frame
// (runtime/src/rigid_body_physics.cpp) and sends what it returns as the nodes' events.
#pragma once

#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gs::physics {

/// What one RigidBody is after a step: its outputs (clause 37.4.8).
struct BodyPose {
  vrml::Node* body = nullptr;
  glm::vec3 position{0.0f};                            // metres, collection coordinates
  vrml::Rotation orientation{0.0f, 0.0f, 1.0f, 0.0f};  // axis (unit) and angle (radians)
  glm::vec3 linearVelocity{0.0f};                      // metres per second
  glm::vec3 angularVelocity{0.0f};                     // radians per second, about the axes
  /// The CollidableShapes and CollidableOffsets of its `geometry`, which stand where it is.
  const std::vector<vrml::Node*>* collidables = nullptr;
};

/// One contact point of the last step (the values of a Contact node, clause 37.4.6).
struct ContactPoint {
  const vrml::Node* body1 = nullptr;  // RigidBody nodes
  const vrml::Node* body2 = nullptr;
  const vrml::Node* geometry1 = nullptr;  // their first collidable (CollidableShape/Offset)
  const vrml::Node* geometry2 = nullptr;
  glm::vec3 position{0.0f};       // metres, on body1's surface
  glm::vec3 contactNormal{0.0f};  // unit, from body2 towards body1
  float depth = 0.0f;             // metres of penetration, >= 0
};

/// One output of a joint (clause 37.4.x forceOutput): the field name and its value.
struct JointOutput {
  vrml::Node* joint = nullptr;
  std::string field;  // e.g. "body1AnchorPoint", "angle", "separation"
  vrml::FieldValue value;
};

/// The Bullet world of one RigidBodyCollection (clause 37.4.9): its enabled bodies with
/// their collision shapes, its joints, gravity and the collider's friction and bounce.
///
/// Built from the nodes' fields as they are when constructed; the caller rebuilds it when
/// signature() of the collection changes (bodies, joints or collider added or removed, a
/// body's enabled, fixed, mass or geometry changed). Bodies whose fields the world did
/// not write are taken up again by resetBody().
///
/// Limits that keep a hostile world bounded: at most kMaxBodies bodies and kMaxJoints
/// joints are made, and a collidable's geometry above kMaxTriangles triangles gives no
/// shape; what was left out is named in warnings().
class RigidBodyWorld {
 public:
  static constexpr std::size_t kMaxBodies = 10'000;
  static constexpr std::size_t kMaxJoints = 10'000;
  static constexpr std::size_t kMaxTriangles = 1'000'000;

  /// Builds the world of RigidBodyCollection `collection` (a node of another type gives
  /// an empty world). Each body's collision shape is made from the geometry of the
  /// collidables in its `geometry` (Box, Sphere, Cylinder and Cone as Bullet's own shapes,
  /// any other geometry as triangles: a convex hull for a moving body, a triangle mesh for a
  /// fixed one); joints are made between bodies of this collection only.
  explicit RigidBodyWorld(const vrml::Node& collection);
  ~RigidBodyWorld();
  RigidBodyWorld(const RigidBodyWorld&) = delete;
  RigidBodyWorld& operator=(const RigidBodyWorld&) = delete;

  /// A hash of what the world was built from (the node lists and each body's enabled,
  /// fixed, mass and geometry list); a collection whose signature differs from the
  /// built one's needs a new world.
  static std::uint64_t signature(const vrml::Node& collection);
  std::uint64_t builtSignature() const;

  /// One frame of physics, `frameInterval` seconds (> 0) after the last: X_ITE's step
  /// (docs/x3d.md): a time step d = (14 d' + min(frameInterval, 0.1)) / 15 (d' the last,
  /// 0 at first), split into `iterations` fixed substeps of d / iterations (at most
  /// iterations + 2 of them, Bullet's substep clock carrying the remainder; preferAccuracy
  /// steps `iterations` times d / iterations exactly). Before it the bodies' forces and
  /// torques (world frame, newtons and newton metres) and gravity (useGlobalGravity) are
  /// applied. The poses reported are Bullet's motion states (the last substep's transform
  /// carried back by the substep clock's remainder, as X_ITE's). Nothing happens when the
  /// collection is not enabled.
  void step(const vrml::Node& collection, double frameInterval);

  /// The bodies' outputs after the last step (enabled bodies, in the collection's order).
  const std::vector<BodyPose>& poses() const;
  /// Takes the fields of RigidBody `body` again (position, orientation, linearVelocity,
  /// angularVelocity, finiteRotationAxis, damping), as set by events since the last step.
  void resetBody(const vrml::Node& body);
  /// The contact points of the last substep (penetration >= 0).
  std::vector<ContactPoint> contacts() const;
  /// The outputs the joints' forceOutput asks for ("ALL" or field names), after the last
  /// step; the rates are the change since the last call over the last step's time step.
  std::vector<JointOutput> jointOutputs();
  /// What could not be made (too many bodies, geometry too large, a degenerate joint), one
  /// sentence each; empty when all was made.
  const std::vector<std::string>& warnings() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

/// The RigidBody nodes of `collection` (its `bodies`), and the collidables each places:
/// for each body, the CollidableShape or CollidableOffset nodes of its `geometry`.
/// X3D 4.0 clause 37.4.8: a collidable directly in a body's geometry is placed at the
/// body's position and orientation (its own translation and rotation are the body's).
std::vector<std::pair<vrml::Node*, std::vector<vrml::Node*>>> bodyCollidables(
    const vrml::Node& collection);

/// The collidables of a CollisionCollection or CollisionSpace `node`, CollisionSpaces
/// flattened (at most `maxDepth` deep), each once.
std::vector<const vrml::Node*> collidablesOf(const vrml::Node& node, int maxDepth = 32);

}  // namespace gs::physics
