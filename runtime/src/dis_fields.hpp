// The field events the DIS nodes send (dis_nodes.cpp, dis_events.cpp): internal to the
// execution model's DIS part (X3D 4.0 clause 28).
#pragma once

#include "execution_state.hpp"

#include "dis/pdu.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string_view>

namespace gs::runtime {

using DisModel = ExecutionModel::State;

inline std::uint64_t disEntityKey(const dis::EntityID& e) {
  return (std::uint64_t{e.site} << 32) | (std::uint64_t{e.application} << 16) | e.entity;
}

inline std::uint64_t disRadioKey(const dis::RadioID& r) {
  return (disEntityKey(r.entity) << 16) | r.radio;
}

/// An SFInt32 field of `n` as a PDU's 16-bit ID (its low 16 bits; 0 when absent).
inline std::uint16_t disId(const vrml::Node& n, std::string_view field) {
  const int i = n.type().findExact(field);
  if (i < 0) return 0;
  const vrml::FieldValue& v = n.fieldAt(static_cast<std::size_t>(i));
  return v.type() == vrml::FieldType::SFInt32
             ? static_cast<std::uint16_t>(v.get<vrml::FieldType::SFInt32>())
             : std::uint16_t{0};
}

/// Sends `v` from field `name` of `ns` when the node has that field with v's type.
inline void disEmit(DisModel& s, NodeState& ns, std::string_view name, vrml::FieldValue v) {
  const int i = ns.node->type().findExact(name);
  if (i >= 0 && ns.node->type().fields[static_cast<std::size_t>(i)].type == v.type())
    s.emitOwn(ns, i, std::move(v));
}

inline void disEmitInt(DisModel& s, NodeState& ns, std::string_view name, std::int64_t v) {
  constexpr std::int64_t kMax = std::numeric_limits<std::int32_t>::max();
  disEmit(s, ns, name,
          vrml::FieldValue::make<vrml::FieldType::SFInt32>(
              static_cast<std::int32_t>(std::min(v, kMax))));
}

/// An EspduTransform reader's events of a Fire PDU it fired (X3D 4.0 clause 28.4.3):
/// fired1 TRUE, firedTime, munitionStartPoint (the PDU's location, as translation takes
/// it), the munition's and the event's IDs, fireMissionIndex, firingRange, firingRate,
/// munitionQuantity, warhead and fuse (dis_events.cpp).
void disSendFire(DisModel& s, NodeState& ns, const dis::FirePdu& p, double now);

/// An EspduTransform reader's events of a Detonation PDU of a munition it fired:
/// isDetonated TRUE, detonateTime, detonationLocation and munitionEndPoint (the PDU's
/// location), detonationRelativeLocation, detonationResult, the munition's and the event's
/// IDs, munitionQuantity, warhead and fuse.
void disSendDetonation(DisModel& s, NodeState& ns, const dis::DetonationPdu& p, double now);

/// An EspduTransform reader's events of a Collision PDU it issued: isCollided TRUE,
/// collideTime, collisionType and the event's IDs.
void disSendCollision(DisModel& s, NodeState& ns, const dis::CollisionPdu& p, double now);

/// The Fire PDU of an EspduTransform networkWriter's fields (IEEE 1278.1 clause 7.3.2): its
/// entity firing, the munition's and the event's IDs, fireMissionIndex, munitionStartPoint
/// as the location, warhead, fuse, munitionQuantity, firingRate, firingRange; `timestamp`
/// in DIS time units.
std::vector<std::uint8_t> disFireBytes(const vrml::Node& n, std::uint32_t timestamp);

/// An EspduTransform reader's geoCoords: `location` (geocentric metres, as a PDU gives
/// it) in the node's geoSystem (X3D 4.0 clause 25.2.2; GD WE by default).
void disSendGeoCoords(DisModel& s, NodeState& ns, const glm::dvec3& location);

}  // namespace gs::runtime
