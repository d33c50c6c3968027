// X3D DIS (X3D 4.0 clause 28) in the execution model. Every DIS node listens on UDP `port`
// of `address` (dis/udp_socket.hpp); the datagrams of each address:port are read once per
// frame, decoded (dis/pdu.hpp) and shared by the nodes listening there.
//
// - EspduTransform, networkMode "networkReader": every readInterval seconds the latest
//   Entity State PDU of its entity (siteID, applicationID, entityID) since its last read
//   sets its translation (the PDU's location), its rotation (its DIS Euler angles), its
//   geoCoords (that location in its geoSystem) and sends the entity's velocity,
//   acceleration, type, force, marking and articulation parameters as its fields' events,
//   with timestamp and isActive. The Fire, Detonation and Collision PDUs of its entity are
//   sent as events the frame they arrive (dis_events.cpp).
// - EspduTransform, TransmitterPdu, SignalPdu, ReceiverPdu, networkMode "networkWriter":
//   every writeInterval seconds a PDU of its fields is sent (disWrite).
// - ReceiverPdu, SignalPdu, TransmitterPdu, networkMode "networkReader": the same with the
//   Receiver, Signal and Transmitter PDUs of their radio (siteID, applicationID, entityID,
//   radioID): each field the X3D node has for a PDU field is sent.
// - DISEntityManager: each Entity State PDU of an entity it has not seen (from siteID /
//   applicationID when they are not 0) makes an EspduTransform (networkReader on the same
//   address and port, for that entity) whose child is an Inline of the url of the
//   DISEntityTypeMapping (its `children`, X3D 3's `mapping`) that best matches the entity
//   type, sent in addedEntities. An entity whose PDUs stop for kDisEntityTimeout seconds,
//   whose PDU says it is deactivated (appearance bit 23), or that a Remove Entity PDU names,
//   is sent in removedEntities.
// - A datagram may carry its PDU behind an RTP header (dis/rtp.hpp); a writer whose
//   rtpHeaderExpected is TRUE puts one before each PDU it sends. A multicast `address` is
//   joined as a group (dis/udp_socket.hpp).
//
// Bytes from the network are untrusted: a datagram that does not decode is dropped
// (counted in a warning once per node), at most kDisMaxDatagrams are read per port per frame,
// and a manager makes at most kDisMaxEntities entities.
#include "dis_fields.hpp"

#include "vrml/transform.hpp"

#include "dis/pdu.hpp"
#include "dis/rtp.hpp"
#include "dis/udp_socket.hpp"
#include "encodings/node_types.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <variant>

