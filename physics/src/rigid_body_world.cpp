// The Bullet world of a RigidBodyCollection (X3D 4.0 clause 37.4.9), stepped as X_ITE 15
// steps its ammo.js world (docs/x3d.md "Rigid body physics").
#include "world_impl.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string_view>

namespace gs::physics {

namespace {

using vrml::FieldType;

bool hasWord(const vrml::Node& n, vrml::FieldName field, std::string_view word) {
  const vrml::FieldValue* f = n.field(field);
  if (f == nullptr || f->type() != FieldType::MFString) return false;
  const auto& words = f->get<FieldType::MFString>();
  return std::find(words.begin(), words.end(), word) != words.end();
}

std::uint64_t mix(std::uint64_t h, std::uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h;
}

}  // namespace

btVector3 toBt(const glm::vec3& v) {
  return {v.x, v.y, v.z};
}
glm::vec3 toGlm(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}

btTransform toTransform(const glm::vec3& p, const vrml::Rotation& r) {
  btTransform t;
  t.setIdentity();
  t.setOrigin(toBt(p));
  const glm::vec3 axis(r.x, r.y, r.z);
  const float length = glm::length(axis);
  if (length > 0.0f && std::isfinite(length) && std::isfinite(r.w))
    t.setRotation(btQuaternion(toBt(axis / length), r.w));
  return t;
}

vrml::Rotation toRotation(const btQuaternion& q0) {
  btQuaternion q = q0;
  const btScalar n = q.length();
  if (!(n > 0)) return {0.0f, 0.0f, 1.0f, 0.0f};
  q /= n;
  const double w = std::clamp<double>(q.w(), -1.0, 1.0);
  const double s = std::sqrt(std::max(0.0, 1.0 - w * w));
  if (s < 1e-7) return {0.0f, 0.0f, 1.0f, 0.0f};
  return {static_cast<float>(q.x() / s), static_cast<float>(q.y() / s),
          static_cast<float>(q.z() / s), static_cast<float>(2.0 * std::acos(w))};
}

int XiteDynamicsWorld::stepAsXite(double timeStep, int maxSubSteps, double fixedTimeStep) {
  m_fixedTimeStep = static_cast<btScalar>(fixedTimeStep);
  double local = static_cast<double>(m_localTime) + timeStep;
  int due = 0;
  if (local >= fixedTimeStep) {
    due = static_cast<int>(local / fixedTimeStep);
    local -= due * fixedTimeStep;
  }
  m_localTime = static_cast<btScalar>(local);
  if (due > 0) {
    const int clamped = std::min(due, maxSubSteps);
    saveKinematicState(static_cast<btScalar>(fixedTimeStep * clamped));
    applyGravity();
    for (int i = 0; i < clamped; ++i) {
      internalSingleStepSimulation(static_cast<btScalar>(fixedTimeStep));
      synchronizeMotionStates();
    }
  } else {
    synchronizeMotionStates();
  }
  clearForces();
  return due;
}

void XiteDynamicsWorld::stepExactly(double timeStep) {
  stepSimulation(static_cast<btScalar>(timeStep), 0);
}

std::vector<std::pair<vrml::Node*, std::vector<vrml::Node*>>> bodyCollidables(
    const vrml::Node& collection) {
  std::vector<std::pair<vrml::Node*, std::vector<vrml::Node*>>> out;
  if (collection.typeId() != vrml::NodeTypeId::RigidBodyCollection) return out;
  for (const vrml::NodePtr& body : collection.mfnode("bodies")) {
    if (!body || body->typeId() != vrml::NodeTypeId::RigidBody) continue;
    std::vector<vrml::Node*> collidables;
    for (const vrml::NodePtr& c : body->mfnode("geometry"))
      if (c && (c->typeId() == vrml::NodeTypeId::CollidableShape ||
                c->typeId() == vrml::NodeTypeId::CollidableOffset))
        collidables.push_back(c.get());
    out.emplace_back(body.get(), std::move(collidables));
  }
  return out;
}

namespace {
void collectCollidables(const vrml::Node& node, int depth, std::vector<const vrml::Node*>& out) {
  if (depth < 0) return;
  for (const vrml::NodePtr& c : node.mfnode("collidables")) {
    if (!c) continue;
    if (c->typeId() == vrml::NodeTypeId::CollisionSpace) {
      collectCollidables(*c, depth - 1, out);
    } else if (std::find(out.begin(), out.end(), c.get()) == out.end()) {
      out.push_back(c.get());
    }
  }
}
}  // namespace

std::vector<const vrml::Node*> collidablesOf(const vrml::Node& node, int maxDepth) {
  std::vector<const vrml::Node*> out;
  collectCollidables(node, maxDepth, out);
  return out;
}

std::uint64_t RigidBodyWorld::signature(const vrml::Node& collection) {
  // Read straight from the fields (no lists made): the execution model asks every frame.
  std::uint64_t h = 0x5eedULL;
  for (const vrml::NodePtr& body : collection.mfnode("bodies")) {
    if (!body || body->typeId() != vrml::NodeTypeId::RigidBody) continue;
    h = mix(h, reinterpret_cast<std::uintptr_t>(body.get()));
    h = mix(h, body->get<FieldType::SFBool>("enabled", true) ? 1 : 2);
    h = mix(h, body->get<FieldType::SFBool>("fixed", false) ? 3 : 4);
    const float mass = body->get<FieldType::SFFloat>("mass", 1.0f);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &mass, sizeof bits);
    h = mix(h, bits);
    for (const vrml::NodePtr& c : body->mfnode("geometry"))
      h = mix(h, reinterpret_cast<std::uintptr_t>(c.get()));
  }
  for (const vrml::NodePtr& j : collection.mfnode("joints"))
    h = mix(h, reinterpret_cast<std::uintptr_t>(j.get()));
  h = mix(h, reinterpret_cast<std::uintptr_t>(collection.sfnode("collider").get()));
  return h;
}

