// An EspduTransform reader's events of the Fire, Detonation and Collision PDUs of its
// entity, and its geoCoords (X3D 4.0 clause 28.4.3; IEEE 1278.1 clauses 7.3.2, 7.3.3,
// 7.2.3). X_ITE 15 declares these fields and sends none of them; the field descriptions of
// the X3D 4.0 node model decide what each carries.
#include "dis_fields.hpp"

#include "dis/udp_socket.hpp"
#include "geospatial/geo_system.hpp"

namespace gs::runtime {

namespace {

using vrml::FieldType;
using vrml::FieldValue;

void disSendVec3(DisModel& s, NodeState& ns, std::string_view name, const glm::vec3& v) {
  disEmit(s, ns, name, FieldValue::make<FieldType::SFVec3f>(v));
}

void disSendEvent(DisModel& s, NodeState& ns, const dis::EventID& e) {
  disEmitInt(s, ns, "eventSiteID", e.site);
  disEmitInt(s, ns, "eventApplicationID", e.application);
  disEmitInt(s, ns, "eventNumber", e.eventNumber);
}

void disSendMunition(DisModel& s, NodeState& ns, const dis::EntityID& munition,
                     const dis::MunitionDescriptor& d) {
  disEmitInt(s, ns, "munitionSiteID", munition.site);
  disEmitInt(s, ns, "munitionApplicationID", munition.application);
  disEmitInt(s, ns, "munitionEntityID", munition.entity);
  disEmitInt(s, ns, "munitionQuantity", d.quantity);
  disEmitInt(s, ns, "warhead", d.warhead);
  disEmitInt(s, ns, "fuse", d.fuse);
}

}  // namespace

void disSendFire(DisModel& s, NodeState& ns, const dis::FirePdu& p, double now) {
  disSendMunition(s, ns, p.munitionID, p.descriptor);
  disSendEvent(s, ns, p.eventID);
  disSendVec3(s, ns, "munitionStartPoint", glm::vec3(p.location));
  disEmitInt(s, ns, "fireMissionIndex", p.fireMissionIndex);
  disEmit(s, ns, "firingRange", FieldValue::make<FieldType::SFFloat>(p.range));
  disEmitInt(s, ns, "firingRate", p.descriptor.rate);
  disEmit(s, ns, "fired1", FieldValue::make<FieldType::SFBool>(true));
  disEmit(s, ns, "firedTime", FieldValue::make<FieldType::SFTime>(now));
}

void disSendDetonation(DisModel& s, NodeState& ns, const dis::DetonationPdu& p, double now) {
  disSendMunition(s, ns, p.munitionID, p.descriptor);
  disSendEvent(s, ns, p.eventID);
  disSendVec3(s, ns, "detonationLocation", glm::vec3(p.location));
  disSendVec3(s, ns, "munitionEndPoint", glm::vec3(p.location));
  disSendVec3(s, ns, "detonationRelativeLocation", p.locationInEntity);
  disEmitInt(s, ns, "detonationResult", p.detonationResult);
  disEmit(s, ns, "isDetonated", FieldValue::make<FieldType::SFBool>(true));
  disEmit(s, ns, "detonateTime", FieldValue::make<FieldType::SFTime>(now));
}

void disSendCollision(DisModel& s, NodeState& ns, const dis::CollisionPdu& p, double now) {
  disSendEvent(s, ns, p.eventID);
  disEmitInt(s, ns, "collisionType", p.collisionType);
  disEmit(s, ns, "isCollided", FieldValue::make<FieldType::SFBool>(true));
  disEmit(s, ns, "collideTime", FieldValue::make<FieldType::SFTime>(now));
}

std::vector<std::uint8_t> disFireBytes(const vrml::Node& n, std::uint32_t timestamp) {
  const auto id = [&](std::string_view field) { return disId(n, field); };
  dis::FirePdu p;
  p.header.timestamp = timestamp;
  p.firingEntityID = {id("siteID"), id("applicationID"), id("entityID")};
  p.munitionID = {id("munitionSiteID"), id("munitionApplicationID"), id("munitionEntityID")};
  p.eventID = {id("eventSiteID"), id("eventApplicationID"), id("eventNumber")};
  p.fireMissionIndex =
      static_cast<std::uint32_t>(std::max(0, n.get<FieldType::SFInt32>("fireMissionIndex", 0)));
  p.location = glm::dvec3(n.get<FieldType::SFVec3f>("munitionStartPoint", glm::vec3(0.0f)));
  p.descriptor.warhead = id("warhead");
  p.descriptor.fuse = id("fuse");
  p.descriptor.quantity = id("munitionQuantity");
  p.descriptor.rate = id("firingRate");
  p.range = n.get<FieldType::SFFloat>("firingRange", 0.0f);
  return dis::encodeFire(p);
}

void disSendGeoCoords(DisModel& s, NodeState& ns, const glm::dvec3& location) {
  const auto system = geospatial::parseGeoSystem(
      ns.node->get<FieldType::MFString>("geoSystem", std::vector<std::string>{"GD", "WE"}));
  disEmit(s, ns, "geoCoords",
          FieldValue::make<FieldType::SFVec3d>(geospatial::fromGeocentric(system, location)));
}

}  // namespace gs::runtime
