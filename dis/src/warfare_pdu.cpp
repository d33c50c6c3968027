// The Fire, Detonation (IEEE 1278.1-2012 clauses 7.3.2, 7.3.3), Collision (7.2.3) and
// Remove Entity (7.5.3) PDUs to and from their big-endian bytes (dis/pdu.hpp).
#include "dis/pdu.hpp"

#include "pdu_bytes.hpp"

#include <algorithm>

namespace gs::dis {

using namespace detail;

namespace {

EventID eventID(Reader& r) {
  EventID e;
  e.site = r.u16();
  e.application = r.u16();
  e.eventNumber = r.u16();
  return e;
}

void eventID(Writer& w, const EventID& e) {
  w.u16(e.site);
  w.u16(e.application);
  w.u16(e.eventNumber);
}

MunitionDescriptor munitionDescriptor(Reader& r) {
  MunitionDescriptor d;
  d.munitionType = entityType(r);
  d.warhead = r.u16();
  d.fuse = r.u16();
  d.quantity = r.u16();
  d.rate = r.u16();
  return d;
}

void munitionDescriptor(Writer& w, const MunitionDescriptor& d) {
  entityType(w, d.munitionType);
  w.u16(d.warhead);
  w.u16(d.fuse);
  w.u16(d.quantity);
  w.u16(d.rate);
}

void notFinite(std::string* error, const char* name) {
  if (error) *error = std::string(name) + " with a number that is not finite";
}

}  // namespace

std::optional<FirePdu> decodeFire(std::span<const std::uint8_t> bytes, std::string* error) {
  const std::optional<PduHeader> header = headerOf(bytes, PduType::fire, "a Fire PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  FirePdu p;
  p.header = *header;
  p.firingEntityID = entityID(r);
  p.targetEntityID = entityID(r);
  p.munitionID = entityID(r);
  p.eventID = eventID(r);
  p.fireMissionIndex = r.u32();
  p.location = vec3d(r);
  p.descriptor = munitionDescriptor(r);
  p.velocity = r.vec3f();
  p.range = r.f32();
  if (!r.ok()) {
    shortError(error, "Fire PDU", header->length, kFireSize);
    return std::nullopt;
  }
  if (!finite(p.location) || !finite(p.velocity) || !std::isfinite(p.range)) {
    notFinite(error, "Fire PDU");
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeFire(const FirePdu& p) {
  Writer w;
  writeHeader(w, p.header, PduType::fire, kWarfareFamily, kFireSize);
  entityID(w, p.firingEntityID);
  entityID(w, p.targetEntityID);
  entityID(w, p.munitionID);
  eventID(w, p.eventID);
  w.u32(p.fireMissionIndex);
  vec3d(w, p.location);
  munitionDescriptor(w, p.descriptor);
  w.vec3f(p.velocity);
  w.f32(p.range);
  return std::move(w.out);
}

std::optional<DetonationPdu> decodeDetonation(std::span<const std::uint8_t> bytes,
                                              std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::detonation, "a Detonation PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  DetonationPdu p;
  p.header = *header;
  p.firingEntityID = entityID(r);
  p.targetEntityID = entityID(r);
  p.munitionID = entityID(r);
  p.eventID = eventID(r);
  p.velocity = r.vec3f();
  p.location = vec3d(r);
  p.descriptor = munitionDescriptor(r);
  p.locationInEntity = r.vec3f();
  p.detonationResult = r.u8();
  const std::size_t parameters = r.u8();
  r.skip(2);  // padding
  const std::size_t needed = kDetonationSize + 16 * parameters;
  if (!r.ok() || header->length < needed) {
    shortError(error, "Detonation PDU", header->length, needed);
    return std::nullopt;
  }
  // The records are now known to lie inside the datagram: what is reserved is read.
  p.articulationParameters.reserve(parameters);
  for (std::size_t i = 0; i < parameters; ++i)
    p.articulationParameters.push_back(articulationParameter(r));
  if (!r.ok() || !finite(p.velocity) || !finite(p.location) || !finite(p.locationInEntity)) {
    notFinite(error, "Detonation PDU");
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeDetonation(const DetonationPdu& p) {
  Writer w;
  const std::size_t parameters =
      std::min(p.articulationParameters.size(), kMaxArticulationParameters);
  writeHeader(w, p.header, PduType::detonation, kWarfareFamily, kDetonationSize + 16 * parameters);
  entityID(w, p.firingEntityID);
  entityID(w, p.targetEntityID);
  entityID(w, p.munitionID);
  eventID(w, p.eventID);
  w.vec3f(p.velocity);
  vec3d(w, p.location);
  munitionDescriptor(w, p.descriptor);
  w.vec3f(p.locationInEntity);
  w.u8(p.detonationResult);
  w.u8(static_cast<std::uint8_t>(parameters));
  w.u16(0);
  for (std::size_t i = 0; i < parameters; ++i)
    articulationParameter(w, p.articulationParameters[i]);
  return std::move(w.out);
}

std::optional<CollisionPdu> decodeCollision(std::span<const std::uint8_t> bytes,
                                            std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::collision, "a Collision PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  CollisionPdu p;
  p.header = *header;
  p.issuingEntityID = entityID(r);
  p.collidingEntityID = entityID(r);
  p.eventID = eventID(r);
  p.collisionType = r.u8();
  r.skip(1);  // padding
  p.velocity = r.vec3f();
  p.mass = r.f32();
  p.location = r.vec3f();
  if (!r.ok()) {
    shortError(error, "Collision PDU", header->length, kCollisionSize);
    return std::nullopt;
  }
  if (!finite(p.velocity) || !std::isfinite(p.mass) || !finite(p.location)) {
    notFinite(error, "Collision PDU");
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeCollision(const CollisionPdu& p) {
  Writer w;
  writeHeader(w, p.header, PduType::collision, kEntityInformationFamily, kCollisionSize);
  entityID(w, p.issuingEntityID);
  entityID(w, p.collidingEntityID);
  eventID(w, p.eventID);
  w.u8(p.collisionType);
  w.u8(0);
  w.vec3f(p.velocity);
  w.f32(p.mass);
  w.vec3f(p.location);
  return std::move(w.out);
}

std::optional<RemoveEntityPdu> decodeRemoveEntity(std::span<const std::uint8_t> bytes,
                                                  std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::removeEntity, "a Remove Entity PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  RemoveEntityPdu p;
  p.header = *header;
  p.originatingID = entityID(r);
  p.receivingID = entityID(r);
  p.requestID = r.u32();
  if (!r.ok()) {
    shortError(error, "Remove Entity PDU", header->length, kRemoveEntitySize);
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeRemoveEntity(const RemoveEntityPdu& p) {
  Writer w;
  writeHeader(w, p.header, PduType::removeEntity, kSimulationManagementFamily, kRemoveEntitySize);
  entityID(w, p.originatingID);
  entityID(w, p.receivingID);
  w.u32(p.requestID);
  return std::move(w.out);
}

}  // namespace gs::dis