PhysicsBody* RigidBodyWorld::Impl::find(const vrml::Node* body) {
  for (auto& b : bodies)
    if (b->node == body) return b.get();
  return nullptr;
}

void RigidBodyWorld::Impl::setPose(PhysicsBody& b) {
  const vrml::Node& n = *b.node;
  const btTransform t =
      toTransform(n.get<FieldType::SFVec3f>("position", glm::vec3(0.0f)),
                  n.get<FieldType::SFRotation>("orientation", vrml::Rotation(0, 0, 1, 0)));
  b.motion->setWorldTransform(t);
  b.rigid->setWorldTransform(t);
  b.rigid->setInterpolationWorldTransform(t);
  const glm::vec3 v =
      b.fixed ? glm::vec3(0.0f) : n.get<FieldType::SFVec3f>("linearVelocity", glm::vec3(0.0f));
  const glm::vec3 w =
      b.fixed ? glm::vec3(0.0f) : n.get<FieldType::SFVec3f>("angularVelocity", glm::vec3(0.0f));
  b.rigid->setLinearVelocity(toBt(v));
  b.rigid->setAngularVelocity(toBt(w));
  b.rigid->setInterpolationLinearVelocity(toBt(v));
  b.rigid->setInterpolationAngularVelocity(toBt(w));
  const bool finite = n.get<FieldType::SFBool>("useFiniteRotation", false);
  b.rigid->setAngularFactor(
      finite ? toBt(n.get<FieldType::SFVec3f>("finiteRotationAxis", glm::vec3(0, 1, 0)))
             : btVector3(1, 1, 1));
  const bool damp = n.get<FieldType::SFBool>("autoDamp", false);
  b.rigid->setDamping(
      damp ? std::clamp(n.get<FieldType::SFFloat>("linearDampingFactor", 0.001f), 0.0f, 1.0f)
           : 0.0f,
      damp ? std::clamp(n.get<FieldType::SFFloat>("angularDampingFactor", 0.001f), 0.0f, 1.0f)
           : 0.0f);
  b.rigid->activate(true);
}

