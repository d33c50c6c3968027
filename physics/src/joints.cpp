// The joints of a RigidBodyCollection (X3D 4.0 clauses 37.4.1, 37.4.5, 37.4.7, 37.4.10,
// 37.4.11, 37.4.13, 37.4.14) as Bullet constraints, and their forceOutput values.
#include "world_impl.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

namespace gs::physics {

namespace {

using vrml::FieldType;

glm::vec3 vec3(const vrml::Node& n, vrml::FieldName f, glm::vec3 fallback) {
  return n.get<FieldType::SFVec3f>(f, fallback);
}
float real(const vrml::Node& n, vrml::FieldName f, float fallback) {
  return n.get<FieldType::SFFloat>(f, fallback);
}

bool usable(const btVector3& axis) {
  return std::isfinite(axis.length2()) && axis.length2() > 1e-12f;
}

/// The joint record of `node` between its bodies in `w`, or null (and a warning) when
/// either body is missing or not in this collection.
std::unique_ptr<PhysicsJoint> jointBetween(RigidBodyWorld::Impl& w, vrml::Node& node,
                                           JointKind kind) {
  const vrml::NodePtr& n1 = node.sfnode("body1");
  const vrml::NodePtr& n2 = node.sfnode("body2");
  PhysicsBody* b1 = n1 ? w.find(n1.get()) : nullptr;
  PhysicsBody* b2 = n2 ? w.find(n2.get()) : nullptr;
  if (b1 == nullptr || b2 == nullptr || b1 == b2) {
    w.warnings.push_back(
        node.typeName() +
        ": body1 and body2 must be two enabled bodies of the collection: no joint");
    return nullptr;
  }
  auto j = std::make_unique<PhysicsJoint>();
  j->node = &node;
  j->kind = kind;
  j->body1 = b1;
  j->body2 = b2;
  const btVector3 anchor = toBt(vec3(node, "anchorPoint", glm::vec3(0.0f)));
  j->localAnchor1 = b1->rigid->getWorldTransform().inverse() * anchor;
  j->localAnchor2 = b2->rigid->getWorldTransform().inverse() * anchor;
  return j;
}

/// axis2 made perpendicular to axis1 (Bullet's universal joint needs it), or a zero
/// vector when they are parallel.
btVector3 perpendicular(const btVector3& axis1, const btVector3& axis2) {
  const btVector3 a = axis1.normalized();
  btVector3 b = axis2 - a * a.dot(axis2);
  return usable(b) ? b.normalized() : btVector3(0, 0, 0);
}

void makeConstraint(PhysicsJoint& j, std::vector<std::string>& warnings) {
  const vrml::Node& n = *j.node;
  btRigidBody& a = *j.body1->rigid;
  btRigidBody& b = *j.body2->rigid;
  const btVector3 anchor = toBt(vec3(n, "anchorPoint", glm::vec3(0.0f)));
  switch (j.kind) {
    case JointKind::ball:
      j.constraint =
          std::make_unique<btPoint2PointConstraint>(a, b, j.localAnchor1, j.localAnchor2);
      break;
    case JointKind::singleAxisHinge: {
      const btVector3 axis = toBt(vec3(n, "axis", glm::vec3(0, 1, 0)));
      if (!usable(axis)) {
        warnings.push_back("SingleAxisHingeJoint: axis 0 0 0: no joint");
        return;
      }
      j.localAxis1 = a.getWorldTransform().getBasis().transpose() * axis.normalized();
      j.localAxis2 = b.getWorldTransform().getBasis().transpose() * axis.normalized();
      auto hinge = std::make_unique<btHingeConstraint>(a, b, j.localAnchor1, j.localAnchor2,
                                                       j.localAxis1, j.localAxis2, false);
      const float low = real(n, "minAngle", -std::numbers::pi_v<float>);
      const float high = real(n, "maxAngle", std::numbers::pi_v<float>);
      if (low <= high && high - low < 2.0f * std::numbers::pi_v<float> - 1e-3f)
        hinge->setLimit(low, high, 0.9f,
                        std::clamp(real(n, "stopErrorCorrection", 0.8f), 0.0f, 1.0f),
                        1.0f - std::clamp(real(n, "stopBounce", 0.0f), 0.0f, 1.0f));
      j.constraint = std::move(hinge);
      break;
    }
    case JointKind::doubleAxisHinge:
    case JointKind::universal: {
      const btVector3 axis1 = toBt(vec3(n, "axis1", glm::vec3(1, 0, 0)));
      const btVector3 axis2 = toBt(vec3(n, "axis2", glm::vec3(0, 1, 0)));
      const btVector3 second = usable(axis1) ? perpendicular(axis1, axis2) : btVector3(0, 0, 0);
      if (!usable(axis1) || !usable(second)) {
        warnings.push_back(n.typeName() + ": axis1 and axis2 must be two directions: no joint");
        return;
      }
      j.localAxis1 = a.getWorldTransform().getBasis().transpose() * axis1.normalized();
      j.localAxis2 = b.getWorldTransform().getBasis().transpose() * second;
      j.constraint =
          std::make_unique<btUniversalConstraint>(a, b, anchor, axis1.normalized(), second);
      break;
    }
    case JointKind::slider: {
      btVector3 axis = toBt(vec3(n, "axis", glm::vec3(0, 1, 0)));
      if (!usable(axis)) {
        warnings.push_back("SliderJoint: axis 0 0 0: no joint");
        return;
      }
      axis.normalize();
      j.localAxis1 = a.getWorldTransform().getBasis().transpose() * axis;
      j.localAxis2 = b.getWorldTransform().getBasis().transpose() * axis;
      // Bullet's slider runs along the frames' X axis; both frames start at body2.
      btTransform frame;
      frame.setIdentity();
      frame.setOrigin(b.getWorldTransform().getOrigin());
      btVector3 xAxis(1, 0, 0);
      frame.setRotation(shortestArcQuatNormalize2(xAxis, axis));
      auto slider =
          std::make_unique<btSliderConstraint>(a, b, a.getWorldTransform().inverse() * frame,
                                               b.getWorldTransform().inverse() * frame, true);
      slider->setLowerLinLimit(real(n, "minSeparation", 0.0f));
      slider->setUpperLinLimit(real(n, "maxSeparation", 1.0f));
      slider->setLowerAngLimit(0.0f);
      slider->setUpperAngLimit(0.0f);
      j.constraint = std::move(slider);
      break;
    }
    case JointKind::motor:
      break;  // torques only (applyJointForces)
  }
}

JointKind kindOf(vrml::NodeTypeId id, bool& known) {
  known = true;
  switch (id) {
    case vrml::NodeTypeId::BallJoint:
      return JointKind::ball;
    case vrml::NodeTypeId::SingleAxisHingeJoint:
      return JointKind::singleAxisHinge;
    case vrml::NodeTypeId::DoubleAxisHingeJoint:
      return JointKind::doubleAxisHinge;
    case vrml::NodeTypeId::UniversalJoint:
      return JointKind::universal;
    case vrml::NodeTypeId::SliderJoint:
      return JointKind::slider;
    case vrml::NodeTypeId::MotorJoint:
      return JointKind::motor;
    default:
      known = false;
      return JointKind::ball;
  }
}

bool wants(const vrml::Node& joint, std::string_view field) {
  const vrml::FieldValue* f = joint.field("forceOutput");
  if (f == nullptr || f->type() != FieldType::MFString) return false;
  for (const std::string& s : f->get<FieldType::MFString>())
    if (s == "ALL" || s == field) return true;
  return false;
}

}  // namespace

void buildJoints(RigidBodyWorld::Impl& w, const vrml::Node& collection) {
  for (const vrml::NodePtr& node : collection.mfnode("joints")) {
    if (!node) continue;
    bool known = false;
    const JointKind kind = kindOf(node->typeId(), known);
    if (!known) continue;
    if (w.joints.size() >= RigidBodyWorld::kMaxJoints) {
      w.warnings.push_back("more than " + std::to_string(RigidBodyWorld::kMaxJoints) +
                           " joints: the rest left out");
      break;
    }
    std::unique_ptr<PhysicsJoint> j = jointBetween(w, *node, kind);
    if (!j) continue;
    makeConstraint(*j, w.warnings);
    if (j->constraint) w.world->addConstraint(j->constraint.get(), true);
    if (j->constraint || kind == JointKind::motor) w.joints.push_back(std::move(j));
  }
}

void applyJointForces(RigidBodyWorld::Impl& w) {
  for (auto& jp : w.joints) {
    PhysicsJoint& j = *jp;
    const vrml::Node& n = *j.node;
    btRigidBody& a = *j.body1->rigid;
    btRigidBody& b = *j.body2->rigid;
    if (j.kind == JointKind::motor) {
      // clause 37.4.7: up to three motor axes, each turned by its axisNTorque.
      static constexpr const char* kAxes[] = {"motor1Axis", "motor2Axis", "motor3Axis"};
      static constexpr const char* kTorques[] = {"axis1Torque", "axis2Torque", "axis3Torque"};
      const int axes = std::clamp(n.get<FieldType::SFInt32>("enabledAxes", 1), 0, 3);
      for (int i = 0; i < axes; ++i) {
        const btVector3 axis = toBt(vec3(n, std::string_view(kAxes[i]), glm::vec3(0.0f)));
        const float torque = real(n, std::string_view(kTorques[i]), 0.0f);
        if (!usable(axis) || !std::isfinite(torque) || torque == 0.0f) continue;
        const btVector3 t = axis.normalized() * torque;
        a.applyTorque(-t);
        b.applyTorque(t);
      }
    } else if (j.kind == JointKind::slider) {
      const float force = real(n, "sliderForce", 0.0f);
      if (!std::isfinite(force) || force == 0.0f) continue;
      const btVector3 axis = a.getWorldTransform().getBasis() * j.localAxis1;
      a.applyCentralForce(-axis * force);
      b.applyCentralForce(axis * force);
    }
  }
}

std::vector<JointOutput> RigidBodyWorld::jointOutputs() {
  std::vector<JointOutput> out;
  for (auto& jp : impl_->joints) {
    PhysicsJoint& j = *jp;
    vrml::Node& n = *j.node;
    const btTransform& t1 = j.body1->rigid->getWorldTransform();
    const btTransform& t2 = j.body2->rigid->getWorldTransform();
    auto vec = [&](const char* field, const btVector3& v) {
      if (wants(n, field))
        out.push_back({&n, field, vrml::FieldValue::make<FieldType::SFVec3f>(toGlm(v))});
    };
    auto scalar = [&](const char* field, double v) {
      if (wants(n, field))
        out.push_back(
            {&n, field, vrml::FieldValue::make<FieldType::SFFloat>(static_cast<float>(v))});
    };
    const double dt = j.lastInterval > 0.0 ? j.lastInterval : 1.0;
    if (j.kind != JointKind::slider && j.kind != JointKind::motor) {
      vec("body1AnchorPoint", t1 * j.localAnchor1);
      vec("body2AnchorPoint", t2 * j.localAnchor2);
    }
    switch (j.kind) {
      case JointKind::singleAxisHinge: {
        const double angle = static_cast<btHingeConstraint&>(*j.constraint).getHingeAngle();
        scalar("angle", angle);
        scalar("angleRate", (angle - j.lastAngle1) / dt);
        j.lastAngle1 = angle;
        break;
      }
      case JointKind::doubleAxisHinge:
      case JointKind::universal: {
        vec("body1Axis", t1.getBasis() * j.localAxis1);
        vec("body2Axis", t2.getBasis() * j.localAxis2);
        if (j.kind == JointKind::universal) break;
        auto& u = static_cast<btUniversalConstraint&>(*j.constraint);
        u.calculateTransforms();
        const double a1 = u.getAngle1(), a2 = u.getAngle2();
        scalar("hinge1Angle", a1);
        scalar("hinge2Angle", a2);
        scalar("hinge1AngleRate", (a1 - j.lastAngle1) / dt);
        scalar("hinge2AngleRate", (a2 - j.lastAngle2) / dt);
        j.lastAngle1 = a1;
        j.lastAngle2 = a2;
        break;
      }
      case JointKind::slider: {
        auto& s = static_cast<btSliderConstraint&>(*j.constraint);
        s.calculateTransforms(t1, t2);
        const double separation = s.getLinearPos();
        scalar("separation", separation);
        scalar("separationRate", (separation - j.lastSeparation) / dt);
        j.lastSeparation = separation;
        break;
      }
      default:
        break;
    }
  }
  return out;
}

}  // namespace gs::physics