namespace gs::runtime {

namespace {

using vrml::FieldType;
using vrml::FieldValue;

constexpr std::size_t kDisMaxDatagrams = 1024;
/// Most entities one DISEntityManager makes (a flood of entity IDs makes no more nodes).
constexpr std::size_t kDisMaxEntities = 1024;
/// Seconds without an Entity State PDU after which a DISEntityManager removes an entity:
/// IEEE 1278.1's entity state timeout, 2.4 (HBT_TIMEOUT_MPLIER) x the 5 s heartbeat.
constexpr double kDisEntityTimeout = 12.0;
/// Entity State PDU appearance bit 23 (IEEE 1278.1 / SISO-REF-010 "State"): deactivated.
constexpr std::uint32_t kDisDeactivated = 1u << 23;

/// The alternative of dis::Pdu a DIS node reads (-1: a DISEntityManager, which reads
/// Entity State PDUs of every entity).
int disPduIndex(vrml::NodeTypeId id) {
  switch (id) {
    case vrml::NodeTypeId::EspduTransform:
      return 0;
    case vrml::NodeTypeId::TransmitterPdu:
      return 1;
    case vrml::NodeTypeId::SignalPdu:
      return 2;
    case vrml::NodeTypeId::ReceiverPdu:
      return 3;
    default:
      return -1;
  }
}

dis::EntityID disEntityOf(const vrml::Node& n) {
  return {disId(n, "siteID"), disId(n, "applicationID"), disId(n, "entityID")};
}

/// Writes `v` into field `name` of a node the execution model made (no event).
void disSet(vrml::Node& n, std::string_view name, FieldValue v) {
  const int i = n.type().findExact(name);
  if (i >= 0 && n.type().fields[static_cast<std::size_t>(i)].type == v.type())
    n.setField(static_cast<std::size_t>(i), std::move(v));
}

void disSendEntityState(DisModel& s, NodeState& ns, const dis::EntityStatePdu& p) {
  disEmit(s, ns, "translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(p.location)));
  disEmit(s, ns, "rotation",
          FieldValue::make<FieldType::SFRotation>(
              vrml::rotationFromQuaternion(dis::eulerToQuaternion(p.orientation))));
  disSendGeoCoords(s, ns, p.location);
  disEmit(s, ns, "linearVelocity", FieldValue::make<FieldType::SFVec3f>(p.linearVelocity));
  disEmit(s, ns, "linearAcceleration", FieldValue::make<FieldType::SFVec3f>(p.linearAcceleration));
  disEmitInt(s, ns, "forceID", p.forceID);
  disEmitInt(s, ns, "entityKind", p.entityType.kind);
  disEmitInt(s, ns, "entityDomain", p.entityType.domain);
  disEmitInt(s, ns, "entityCountry", p.entityType.country);
  disEmitInt(s, ns, "entityCategory", p.entityType.category);
  disEmitInt(s, ns, "entitySubcategory", p.entityType.subcategory);
  disEmitInt(s, ns, "entitySpecific", p.entityType.specific);
  disEmitInt(s, ns, "entityExtra", p.entityType.extra);
  disEmitInt(s, ns, "deadReckoning", p.deadReckoningAlgorithm);
  disEmit(s, ns, "marking", FieldValue::make<FieldType::SFString>(p.marking));
  disEmitInt(s, ns, "articulationParameterCount",
             static_cast<std::int64_t>(p.articulationParameters.size()));
  static constexpr std::array<const char*, 8> kValues = {
      "articulationParameterValue0_changed", "articulationParameterValue1_changed",
      "articulationParameterValue2_changed", "articulationParameterValue3_changed",
      "articulationParameterValue4_changed", "articulationParameterValue5_changed",
      "articulationParameterValue6_changed", "articulationParameterValue7_changed"};
  for (std::size_t k = 0; k < kValues.size() && k < p.articulationParameters.size(); ++k)
    disEmit(s, ns, kValues[k],
            FieldValue::make<FieldType::SFFloat>(
                static_cast<float>(p.articulationParameters[k].value)));
}

void disSendTransmitter(DisModel& s, NodeState& ns, const dis::TransmitterPdu& p) {
  disEmit(s, ns, "antennaLocation",
          FieldValue::make<FieldType::SFVec3f>(glm::vec3(p.antennaLocation)));
  disEmit(s, ns, "relativeAntennaLocation",
          FieldValue::make<FieldType::SFVec3f>(p.relativeAntennaLocation));
  disEmitInt(s, ns, "antennaPatternType", p.antennaPatternType);
  disEmitInt(s, ns, "antennaPatternLength", static_cast<std::int64_t>(p.antennaPattern.size()));
  disEmitInt(s, ns, "cryptoSystem", p.cryptoSystem);
  disEmitInt(s, ns, "cryptoKeyID", p.cryptoKeyID);
  // SFInt32 hertz: a frequency above 2^31 - 1 Hz (2.1 GHz) is sent as 2^31 - 1.
  disEmitInt(s, ns, "frequency",
             static_cast<std::int64_t>(std::min<std::uint64_t>(p.frequency, 0x7fffffffu)));
  disEmitInt(s, ns, "inputSource", p.inputSource);
  disEmitInt(s, ns, "lengthOfModulationParameters",
             static_cast<std::int64_t>(p.modulationParameters.size()));
  disEmitInt(s, ns, "modulationTypeDetail", p.modulationType.detail);
  disEmitInt(s, ns, "modulationTypeMajor", p.modulationType.major);
  disEmitInt(s, ns, "modulationTypeSpreadSpectrum", p.modulationType.spreadSpectrum);
  disEmitInt(s, ns, "modulationTypeSystem", p.modulationType.radioSystem);
  disEmit(s, ns, "power", FieldValue::make<FieldType::SFFloat>(p.power));
  disEmitInt(s, ns, "radioEntityTypeCategory", p.radioEntityType.category);
  disEmitInt(s, ns, "radioEntityTypeCountry", p.radioEntityType.country);
  disEmitInt(s, ns, "radioEntityTypeDomain", p.radioEntityType.domain);
  disEmitInt(s, ns, "radioEntityTypeKind", p.radioEntityType.kind);
  disEmitInt(s, ns, "radioEntityTypeNomenclature", p.radioEntityType.nomenclature);
  disEmitInt(s, ns, "radioEntityTypeNomenclatureVersion", p.radioEntityType.nomenclatureVersion);
  disEmit(s, ns, "transmitFrequencyBandwidth",
          FieldValue::make<FieldType::SFFloat>(p.transmitFrequencyBandwidth));
  disEmitInt(s, ns, "transmitState", p.transmitState);
}

void disSendSignal(DisModel& s, NodeState& ns, const dis::SignalPdu& p) {
  // One MFInt32 value per data byte (0..255), in the order received.
  std::vector<std::int32_t> data(p.data.begin(), p.data.end());
  disEmit(s, ns, "data", FieldValue::make<FieldType::MFInt32>(std::move(data)));
  disEmitInt(s, ns, "dataLength", p.dataLength);
  disEmitInt(s, ns, "encodingScheme", p.encodingScheme);
  disEmitInt(s, ns, "sampleRate", p.sampleRate);
  disEmitInt(s, ns, "samples", p.samples);
  disEmitInt(s, ns, "tdlType", p.tdlType);
}

void disSendReceiver(DisModel& s, NodeState& ns, const dis::ReceiverPdu& p) {
  disEmit(s, ns, "receivedPower", FieldValue::make<FieldType::SFFloat>(p.receivedPower));
  disEmitInt(s, ns, "receiverState", p.receiverState);
  disEmitInt(s, ns, "transmitterSiteID", p.transmitter.entity.site);
  disEmitInt(s, ns, "transmitterApplicationID", p.transmitter.entity.application);
  disEmitInt(s, ns, "transmitterEntityID", p.transmitter.entity.entity);
  disEmitInt(s, ns, "transmitterRadioID", p.transmitter.radio);
}

/// The DISEntityTypeMapping of `manager` that best matches `type`, or null. X3D 4.0
/// 28.4.3 (and X_ITE's documentation) compare kind, domain, country, category,
/// subcategory, specific, extra in that order; here a mapping's field of 0 matches any
/// value (a wildcard), any other value must equal the entity's, and of the mappings that
/// match, the one whose fields match exactly the furthest down that list wins (the first
/// listed on a tie).
const vrml::NodePtr* disBestMapping(const vrml::Node& manager, const dis::EntityType& type) {
  const std::array<int, 7> wanted = {type.kind,        type.domain,   type.country, type.category,
                                     type.subcategory, type.specific, type.extra};
  static constexpr std::array<std::string_view, 7> kFields = {
      "kind", "domain", "country", "category", "subcategory", "specific", "extra"};
  const vrml::NodePtr* best = nullptr;
  int bestDepth = -1;
  for (const vrml::NodePtr& m : manager.mfnode("children")) {
    if (!m || m->typeId() != vrml::NodeTypeId::DISEntityTypeMapping) continue;
    int depth = 0;
    bool matches = true, exact = true;
    for (std::size_t k = 0; k < kFields.size() && matches; ++k) {
      const int v = m->get<FieldType::SFInt32>(kFields[k], 0);
      if (v != 0 && v != wanted[k]) matches = false;
      exact = exact && v == wanted[k];
      if (exact) depth = static_cast<int>(k) + 1;
    }
    if (matches && depth > bestDepth) {
      best = &m;
      bestDepth = depth;
    }
  }
  return best;
}

/// A networkReader EspduTransform for `pdu`'s entity on the manager's address and port,
/// its child an Inline of the best mapping's url (none when no mapping matches).
vrml::NodePtr disMakeEntity(const vrml::Node& manager, const dis::EntityStatePdu& pdu) {
  static const std::shared_ptr<const vrml::NodeType> kEspdu = vrml::x3dNodeType("EspduTransform");
  static const std::shared_ptr<const vrml::NodeType> kInline = vrml::x3dNodeType("Inline");
  auto t = std::make_shared<vrml::Node>(kEspdu);
  disSet(*t, "networkMode", FieldValue::make<FieldType::SFString>(std::string("networkReader")));
  for (std::string_view f : {"address", "port"})
    if (const FieldValue* v = manager.field(f)) disSet(*t, f, *v);
  disSet(*t, "siteID", FieldValue::make<FieldType::SFInt32>(pdu.entityID.site));
  disSet(*t, "applicationID", FieldValue::make<FieldType::SFInt32>(pdu.entityID.application));
  disSet(*t, "entityID", FieldValue::make<FieldType::SFInt32>(pdu.entityID.entity));
  disSet(*t, "marking", FieldValue::make<FieldType::SFString>(pdu.marking));
  if (const vrml::NodePtr* m = disBestMapping(manager, pdu.entityType)) {
    auto model = std::make_shared<vrml::Node>(kInline);
    model->urlBase = (*m)->urlBase;  // its url resolves as the mapping's would
    if (const FieldValue* url = (*m)->field("url")) disSet(*model, "url", *url);
    disSet(*t, "children", FieldValue::make<FieldType::MFNode>(std::vector<vrml::NodePtr>{model}));
  }
  return t;
}

/// The receiver of `ns` (opened on first use), or null when the node does not listen
/// (not a networkReader, disabled) or its socket could not open (reported once).
DisInbox* disInboxOf(DisModel& s, NodeState& ns) {
  const vrml::Node& n = *ns.node;
  EspduState& st = *ns.espdu;
  const int port = n.get<FieldType::SFInt32>("port", 0);
  const std::string address = n.get<FieldType::SFString>("address", std::string("localhost"));
  st.key = address + ":" + std::to_string(port);
  DisInbox& inbox = s.disReceivers[st.key];
  if (!inbox.socket) {
    inbox.socket = std::make_unique<dis::UdpReceiver>();
    std::string error;
    if (!inbox.socket->open(port, address, error) && !st.reported) {
      st.reported = true;
      s.report(vrml::Severity::error, n, error + ": " + n.typeName() + " reads no PDUs");
    }
  }
  return inbox.socket->isOpen() ? &inbox : nullptr;
}

/// Reads the datagrams waiting on `inbox` and decodes them (this frame's PDUs).
void disDrain(DisInbox& inbox) {
  inbox.pdus.clear();
  for (auto& m : inbox.latest) m.clear();
  for (const std::vector<std::uint8_t>& d : inbox.socket->receive(kDisMaxDatagrams)) {
    // A PDU behind an RTP header (rtpHeaderExpected) or bare: the first byte tells.
    std::optional<dis::Pdu> p = dis::decodePdu(dis::withoutRtpHeader(d), nullptr);
    if (!p) {
      ++inbox.dropped;
      continue;
    }
    const std::uint64_t key = std::visit(
        [](const auto& pdu) -> std::uint64_t {
          using P = std::decay_t<decltype(pdu)>;
          if constexpr (std::is_same_v<P, dis::EntityStatePdu>)
            return disEntityKey(pdu.entityID);
          else if constexpr (std::is_same_v<P, dis::FirePdu> ||
                             std::is_same_v<P, dis::DetonationPdu>)
            return disEntityKey(pdu.firingEntityID);
          else if constexpr (std::is_same_v<P, dis::CollisionPdu>)
            return disEntityKey(pdu.issuingEntityID);
          else if constexpr (std::is_same_v<P, dis::RemoveEntityPdu>)
            return disEntityKey(pdu.receivingID);
          else
            return disRadioKey(pdu.radio);
        },
        *p);
    inbox.latest[p->index()][key] = inbox.pdus.size();
    inbox.pdus.push_back(std::move(*p));
  }
}

/// An EspduTransform reader between Entity State PDUs (IEEE 1278.1 annex E): from the last
/// PDU read, `dt` seconds ago, its dead reckoning algorithm moves the translation (2, 3, 6,
/// 7: P + V dt; 4, 5, 8, 9: P + V dt + A dt^2 / 2; 6 to 9 take V and A in the entity's body
/// axes) and turns the rotation by the angular velocity (body axes; 3, 4, 7, 8). 1
/// (static), 0 (other) and unknown values leave it where the PDU put it.
void disDeadReckon(DisModel& s, NodeState& ns, double now) {
  const EspduState& st = *ns.espdu;
  const dis::EntityStatePdu& p = *st.reckoned;
  const int algorithm = p.deadReckoningAlgorithm;
  if (algorithm < 2 || algorithm > 9) return;
  const double dt = now - st.reckonedAt;
  const glm::dquat orientation = dis::eulerToQuaternion(p.orientation);
  const bool body = algorithm >= 6;
  const bool rotates = algorithm == 3 || algorithm == 4 || algorithm == 7 || algorithm == 8;
  const bool accelerates = algorithm == 4 || algorithm == 5 || algorithm == 8 || algorithm == 9;
  glm::dvec3 v(p.linearVelocity), a(p.linearAcceleration);
  if (body) {
    v = orientation * v;
    a = orientation * a;
  }
  glm::dvec3 position = p.location + v * dt;
  if (accelerates) position += 0.5 * a * dt * dt;
  disEmit(s, ns, "translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(position)));
  disSendGeoCoords(s, ns, position);
  const glm::dvec3 w(p.angularVelocity);
  if (rotates && glm::length(w) > 0.0) {
    const glm::dquat turned = orientation * glm::angleAxis(glm::length(w) * dt, glm::normalize(w));
    disEmit(s, ns, "rotation",
            FieldValue::make<FieldType::SFRotation>(vrml::rotationFromQuaternion(turned)));
  }
}

/// DIS relative time at SFTime `now`: 2^31 units per hour past the hour, bit 0 clear.
std::uint32_t disTimestamp(double now) {
  const double pastHour = std::fmod(std::max(now, 0.0), 3600.0) / 3600.0;
  return static_cast<std::uint32_t>(pastHour * 2147483647.0) << 1;
}

std::int32_t disInt(const vrml::Node& n, vrml::FieldName field) {
  return n.get<FieldType::SFInt32>(field, 0);
}

/// An SFInt32 field as a PDU's byte (its low 8 bits).
std::uint8_t disByte(const vrml::Node& n, vrml::FieldName field) {
  return static_cast<std::uint8_t>(disInt(n, field));
}

dis::RadioID disRadioOf(const vrml::Node& n) {
  return {disEntityOf(n), disId(n, "radioID")};
}

/// The Entity State PDU of an EspduTransform's fields: its entity and type, forceID,
/// translation as the location, rotation as DIS Euler angles, linearVelocity,
/// linearAcceleration, deadReckoning, marking (11 characters) and its articulation
/// parameter arrays (at most articulationParameterCount, as many as every array holds).
std::vector<std::uint8_t> disEntityStateBytes(const vrml::Node& n, double now) {
  dis::EntityStatePdu p;
  p.header.timestamp = disTimestamp(now);
  p.entityID = disEntityOf(n);
  p.forceID = disByte(n, "forceID");
  p.entityType = {disByte(n, "entityKind"),        disByte(n, "entityDomain"),
                  disId(n, "entityCountry"),       disByte(n, "entityCategory"),
                  disByte(n, "entitySubcategory"), disByte(n, "entitySpecific"),
                  disByte(n, "entityExtra")};
  p.location = glm::dvec3(n.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)));
  const vrml::Rotation r = n.get<FieldType::SFRotation>("rotation", vrml::Rotation{});
  const glm::dvec3 axis(r.x, r.y, r.z);
  if (glm::length(axis) > 0.0)
    p.orientation =
        dis::quaternionToEuler(glm::angleAxis(static_cast<double>(r.w), glm::normalize(axis)));
  p.linearVelocity = n.get<FieldType::SFVec3f>("linearVelocity", glm::vec3(0.0f));
  p.linearAcceleration = n.get<FieldType::SFVec3f>("linearAcceleration", glm::vec3(0.0f));
  p.deadReckoningAlgorithm = disByte(n, "deadReckoning");
  p.marking = n.get<FieldType::SFString>("marking", std::string()).substr(0, 11);
  const auto ints = [&](std::string_view field) {
    return n.get<FieldType::MFInt32>(vrml::FieldName(field), std::vector<std::int32_t>{});
  };
  const std::vector<float> values =
      n.get<FieldType::MFFloat>("articulationParameterArray", std::vector<float>{});
  const std::vector<std::int32_t> designators = ints("articulationParameterDesignatorArray"),
                                  changes = ints("articulationParameterChangeIndicatorArray"),
                                  attached = ints("articulationParameterIdPartAttachedToArray"),
                                  types = ints("articulationParameterTypeArray");
  const std::size_t count =
      std::min({static_cast<std::size_t>(
                    std::max(0, n.get<FieldType::SFInt32>("articulationParameterCount", 0))),
                values.size(), designators.size(), changes.size(), attached.size(), types.size(),
                dis::kMaxArticulationParameters});
  for (std::size_t i = 0; i < count; ++i)
    p.articulationParameters.push_back(
        {static_cast<std::uint8_t>(designators[i]), static_cast<std::uint8_t>(changes[i]),
         static_cast<std::uint16_t>(attached[i]), static_cast<std::uint32_t>(types[i]),
         static_cast<double>(values[i])});
  return dis::encodeEntityState(p);
}

/// The Transmitter PDU of a TransmitterPdu node's fields (those disSendTransmitter sends;
/// no modulation parameters or antenna pattern bytes).
std::vector<std::uint8_t> disTransmitterBytes(const vrml::Node& n, double now) {
  dis::TransmitterPdu p;
  p.header.timestamp = disTimestamp(now);
  p.radio = disRadioOf(n);
  p.radioEntityType = {disByte(n, "radioEntityTypeKind"),
                       disByte(n, "radioEntityTypeDomain"),
                       disId(n, "radioEntityTypeCountry"),
                       disByte(n, "radioEntityTypeCategory"),
                       disByte(n, "radioEntityTypeNomenclatureVersion"),
                       disId(n, "radioEntityTypeNomenclature")};
  p.transmitState = disByte(n, "transmitState");
  p.inputSource = disByte(n, "inputSource");
  p.antennaLocation = glm::dvec3(n.get<FieldType::SFVec3f>("antennaLocation", glm::vec3(0.0f)));
  p.relativeAntennaLocation = n.get<FieldType::SFVec3f>("relativeAntennaLocation", glm::vec3(0.0f));
  p.antennaPatternType = disId(n, "antennaPatternType");
  p.frequency = static_cast<std::uint64_t>(std::max(0, disInt(n, "frequency")));
  p.transmitFrequencyBandwidth = n.get<FieldType::SFFloat>("transmitFrequencyBandwidth", 0.0f);
  p.power = n.get<FieldType::SFFloat>("power", 0.0f);
  p.modulationType = {disId(n, "modulationTypeSpreadSpectrum"), disId(n, "modulationTypeMajor"),
                      disId(n, "modulationTypeDetail"), disId(n, "modulationTypeSystem")};
  p.cryptoSystem = disId(n, "cryptoSystem");
  p.cryptoKeyID = disId(n, "cryptoKeyID");
  return dis::encodeTransmitter(p);
}

/// The Signal PDU of a SignalPdu node's fields: `data` one byte per value (at most
/// dis::kMaxSignalData), dataLength bits of it (at most its bytes' bits).
std::vector<std::uint8_t> disSignalBytes(const vrml::Node& n, double now) {
  dis::SignalPdu p;
  p.header.timestamp = disTimestamp(now);
  p.radio = disRadioOf(n);
  p.encodingScheme = disId(n, "encodingScheme");
  p.tdlType = disId(n, "tdlType");
  p.sampleRate = static_cast<std::uint32_t>(std::max(0, disInt(n, "sampleRate")));
  p.samples = disId(n, "samples");
  const std::vector<std::int32_t> data =
      n.get<FieldType::MFInt32>("data", std::vector<std::int32_t>{});
  for (std::size_t i = 0; i < data.size() && i < dis::kMaxSignalData; ++i)
    p.data.push_back(static_cast<std::uint8_t>(data[i]));
  const std::int64_t bits = std::min<std::int64_t>(
      {std::max(0, disInt(n, "dataLength")), static_cast<std::int64_t>(p.data.size()) * 8, 65535});
  p.dataLength = static_cast<std::uint16_t>(bits);
  p.data.resize((static_cast<std::size_t>(bits) + 7) / 8);
  return dis::encodeSignal(p);
}

/// The Receiver PDU of a ReceiverPdu node's fields.
std::vector<std::uint8_t> disReceiverBytes(const vrml::Node& n, double now) {
  dis::ReceiverPdu p;
  p.header.timestamp = disTimestamp(now);
  p.radio = disRadioOf(n);
  p.receiverState = disId(n, "receiverState");
  p.receivedPower = n.get<FieldType::SFFloat>("receivedPower", 0.0f);
  p.transmitter = {{disId(n, "transmitterSiteID"), disId(n, "transmitterApplicationID"),
                    disId(n, "transmitterEntityID")},
                   disId(n, "transmitterRadioID")};
  return dis::encodeReceiver(p);
}

/// A DIS node in "networkWriter" mode (X3D 4.0 clauses 28.4.3 to 28.4.6): every
/// writeInterval seconds (1 by default; 0: no writing, as the field says) one PDU of its
/// fields (an
/// EspduTransform's Entity State, a TransmitterPdu's, SignalPdu's or ReceiverPdu's) goes to
/// UDP `port` of `address`. A world read from the network sends to the loopback only,
/// whatever its address says. A PDU that cannot be sent is one error at the node; then
/// timestamp, and isActive TRUE the first time.
/// Sends `bytes` to the node's UDP `port` of `address` (the loopback for a world read from
/// the network); false, and one error at the node, when it cannot.
bool disSend(DisModel& s, NodeState& ns, const std::vector<std::uint8_t>& bytes) {
  const vrml::Node& n = *ns.node;
  EspduState& st = *ns.espdu;
  std::string address = n.get<FieldType::SFString>("address", std::string("localhost"));
  const auto world = s.nodeScenes.find(&n);
  const vrml::Scene* scene = world != s.nodeScenes.end() ? world->second : s.scene.get();
  if (scene != nullptr && (scene->url.starts_with("http://") || scene->url.starts_with("https://")))
    address = "localhost";  // remote content reaches no other host through the browser
  // rtpHeaderExpected: an RTP header before the PDU (RFC 3550), numbered per node; its
  // timestamp the PDU header's, its SSRC the node's site and application numbers.
  std::vector<std::uint8_t> datagram;
  if (n.get<FieldType::SFBool>("rtpHeaderExpected", false) && bytes.size() >= 8) {
    const std::uint32_t timestamp = (std::uint32_t{bytes[4]} << 24) |
                                    (std::uint32_t{bytes[5]} << 16) |
                                    (std::uint32_t{bytes[6]} << 8) | bytes[7];
    const dis::EntityID me = disEntityOf(n);
    datagram = dis::rtpHeader(st.rtpSequence++, timestamp,
                              (std::uint32_t{me.site} << 16) | me.application);
  }
  datagram.insert(datagram.end(), bytes.begin(), bytes.end());
  std::string error;
  if (!dis::UdpReceiver::sendTo(address, n.get<FieldType::SFInt32>("port", 0), datagram, error)) {
    if (!st.reported)
      s.report(vrml::Severity::error, n, error + ": " + n.typeName() + " writes no PDUs");
    st.reported = true;
    return false;
  }
  return true;
}

/// An EspduTransform writer whose fired1 or fired2 turned TRUE sends one Fire PDU of its
/// fields (disFireBytes) and firedTime, at once (not held for writeInterval, though 0 there
/// still means no writing); another once both were FALSE and one is TRUE again.
void disWriteFire(DisModel& s, NodeState& ns, double now) {
  const vrml::Node& n = *ns.node;
  EspduState& st = *ns.espdu;
  const bool fired =
      n.get<FieldType::SFBool>("fired1", false) || n.get<FieldType::SFBool>("fired2", false);
  if (!fired) st.fireSent = false;
  if (!fired || st.fireSent) return;
  st.fireSent = true;
  if (disSend(s, ns, disFireBytes(n, disTimestamp(now))))
    disEmit(s, ns, "firedTime", FieldValue::make<FieldType::SFTime>(now));
}

void disWrite(DisModel& s, NodeState& ns, double now, int index) {
  const vrml::Node& n = *ns.node;
  EspduState& st = *ns.espdu;
  const double interval = n.get<FieldType::SFTime>("writeInterval", 1.0);
  if (!(interval > 0.0)) return;  // 0: no writing
  if (index == 0) disWriteFire(s, ns, now);
  if (now - st.lastWrite < interval) return;
  st.lastWrite = now;
  const std::vector<std::uint8_t> bytes = index == 0   ? disEntityStateBytes(n, now)
                                          : index == 1 ? disTransmitterBytes(n, now)
                                          : index == 2 ? disSignalBytes(n, now)
                                                       : disReceiverBytes(n, now);
  if (!disSend(s, ns, bytes)) return;
  disEmit(s, ns, "timestamp", FieldValue::make<FieldType::SFTime>(now));
  if (!st.active) {
    st.active = true;
    disEmit(s, ns, "isActive", FieldValue::make<FieldType::SFBool>(true));
  }
}

/// The latest Fire, Detonation and Collision PDUs of entity `key` this frame, sent as an
/// EspduTransform's events (dis_events.cpp).
void disSendWarfare(DisModel& s, NodeState& ns, const DisInbox& inbox, std::uint64_t key,
                    double now) {
  static_assert(std::is_same_v<std::variant_alternative_t<4, dis::Pdu>, dis::FirePdu> &&
                std::is_same_v<std::variant_alternative_t<5, dis::Pdu>, dis::DetonationPdu> &&
                std::is_same_v<std::variant_alternative_t<6, dis::Pdu>, dis::CollisionPdu>);
  const auto latestOf = [&](std::size_t alternative) -> const dis::Pdu* {
    const auto& latest = inbox.latest[alternative];
    const auto it = latest.find(key);
    return it == latest.end() ? nullptr : &inbox.pdus[it->second];
  };
  if (const dis::Pdu* p = latestOf(4)) disSendFire(s, ns, std::get<dis::FirePdu>(*p), now);
  if (const dis::Pdu* p = latestOf(5))
    disSendDetonation(s, ns, std::get<dis::DetonationPdu>(*p), now);
  if (const dis::Pdu* p = latestOf(6))
    disSendCollision(s, ns, std::get<dis::CollisionPdu>(*p), now);
}

}  // namespace

bool ExecutionModel::State::classifyDis(NodeState& ns) {
  const vrml::NodeTypeId id = ns.node->typeId();
  if (disPduIndex(id) < 0 && id != vrml::NodeTypeId::DISEntityManager) return false;
  ns.espdu = std::make_unique<EspduState>();
  espduTransforms.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluateDis() {
  const double now = model.now();
  std::unordered_set<DisInbox*> drained;
  // By index: a DISEntityManager's new EspduTransforms join the list, and are read, now.
  for (std::size_t i = 0; i < espduTransforms.size(); ++i) {
    NodeState& ns = *espduTransforms[i];
    const vrml::Node& n = *ns.node;
    EspduState& st = *ns.espdu;
    const int index = disPduIndex(n.typeId());
    const bool manager = index < 0;
    const std::string mode = n.get<FieldType::SFString>("networkMode", std::string("standAlone"));
    const bool reader = mode == "networkReader";
    const bool writer = mode == "networkWriter" && !manager;
    if (!st.announced && !manager) {
      st.announced = true;
      disEmit(*this, ns, "isNetworkReader", FieldValue::make<FieldType::SFBool>(reader));
      disEmit(*this, ns, "isNetworkWriter", FieldValue::make<FieldType::SFBool>(writer));
      disEmit(*this, ns, "isStandAlone", FieldValue::make<FieldType::SFBool>(!reader && !writer));
    }
    if (writer) {
      if (n.get<FieldType::SFBool>("enabled", true)) disWrite(*this, ns, now, index);
      continue;
    }
    if (!manager && (!reader || !n.get<FieldType::SFBool>("enabled", true))) continue;
    DisInbox* inbox = disInboxOf(*this, ns);
    if (inbox == nullptr) continue;
    if (drained.insert(inbox).second) disDrain(*inbox);
    if (inbox->dropped > 0 && !st.dropReported) {
      st.dropReported = true;
      report(vrml::Severity::warning, n,
             std::to_string(inbox->dropped) + " datagram(s) on UDP " + st.key +
                 " were not Entity State, Fire, Detonation, Collision, Transmitter, Signal "
                 "or Receiver PDUs that decode: dropped (reported once)");
    }
    if (manager) {
      // New entities, entities heard again, entities deactivated; then the silent ones.
      const auto site = static_cast<std::uint16_t>(n.get<FieldType::SFInt32>("siteID", 0));
      const auto application =
          static_cast<std::uint16_t>(n.get<FieldType::SFInt32>("applicationID", 0));
      std::vector<vrml::NodePtr> added, removed;
      for (const dis::Pdu& any : inbox->pdus) {
        // A Remove Entity PDU (IEEE 1278.1 clause 7.5.3) naming one of its entities removes it.
        if (const auto* r = std::get_if<dis::RemoveEntityPdu>(&any)) {
          auto it = st.entities.find(disEntityKey(r->receivingID));
          if (it == st.entities.end()) continue;
          disSet(*it->second.transform, "enabled", FieldValue::make<FieldType::SFBool>(false));
          removed.push_back(it->second.transform);
          st.entities.erase(it);
          continue;
        }
        const auto* p = std::get_if<dis::EntityStatePdu>(&any);
        if (p == nullptr || (site != 0 && p->entityID.site != site) ||
            (application != 0 && p->entityID.application != application))
          continue;
        const std::uint64_t key = disEntityKey(p->entityID);
        const bool deactivated = (p->appearance & kDisDeactivated) != 0;
        auto it = st.entities.find(key);
        if (it != st.entities.end()) {
          it->second.lastHeard = now;
          if (deactivated) {
            disSet(*it->second.transform, "enabled", FieldValue::make<FieldType::SFBool>(false));
            removed.push_back(it->second.transform);
            st.entities.erase(it);
          }
          continue;
        }
        if (deactivated) continue;
        if (st.entities.size() >= kDisMaxEntities) {
          if (!st.limitReported) {
            st.limitReported = true;
            report(vrml::Severity::warning, n,
                   "more than " + std::to_string(kDisMaxEntities) +
                       " DIS entities: the others get no EspduTransform (reported once)");
          }
          continue;
        }
        vrml::NodePtr t = disMakeEntity(n, *p);
        reach(t, false);  // joins espduTransforms: read later in this loop
        st.entities.emplace(key, DisEntityRecord{t, now});
        added.push_back(std::move(t));
      }
      for (auto it = st.entities.begin(); it != st.entities.end();) {
        if (now - it->second.lastHeard > kDisEntityTimeout) {
          disSet(*it->second.transform, "enabled", FieldValue::make<FieldType::SFBool>(false));
          removed.push_back(it->second.transform);
          it = st.entities.erase(it);
        } else {
          ++it;
        }
      }
      if (!added.empty())
        disEmit(*this, ns, "addedEntities", FieldValue::make<FieldType::MFNode>(std::move(added)));
      if (!removed.empty())
        disEmit(*this, ns, "removedEntities",
                FieldValue::make<FieldType::MFNode>(std::move(removed)));
      continue;
    }
    // The latest PDU of this node's entity or radio this frame waits for its next read.
    const dis::EntityID me = disEntityOf(n);
    const std::uint64_t key =
        index == 0 ? disEntityKey(me) : disRadioKey({me, disId(n, "radioID")});
    const auto& latest = inbox->latest[static_cast<std::size_t>(index)];
    if (auto it = latest.find(key); it != latest.end()) st.pending = inbox->pdus[it->second];
    // readInterval 0 means no reading (X3D 4.0 clause 28.4.3's field description).
    const double interval = n.get<FieldType::SFTime>("readInterval", 0.1);
    if (!(interval > 0.0)) continue;
    // An EspduTransform's entity fired, its munition detonated, it collided: events sent
    // the frame their PDU arrives, not held for the next read.
    if (index == 0) disSendWarfare(*this, ns, *inbox, key, now);
    if (!st.pending || now - st.lastRead < interval) {
      // Between PDUs the entity moves as its dead reckoning algorithm says.
      if (st.reckoned) disDeadReckon(*this, ns, now);
      continue;
    }
    st.lastRead = now;
    if (const auto* e = std::get_if<dis::EntityStatePdu>(&*st.pending)) {
      st.reckoned = *e;
      st.reckonedAt = now;
    }
    std::visit(
        [&](const auto& p) {
          using P = std::decay_t<decltype(p)>;
          if constexpr (std::is_same_v<P, dis::EntityStatePdu>)
            disSendEntityState(*this, ns, p);
          else if constexpr (std::is_same_v<P, dis::TransmitterPdu>)
            disSendTransmitter(*this, ns, p);
          else if constexpr (std::is_same_v<P, dis::SignalPdu>)
            disSendSignal(*this, ns, p);
          else if constexpr (std::is_same_v<P, dis::ReceiverPdu>)
            disSendReceiver(*this, ns, p);
        },
        *st.pending);
    st.pending.reset();
    disEmit(*this, ns, "timestamp", FieldValue::make<FieldType::SFTime>(now));
    if (!st.active) {
      st.active = true;
      disEmit(*this, ns, "isActive", FieldValue::make<FieldType::SFBool>(true));
    }
  }
}

}  // namespace gs::runtime
