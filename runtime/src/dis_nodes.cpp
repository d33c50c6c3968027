// X3D DIS (X3D 4.0 clause 28) in the execution model: an EspduTransform whose networkMode is
// "networkReader" listens on UDP `port` of `address` (dis/udp_socket.hpp) and, every
// readInterval seconds, takes the Entity State PDUs (dis/pdu.hpp) of its entity (siteID,
// applicationID, entityID): its translation becomes the PDU's location, its rotation the
// PDU's orientation (DIS Euler angles), and the entity's velocity, acceleration, type,
// force, marking and articulation parameters are sent as its fields' events, with
// timestamp and isActive. Bytes from the network are untrusted: a PDU that does not decode
// is dropped (counted in a warning once), at most kMaxDatagrams are read per frame.
#include "execution_state.hpp"

#include "dis/pdu.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace gs::runtime {

namespace {

using vrml::FieldType;
using vrml::FieldValue;

constexpr std::size_t kMaxDatagrams = 1024;

int disField(const vrml::Node& n, std::string_view name) {
  return n.type().findExact(name);
}

}  // namespace

bool ExecutionModel::State::classifyDis(NodeState& ns) {
  if (ns.node->typeId() != vrml::NodeTypeId::EspduTransform) return false;
  ns.espdu = std::make_unique<EspduState>();
  espduTransforms.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluateDis() {
  const double now = model.now();
  // The datagrams of each receiver, read once per frame and shared by its nodes.
  std::unordered_map<std::string, std::vector<dis::EntityStatePdu>> arrived;
  std::unordered_map<std::string, std::size_t> dropped;
  auto emitIf = [this](NodeState& ns, std::string_view name, FieldValue v) {
    const int i = disField(*ns.node, name);
    if (i >= 0 && ns.node->type().fields[static_cast<std::size_t>(i)].type == v.type())
      emitOwn(ns, i, std::move(v));
  };
  for (NodeState* ns : espduTransforms) {
    const vrml::Node& n = *ns->node;
    EspduState& st = *ns->espdu;
    const bool reader =
        n.get<FieldType::SFString>("networkMode", std::string("standAlone")) == "networkReader";
    if (!st.announced) {
      st.announced = true;
      emitIf(*ns, "isNetworkReader", FieldValue::make<FieldType::SFBool>(reader));
      emitIf(*ns, "isStandAlone", FieldValue::make<FieldType::SFBool>(!reader));
    }
    if (!reader || !n.get<FieldType::SFBool>("enabled", true)) continue;
    const int port = n.get<FieldType::SFInt32>("port", 0);
    const std::string address = n.get<FieldType::SFString>("address", std::string("localhost"));
    const std::string key = address + ":" + std::to_string(port);
    auto& receiver = disReceivers[key];
    if (!receiver) {
      receiver = std::make_unique<dis::UdpReceiver>();
      std::string error;
      if (!receiver->open(port, address, error) && !st.reported) {
        st.reported = true;
        report(vrml::Severity::error, n, error + ": EspduTransform reads no PDUs");
      }
    }
    if (!receiver->isOpen()) continue;
    const double interval = std::max(0.0, n.get<FieldType::SFTime>("readInterval", 0.1));
    if (now - st.lastRead < interval) continue;
    st.lastRead = now;
    if (!arrived.contains(key)) {
      std::vector<dis::EntityStatePdu>& pdus = arrived[key];
      for (const std::vector<std::uint8_t>& d : receiver->receive(kMaxDatagrams)) {
        std::optional<dis::EntityStatePdu> p = dis::decodeEntityState(d, nullptr);
        if (p)
          pdus.push_back(std::move(*p));
        else
          ++dropped[key];
      }
    }
    if (dropped[key] > 0 && !st.dropReported) {
      st.dropReported = true;
      report(vrml::Severity::warning, n,
             std::to_string(dropped[key]) + " datagram(s) on UDP " + key +
                 " were not Entity State PDUs that decode: dropped (reported once)");
    }
    const dis::EntityID me{
        static_cast<std::uint16_t>(n.get<FieldType::SFInt32>("siteID", 0)),
        static_cast<std::uint16_t>(n.get<FieldType::SFInt32>("applicationID", 0)),
        static_cast<std::uint16_t>(n.get<FieldType::SFInt32>("entityID", 0))};
    const dis::EntityStatePdu* latest = nullptr;
    for (const dis::EntityStatePdu& p : arrived[key])
      if (p.entityID == me) latest = &p;
    if (latest == nullptr) continue;
    const dis::EntityStatePdu& p = *latest;
    emitIf(*ns, "translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(p.location)));
    const glm::dquat q = dis::eulerToQuaternion(p.orientation);
    const double angle = 2.0 * std::acos(std::clamp(q.w, -1.0, 1.0));
    const double s = std::sqrt(std::max(0.0, 1.0 - q.w * q.w));
    const vrml::Rotation r =
        s > 1e-9 ? vrml::Rotation(q.x / s, q.y / s, q.z / s, angle) : vrml::Rotation(0, 0, 1, 0);
    emitIf(*ns, "rotation", FieldValue::make<FieldType::SFRotation>(r));
    emitIf(*ns, "linearVelocity", FieldValue::make<FieldType::SFVec3f>(p.linearVelocity));
    emitIf(*ns, "linearAcceleration", FieldValue::make<FieldType::SFVec3f>(p.linearAcceleration));
    emitIf(*ns, "forceID", FieldValue::make<FieldType::SFInt32>(p.forceID));
    emitIf(*ns, "entityKind", FieldValue::make<FieldType::SFInt32>(p.entityType.kind));
    emitIf(*ns, "entityDomain", FieldValue::make<FieldType::SFInt32>(p.entityType.domain));
    emitIf(*ns, "entityCountry", FieldValue::make<FieldType::SFInt32>(p.entityType.country));
    emitIf(*ns, "entityCategory", FieldValue::make<FieldType::SFInt32>(p.entityType.category));
    emitIf(*ns, "entitySubcategory",
           FieldValue::make<FieldType::SFInt32>(p.entityType.subcategory));
    emitIf(*ns, "entitySpecific", FieldValue::make<FieldType::SFInt32>(p.entityType.specific));
    emitIf(*ns, "entityExtra", FieldValue::make<FieldType::SFInt32>(p.entityType.extra));
    emitIf(*ns, "deadReckoning", FieldValue::make<FieldType::SFInt32>(p.deadReckoningAlgorithm));
    emitIf(*ns, "marking", FieldValue::make<FieldType::SFString>(p.marking));
    const auto count = static_cast<std::int32_t>(p.articulationParameters.size());
    emitIf(*ns, "articulationParameterCount", FieldValue::make<FieldType::SFInt32>(count));
    static constexpr std::array<const char*, 8> kValues = {
        "articulationParameterValue0_changed", "articulationParameterValue1_changed",
        "articulationParameterValue2_changed", "articulationParameterValue3_changed",
        "articulationParameterValue4_changed", "articulationParameterValue5_changed",
        "articulationParameterValue6_changed", "articulationParameterValue7_changed"};
    for (std::size_t k = 0; k < kValues.size() && k < p.articulationParameters.size(); ++k)
      emitIf(*ns, kValues[k],
             FieldValue::make<FieldType::SFFloat>(
                 static_cast<float>(p.articulationParameters[k].value)));
    emitIf(*ns, "timestamp", FieldValue::make<FieldType::SFTime>(now));
    if (!st.active) {
      st.active = true;
      emitIf(*ns, "isActive", FieldValue::make<FieldType::SFBool>(true));
    }
  }
}

}  // namespace gs::runtime
