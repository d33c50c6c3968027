// X3D rigid body physics in the execution model (X3D 4.0 clause 37): each
// RigidBodyCollection gets a physics::RigidBodyWorld (Bullet), built once the world's
// nodes are in and stepped once per frame after the frame's time events (X_ITE's sensor
// phase); the bodies' position, orientation and velocities, the collidables they move
// (translation, rotation: what is drawn), the joints' forceOutput fields and the
// CollisionSensors' contacts are sent as events of the same timestamp.
#include "execution_state.hpp"

#include "encodings/node_types.hpp"

#include <algorithm>

namespace gs::runtime {

namespace {

using vrml::FieldType;
using vrml::FieldValue;

int rigidFieldIndex(const vrml::Node& n, std::string_view name) {
  return n.type().findExact(name);
}

bool sameVec3(const vrml::Node& n, int i, const glm::vec3& v) {
  const FieldValue& f = n.fieldAt(static_cast<std::size_t>(i));
  return f.type() == FieldType::SFVec3f && f.get<FieldType::SFVec3f>() == v;
}

bool sameRotation(const vrml::Node& n, int i, const vrml::Rotation& r) {
  const FieldValue& f = n.fieldAt(static_cast<std::size_t>(i));
  return f.type() == FieldType::SFRotation && f.get<FieldType::SFRotation>() == r;
}

}  // namespace

bool ExecutionModel::State::classifyRigidBodyPhysics(NodeState& ns) {
  const vrml::NodeTypeId id = ns.node->typeId();
  if (id == vrml::NodeTypeId::RigidBodyCollection) {
    ns.rigidBodies = std::make_unique<RigidBodyCollectionState>();
    rigidBodyCollections.push_back(&ns);
    newRigidBodyCollections.push_back(&ns);
    return true;
  }
  if (id == vrml::NodeTypeId::CollisionSensor) {
    ns.collision = std::make_unique<CollisionSensorState>();
    ns.collision->isActive = rigidFieldIndex(*ns.node, "isActive");
    ns.collision->contacts = rigidFieldIndex(*ns.node, "contacts");
    ns.collision->intersections = rigidFieldIndex(*ns.node, "intersections");
    collisionSensors.push_back(&ns);
    return true;
  }
  return false;
}

namespace {

/// Sends `value` from field `name` of `ns` when it differs from the field's value.
template <class Emit>
void sendVec3(NodeState& ns, std::string_view name, const glm::vec3& v, Emit&& emitOwn) {
  const int i = rigidFieldIndex(*ns.node, name);
  if (i < 0 || sameVec3(*ns.node, i, v)) return;
  emitOwn(ns, i, FieldValue::make<FieldType::SFVec3f>(v));
}
template <class Emit>
void sendRotation(NodeState& ns, std::string_view name, const vrml::Rotation& r, Emit&& emitOwn) {
  const int i = rigidFieldIndex(*ns.node, name);
  if (i < 0 || sameRotation(*ns.node, i, r)) return;
  emitOwn(ns, i, FieldValue::make<FieldType::SFRotation>(r));
}

}  // namespace

void ExecutionModel::State::startNewRigidBodyCollections() {
  if (newRigidBodyCollections.empty()) return;
  std::vector<NodeState*> fresh;
  fresh.swap(newRigidBodyCollections);
  auto emitter = [this](NodeState& n, int f, FieldValue v) { emitOwn(n, f, std::move(v)); };
  for (NodeState* c : fresh) {
    RigidBodyCollectionState& r = *c->rigidBodies;
    r.world = std::make_unique<physics::RigidBodyWorld>(*c->node);
    r.lastTime = model.now();
    // clause 37.4.8: a body's collidables stand where the body is.
    for (auto& [body, collidables] : physics::bodyCollidables(*c->node)) {
      const glm::vec3 p = body->get<FieldType::SFVec3f>("position", glm::vec3(0.0f));
      const vrml::Rotation o =
          body->get<FieldType::SFRotation>("orientation", vrml::Rotation(0, 0, 1, 0));
      for (vrml::Node* collidable : collidables) {
        NodeState& cs = reach(*collidable, false);
        sendVec3(cs, "translation", p, emitter);
        sendRotation(cs, "rotation", o, emitter);
      }
      r.bodyRevisions[body] = body->revision();
    }
  }
}

void ExecutionModel::State::evaluateRigidBodyPhysics() {
  startNewRigidBodyCollections();
  const double now = model.now();
  auto emitter = [this](NodeState& n, int f, FieldValue v) { emitOwn(n, f, std::move(v)); };
  for (NodeState* c : rigidBodyCollections) {
    RigidBodyCollectionState& r = *c->rigidBodies;
    if (!r.world || physics::RigidBodyWorld::signature(*c->node) != r.world->builtSignature()) {
      r.world = std::make_unique<physics::RigidBodyWorld>(*c->node);
      r.warningsReported = 0;
    }
    physics::RigidBodyWorld& world = *r.world;
    const double interval = now - r.lastTime;
    r.lastTime = now;
    // Bodies whose fields an event set since the last step start from there.
    for (const physics::BodyPose& p : world.poses()) {
      const auto it = r.bodyRevisions.find(p.body);
      if (it == r.bodyRevisions.end() || it->second != p.body->revision()) world.resetBody(*p.body);
    }
    world.step(*c->node, interval);
    const auto& warnings = world.warnings();
    for (; r.warningsReported < warnings.size(); ++r.warningsReported)
      report(vrml::Severity::warning, *c->node, warnings[r.warningsReported]);
    for (const physics::BodyPose& p : world.poses()) {
      NodeState& b = reach(*p.body, false);
      sendVec3(b, "position", p.position, emitter);
      sendRotation(b, "orientation", p.orientation, emitter);
      sendVec3(b, "linearVelocity", p.linearVelocity, emitter);
      sendVec3(b, "angularVelocity", p.angularVelocity, emitter);
      for (vrml::Node* collidable : *p.collidables) {
        NodeState& cs = reach(*collidable, false);
        sendVec3(cs, "translation", p.position, emitter);
        sendRotation(cs, "rotation", p.orientation, emitter);
      }
      r.bodyRevisions[p.body] = p.body->revision();
    }
    for (physics::JointOutput& o : world.jointOutputs()) {
      const int i = rigidFieldIndex(*o.joint, o.field);
      if (i >= 0 && o.joint->type().fields[static_cast<std::size_t>(i)].type == o.value.type())
        emitOwn(reach(*o.joint, false), i, std::move(o.value));
    }
  }

  // CollisionSensors (clause 37.4.5): the contacts of the bodies whose collidables are
  // in the sensor's collider; contacts and intersections are sent when there are any.
  for (NodeState* s : collisionSensors) {
    CollisionSensorState& cs = *s->collision;
    const vrml::NodePtr& collider = s->node->sfnode("collider");
    if (!collider || !s->node->get<FieldType::SFBool>("enabled", true)) continue;
    const std::vector<const vrml::Node*> watched = physics::collidablesOf(*collider);
    auto isWatched = [&](const vrml::Node* n) {
      return n != nullptr && std::find(watched.begin(), watched.end(), n) != watched.end();
    };
    std::vector<physics::ContactPoint> points;
    for (NodeState* c : rigidBodyCollections)
      if (c->rigidBodies->world)
        for (const physics::ContactPoint& p : c->rigidBodies->world->contacts())
          if (isWatched(p.geometry1) || isWatched(p.geometry2)) points.push_back(p);
    constexpr std::size_t kMaxContacts = 10'000;
    if (points.size() > kMaxContacts) points.resize(kMaxContacts);
    const bool active = !points.empty();
    if (active != cs.active && cs.isActive >= 0) {
      cs.active = active;
      emitOwn(*s, cs.isActive, FieldValue::make<FieldType::SFBool>(active));
    }
    if (!active) continue;
    static const std::shared_ptr<const vrml::NodeType> kContact = vrml::x3dNodeType("Contact");
    std::vector<vrml::NodePtr> contacts;
    std::vector<vrml::NodePtr> intersections;
    auto owning = [&](const vrml::Node* n) -> vrml::NodePtr {
      if (n == nullptr) return nullptr;
      for (const vrml::NodePtr& c : collider->mfnode("collidables"))
        if (c.get() == n) return c;
      const auto it = nodes.find(n);
      return it != nodes.end() ? it->second->keepAlive : nullptr;
    };
    for (std::size_t k = 0; k < points.size(); ++k) {
      if (k >= cs.contactNodes.size())
        cs.contactNodes.push_back(std::make_shared<vrml::Node>(kContact));
      vrml::Node& contact = *cs.contactNodes[k];
      const physics::ContactPoint& p = points[k];
      auto set = [&](std::string_view field, FieldValue v) {
        const int i = rigidFieldIndex(contact, field);
        if (i >= 0 && contact.type().fields[static_cast<std::size_t>(i)].type == v.type())
          contact.setField(static_cast<std::size_t>(i), std::move(v));
      };
      set("position", FieldValue::make<FieldType::SFVec3f>(p.position));
      set("contactNormal", FieldValue::make<FieldType::SFVec3f>(p.contactNormal));
      set("depth", FieldValue::make<FieldType::SFFloat>(p.depth));
      set("body1", FieldValue::make<FieldType::SFNode>(owning(p.body1)));
      set("body2", FieldValue::make<FieldType::SFNode>(owning(p.body2)));
      set("geometry1", FieldValue::make<FieldType::SFNode>(owning(p.geometry1)));
      set("geometry2", FieldValue::make<FieldType::SFNode>(owning(p.geometry2)));
      for (std::string_view f :
           {"bounce", "minBounceSpeed", "softnessConstantForceMix", "softnessErrorCorrection"})
        if (const FieldValue* v = collider->field(f)) set(f, *v);
      for (std::string_view f : {"appliedParameters", "frictionCoefficients", "surfaceSpeed"})
        if (const FieldValue* v = collider->field(f)) set(f, *v);
      if (const FieldValue* v = collider->field("slipFactors")) set("slipCoefficients", *v);
      contacts.push_back(cs.contactNodes[k]);
      for (const vrml::Node* g : {p.geometry1, p.geometry2})
        if (isWatched(g)) {
          vrml::NodePtr gp = owning(g);
          if (gp &&
              std::find(intersections.begin(), intersections.end(), gp) == intersections.end())
            intersections.push_back(std::move(gp));
        }
    }
    if (cs.contacts >= 0)
      emitOwn(*s, cs.contacts, FieldValue::make<FieldType::MFNode>(std::move(contacts)));
    if (cs.intersections >= 0)
      emitOwn(*s, cs.intersections, FieldValue::make<FieldType::MFNode>(std::move(intersections)));
  }
}

}  // namespace gs::runtime