RigidBodyWorld::RigidBodyWorld(const vrml::Node& collection) : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.signature = signature(collection);
  w.configuration = std::make_unique<btDefaultCollisionConfiguration>();
  w.dispatcher = std::make_unique<btCollisionDispatcher>(w.configuration.get());
  w.broadphase = std::make_unique<btDbvtBroadphase>();
  w.solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  w.world = std::make_unique<XiteDynamicsWorld>(w.dispatcher.get(), w.broadphase.get(),
                                                w.solver.get(), w.configuration.get());
  // Bullet 2.83's (ammo.js's) split-impulse error reduction; the bounce threshold is the
  // collider's minBounceSpeed (set per step).
  w.world->getSolverInfo().m_erp2 = 0.8f;
  w.world->getSolverInfo().m_restitutionVelocityThreshold = 0.0f;
  w.world->setGravity(toBt(collection.get<FieldType::SFVec3f>("gravity", glm::vec3(0, -9.8f, 0))));

  const vrml::NodePtr& collider = collection.sfnode("collider");
  float friction = 0.5f, rollingFriction = 0.0f;
  if (collider && hasWord(*collider, "appliedParameters", "FRICTION_COEFFICIENT-2")) {
    const glm::vec2 f = collider->get<FieldType::SFVec2f>("frictionCoefficients", glm::vec2(0.0f));
    friction = f.x;
    rollingFriction = f.y;
  }
  const float margin = collection.get<FieldType::SFFloat>("contactSurfaceThickness", 0.0f);

  std::size_t made = 0;
  for (auto& [node, collidables] : bodyCollidables(collection)) {
    if (!node->get<FieldType::SFBool>("enabled", true)) continue;
    if (w.find(node) != nullptr) continue;  // listed twice
    if (++made > kMaxBodies) {
      w.warnings.push_back("more than " + std::to_string(kMaxBodies) +
                           " bodies: the rest left out");
      break;
    }
    auto b = std::make_unique<PhysicsBody>();
    b->node = node;
    b->collidables = collidables;
    b->fixed = node->get<FieldType::SFBool>("fixed", false);
    b->compound = std::make_unique<btCompoundShape>();
    buildCollisionShape(*b, w.warnings);
    if (std::isfinite(margin) && margin > 0.0f) b->compound->setMargin(margin);
    b->motion = std::make_unique<btDefaultMotionState>();
    float mass = b->fixed ? 0.0f : node->get<FieldType::SFFloat>("mass", 1.0f);
    if (!(mass > 0.0f) || !std::isfinite(mass)) mass = 0.0f;
    btVector3 inertia(0, 0, 0);
    if (mass > 0.0f && b->compound->getNumChildShapes() > 0)
      b->compound->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, b->motion.get(), b->compound.get(),
                                                  inertia);
    info.m_friction = friction;
    info.m_rollingFriction = rollingFriction;
    b->rigid = std::make_unique<btRigidBody>(info);
    b->rigid->setFlags(0);  // no gyroscopic force (Bullet 2.83's default)
    b->rigid->setUserPointer(b.get());
    w.setPose(*b);
    b->rigid->setSleepingThresholds(0.0f, 0.0f);  // bodies are woken every frame (X_ITE)
    w.world->addRigidBody(b->rigid.get());
    w.bodies.push_back(std::move(b));
  }
  buildJoints(w, collection);
  w.readPoses();
}

RigidBodyWorld::~RigidBodyWorld() {
  if (!impl_) return;
  Impl& w = *impl_;
  for (auto& j : w.joints)
    if (j->constraint) w.world->removeConstraint(j->constraint.get());
  for (auto& b : w.bodies) w.world->removeRigidBody(b->rigid.get());
}

std::uint64_t RigidBodyWorld::builtSignature() const {
  return impl_->signature;
}

const std::vector<BodyPose>& RigidBodyWorld::poses() const {
  return impl_->poses;
}

const std::vector<std::string>& RigidBodyWorld::warnings() const {
  return impl_->warnings;
}

void RigidBodyWorld::resetBody(const vrml::Node& body) {
  if (PhysicsBody* b = impl_->find(&body)) impl_->setPose(*b);
}

void RigidBodyWorld::Impl::readPoses() {
  poses.clear();
  for (auto& b : bodies) {
    btTransform t;
    b->motion->getWorldTransform(t);
    BodyPose p;
    p.body = b->node;
    p.position = toGlm(t.getOrigin());
    p.orientation = toRotation(t.getRotation());
    p.linearVelocity = toGlm(b->rigid->getLinearVelocity());
    p.angularVelocity = toGlm(b->rigid->getAngularVelocity());
    p.collidables = &b->collidables;
    poses.push_back(p);
  }
}

