// Private to physics/: what a RigidBodyWorld holds (rigid_body_world.cpp), its collision
// shapes (collision_shapes.cpp) and joints (joints.cpp).
#pragma once

#include "physics/rigid_body_world.hpp"

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <string>
#include <vector>

namespace gs::physics {

/// Bullet's world with X_ITE's substep clock (docs/x3d.md "Rigid body physics"): ammo.js
/// keeps the clock in double arithmetic and stores it as float, so Bullet 3's own float
/// bookkeeping would take another number of substeps in some frames.
class XiteDynamicsWorld : public btDiscreteDynamicsWorld {
 public:
  using btDiscreteDynamicsWorld::btDiscreteDynamicsWorld;
  /// stepSimulation(timeStep, maxSubSteps, fixedTimeStep) as ammo.js computes it; returns
  /// the substeps due (more than maxSubSteps are dropped).
  int stepAsXite(double timeStep, int maxSubSteps, double fixedTimeStep);
  /// Bullet's variable step (fixedTimeStep 0): one substep of exactly `timeStep`.
  void stepExactly(double timeStep);
};

struct PhysicsBody {
  vrml::Node* node = nullptr;
  std::vector<vrml::Node*> collidables;  // of its geometry (CollidableShape / Offset)
  std::unique_ptr<btCompoundShape> compound;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btTriangleMesh>> meshes;
  std::unique_ptr<btDefaultMotionState> motion;
  std::unique_ptr<btRigidBody> rigid;
  bool fixed = false;
};

enum class JointKind { ball, singleAxisHinge, doubleAxisHinge, universal, slider, motor };

struct PhysicsJoint {
  vrml::Node* node = nullptr;
  JointKind kind = JointKind::ball;
  PhysicsBody* body1 = nullptr;
  PhysicsBody* body2 = nullptr;
  std::unique_ptr<btTypedConstraint> constraint;           // null for MotorJoint (torques only)
  btVector3 localAnchor1{0, 0, 0}, localAnchor2{0, 0, 0};  // anchorPoint in each body
  btVector3 localAxis1{0, 0, 0}, localAxis2{0, 0, 0};      // axis1 in body1, axis2 in body2
  double lastAngle1 = 0.0, lastAngle2 = 0.0, lastSeparation = 0.0;
  double lastInterval = 0.0;  // seconds of the last step (for the rates)
};

struct RigidBodyWorld::Impl {
  std::uint64_t signature = 0;
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::unique_ptr<XiteDynamicsWorld> world;
  std::vector<std::unique_ptr<PhysicsBody>> bodies;
  std::vector<std::unique_ptr<PhysicsJoint>> joints;
  std::vector<BodyPose> poses;
  std::vector<std::string> warnings;
  double deltaTime = 0.0;  // X_ITE's smoothed time step (seconds)
  bool stepped = false;

  PhysicsBody* find(const vrml::Node* body);
  void setPose(PhysicsBody& b);
  void readPoses();
};

/// Makes the collision shape of `b` (its compound's children) from its collidables.
void buildCollisionShape(PhysicsBody& b, std::vector<std::string>& warnings);
/// Makes the joints of `collection` between its bodies.
void buildJoints(RigidBodyWorld::Impl& w, const vrml::Node& collection);
/// MotorJoint torques and SliderJoint forces, before a step.
void applyJointForces(RigidBodyWorld::Impl& w);

/// The transform of position `p` and orientation `r` (axis-angle; a zero axis is none).
btTransform toTransform(const glm::vec3& p, const vrml::Rotation& r);
btVector3 toBt(const glm::vec3& v);
glm::vec3 toGlm(const btVector3& v);
/// Axis-angle of `q`; the identity is (0, 0, 1, 0).
vrml::Rotation toRotation(const btQuaternion& q);

}  // namespace gs::physics