void RigidBodyWorld::step(const vrml::Node& collection, double frameInterval) {
  Impl& w = *impl_;
  if (!collection.get<FieldType::SFBool>("enabled", true)) return;
  if (!(frameInterval > 0.0) || !std::isfinite(frameInterval)) return;
  // X_ITE's time step: 1 / max(10, frame rate), smoothed over 15 frames from 0.
  constexpr double kDelay = 15.0;
  w.deltaTime = ((kDelay - 1.0) * w.deltaTime + std::min(frameInterval, 0.1)) / kDelay;
  int iterations = collection.get<FieldType::SFInt32>("iterations", 10);
  iterations = std::clamp(iterations, 1, 1000);

  const glm::vec3 gravity = collection.get<FieldType::SFVec3f>("gravity", glm::vec3(0, -9.8f, 0));
  w.world->setGravity(toBt(gravity));
  // The collider's bounce (clause 37.4.3): restitution `bounce` above minBounceSpeed.
  const vrml::NodePtr& collider = collection.sfnode("collider");
  float bounce = 0.0f, minBounceSpeed = 0.1f;
  if (collider && collider->get<FieldType::SFBool>("enabled", true) &&
      hasWord(*collider, "appliedParameters", "BOUNCE")) {
    bounce = std::clamp(collider->get<FieldType::SFFloat>("bounce", 0.0f), 0.0f, 1.0f);
    minBounceSpeed = std::max(0.0f, collider->get<FieldType::SFFloat>("minBounceSpeed", 0.1f));
  }
  w.world->getSolverInfo().m_restitutionVelocityThreshold = minBounceSpeed;
  // Bullet multiplies the two bodies' restitutions: each takes sqrt(bounce).
  const float restitution = std::sqrt(bounce);

  auto applyForces = [&] {
    for (auto& b : w.bodies) {
      b->rigid->setRestitution(restitution);
      if (b->fixed || b->rigid->isStaticObject()) continue;
      const vrml::Node& n = *b->node;
      b->rigid->setGravity(n.get<FieldType::SFBool>("useGlobalGravity", true) ? toBt(gravity)
                                                                              : btVector3(0, 0, 0));
      glm::vec3 force(0.0f), torque(0.0f);
      if (const vrml::FieldValue* f = n.field("forces");
          f != nullptr && f->type() == FieldType::MFVec3f)
        for (const glm::vec3& v : f->get<FieldType::MFVec3f>()) force += v;
      if (const vrml::FieldValue* f = n.field("torques");
          f != nullptr && f->type() == FieldType::MFVec3f)
        for (const glm::vec3& v : f->get<FieldType::MFVec3f>()) torque += v;
      if (std::isfinite(force.x + force.y + force.z)) b->rigid->applyCentralForce(toBt(force));
      if (std::isfinite(torque.x + torque.y + torque.z)) b->rigid->applyTorque(toBt(torque));
      b->rigid->activate(true);
    }
    applyJointForces(w);
  };

  if (collection.get<FieldType::SFBool>("preferAccuracy", false)) {
    const double d = w.deltaTime / iterations;
    for (int i = 0; i < iterations; ++i) {
      applyForces();
      w.world->stepExactly(d);
    }
  } else {
    applyForces();
    w.world->stepAsXite(w.deltaTime, iterations + 2, w.deltaTime / iterations);
  }
  for (auto& j : w.joints) j->lastInterval = w.deltaTime;
  w.readPoses();
  w.stepped = true;
}

std::vector<ContactPoint> RigidBodyWorld::contacts() const {
  std::vector<ContactPoint> out;
  const Impl& w = *impl_;
  btDispatcher* d = w.world->getDispatcher();
  const int manifolds = d->getNumManifolds();
  for (int i = 0; i < manifolds; ++i) {
    const btPersistentManifold* m = d->getManifoldByIndexInternal(i);
    const auto* a = static_cast<const PhysicsBody*>(m->getBody0()->getUserPointer());
    const auto* b = static_cast<const PhysicsBody*>(m->getBody1()->getUserPointer());
    if (a == nullptr || b == nullptr) continue;
    for (int k = 0; k < m->getNumContacts(); ++k) {
      const btManifoldPoint& p = m->getContactPoint(k);
      if (p.getDistance() > 0) continue;
      ContactPoint c;
      c.body1 = a->node;
      c.body2 = b->node;
      c.geometry1 = a->collidables.empty() ? nullptr : a->collidables.front();
      c.geometry2 = b->collidables.empty() ? nullptr : b->collidables.front();
      c.position = toGlm(p.getPositionWorldOnA());
      c.contactNormal = toGlm(p.m_normalWorldOnB);
      c.depth = -p.getDistance();
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace gs::physics
