// DIS PDUs (IEEE 1278.1-2012) to and from their big-endian bytes (dis/pdu.hpp).
#include "dis/pdu.hpp"

#include "pdu_bytes.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace gs::dis {

using namespace detail;

std::optional<PduHeader> decodeHeader(std::span<const std::uint8_t> bytes, std::string* error) {
  Reader r(bytes);
  PduHeader h;
  h.protocolVersion = r.u8();
  h.exerciseID = r.u8();
  h.pduType = r.u8();
  h.protocolFamily = r.u8();
  h.timestamp = r.u32();
  h.length = r.u16();
  r.skip(2);
  if (!r.ok()) {
    if (error)
      *error =
          "a PDU of " + std::to_string(bytes.size()) + " bytes, shorter than its 12-byte header";
    return std::nullopt;
  }
  if (h.length < 12 || h.length > bytes.size()) {
    if (error)
      *error = "PDU length " + std::to_string(h.length) + " does not fit the " +
               std::to_string(bytes.size()) + " bytes received";
    return std::nullopt;
  }
  return h;
}

std::optional<EntityStatePdu> decodeEntityState(std::span<const std::uint8_t> bytes,
                                                std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::entityState, "an Entity State PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  EntityStatePdu p;
  p.header = *header;
  p.entityID = entityID(r);
  p.forceID = r.u8();
  const std::size_t parameters = r.u8();
  p.entityType = entityType(r);
  p.alternativeEntityType = entityType(r);
  p.linearVelocity = r.vec3f();
  p.location = vec3d(r);
  p.orientation = r.vec3f();
  p.appearance = r.u32();
  p.deadReckoningAlgorithm = r.u8();
  r.skip(15);  // other dead-reckoning parameters
  p.linearAcceleration = r.vec3f();
  p.angularVelocity = r.vec3f();
  p.markingCharacterSet = r.u8();
  for (int i = 0; i < 11; ++i) {
    const char c = static_cast<char>(r.u8());
    if (c == '\0') {
      r.skip(static_cast<std::size_t>(10 - i));
      break;
    }
    p.marking.push_back(c);
  }
  p.capabilities = r.u32();
  if (!r.ok() || header->length < kEntityStateSize + 16 * parameters) {
    if (error)
      *error = "Entity State PDU of " + std::to_string(header->length) + " bytes, short of the " +
               std::to_string(kEntityStateSize + 16 * parameters) + " its " +
               std::to_string(parameters) + " articulation parameters need";
    return std::nullopt;
  }
  p.articulationParameters.reserve(parameters);
  for (std::size_t i = 0; i < parameters; ++i)
    p.articulationParameters.push_back(articulationParameter(r));
  if (!r.ok() || !finite(p.linearVelocity) || !finite(p.orientation) || !finite(p.location) ||
      !finite(p.linearAcceleration) || !finite(p.angularVelocity)) {
    if (error) *error = "Entity State PDU with a number that is not finite";
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeEntityState(const EntityStatePdu& p) {
  Writer w;
  const std::size_t parameters =
      std::min(p.articulationParameters.size(), kMaxArticulationParameters);
  writeHeader(w, p.header, PduType::entityState, p.header.protocolFamily,
              kEntityStateSize + 16 * parameters);
  entityID(w, p.entityID);
  w.u8(p.forceID);
  w.u8(static_cast<std::uint8_t>(parameters));
  entityType(w, p.entityType);
  entityType(w, p.alternativeEntityType);
  w.vec3f(p.linearVelocity);
  vec3d(w, p.location);
  w.vec3f(p.orientation);
  w.u32(p.appearance);
  w.u8(p.deadReckoningAlgorithm);
  for (int i = 0; i < 15; ++i) w.u8(0);
  w.vec3f(p.linearAcceleration);
  w.vec3f(p.angularVelocity);
  w.u8(p.markingCharacterSet);
  for (std::size_t i = 0; i < 11; ++i)
    w.u8(i < p.marking.size() ? static_cast<std::uint8_t>(p.marking[i]) : 0);
  w.u32(p.capabilities);
  for (std::size_t i = 0; i < parameters; ++i)
    articulationParameter(w, p.articulationParameters[i]);
  return std::move(w.out);
}

std::optional<TransmitterPdu> decodeTransmitter(std::span<const std::uint8_t> bytes,
                                                std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::transmitter, "a Transmitter PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  TransmitterPdu p;
  p.header = *header;
  p.radio = radioID(r);
  p.radioEntityType.kind = r.u8();
  p.radioEntityType.domain = r.u8();
  p.radioEntityType.country = r.u16();
  p.radioEntityType.category = r.u8();
  p.radioEntityType.nomenclatureVersion = r.u8();
  p.radioEntityType.nomenclature = r.u16();
  p.transmitState = r.u8();
  p.inputSource = r.u8();
  r.skip(2);  // number of Variable Transmitter Parameters records (1998: padding)
  p.antennaLocation = vec3d(r);
  p.relativeAntennaLocation = r.vec3f();
  p.antennaPatternType = r.u16();
  const std::size_t patternLength = r.u16();
  p.frequency = r.unsignedOf(8);
  p.transmitFrequencyBandwidth = r.f32();
  p.power = r.f32();
  p.modulationType.spreadSpectrum = r.u16();
  p.modulationType.major = r.u16();
  p.modulationType.detail = r.u16();
  p.modulationType.radioSystem = r.u16();
  p.cryptoSystem = r.u16();
  p.cryptoKeyID = r.u16();
  const std::size_t modulationLength = r.u8();
  r.skip(3);  // padding
  const std::size_t needed = kTransmitterSize + modulationLength + patternLength;
  if (!r.ok() || header->length < needed) {
    shortError(error, "Transmitter PDU", header->length, needed);
    return std::nullopt;
  }
  // Both lengths are now known to lie inside the datagram: what is allocated is read.
  p.modulationParameters.resize(modulationLength);
  for (std::uint8_t& b : p.modulationParameters) b = r.u8();
  p.antennaPattern.resize(patternLength);
  for (std::uint8_t& b : p.antennaPattern) b = r.u8();
  if (!r.ok() || !finite(p.antennaLocation) || !finite(p.relativeAntennaLocation) ||
      !std::isfinite(p.transmitFrequencyBandwidth) || !std::isfinite(p.power)) {
    if (error) *error = "Transmitter PDU with a number that is not finite";
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeTransmitter(const TransmitterPdu& p) {
  Writer w;
  const std::size_t modulationLength = std::min<std::size_t>(p.modulationParameters.size(), 255);
  const std::size_t patternLength = std::min(p.antennaPattern.size(), kMaxAntennaPattern);
  writeHeader(w, p.header, PduType::transmitter, kRadioCommunicationsFamily,
              kTransmitterSize + modulationLength + patternLength);
  radioID(w, p.radio);
  w.u8(p.radioEntityType.kind);
  w.u8(p.radioEntityType.domain);
  w.u16(p.radioEntityType.country);
  w.u8(p.radioEntityType.category);
  w.u8(p.radioEntityType.nomenclatureVersion);
  w.u16(p.radioEntityType.nomenclature);
  w.u8(p.transmitState);
  w.u8(p.inputSource);
  w.u16(0);  // no Variable Transmitter Parameters records
  vec3d(w, p.antennaLocation);
  w.vec3f(p.relativeAntennaLocation);
  w.u16(p.antennaPatternType);
  w.u16(static_cast<std::uint16_t>(patternLength));
  w.unsignedOf(p.frequency, 8);
  w.f32(p.transmitFrequencyBandwidth);
  w.f32(p.power);
  w.u16(p.modulationType.spreadSpectrum);
  w.u16(p.modulationType.major);
  w.u16(p.modulationType.detail);
  w.u16(p.modulationType.radioSystem);
  w.u16(p.cryptoSystem);
  w.u16(p.cryptoKeyID);
  w.u8(static_cast<std::uint8_t>(modulationLength));
  w.u8(0);
  w.u16(0);
  for (std::size_t i = 0; i < modulationLength; ++i) w.u8(p.modulationParameters[i]);
  for (std::size_t i = 0; i < patternLength; ++i) w.u8(p.antennaPattern[i]);
  return std::move(w.out);
}

std::optional<SignalPdu> decodeSignal(std::span<const std::uint8_t> bytes, std::string* error) {
  const std::optional<PduHeader> header = headerOf(bytes, PduType::signal, "a Signal PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  SignalPdu p;
  p.header = *header;
  p.radio = radioID(r);
  p.encodingScheme = r.u16();
  p.tdlType = r.u16();
  p.sampleRate = r.u32();
  p.dataLength = r.u16();
  p.samples = r.u16();
  const std::size_t dataBytes = (static_cast<std::size_t>(p.dataLength) + 7) / 8;
  if (!r.ok() || header->length < kSignalSize + dataBytes) {
    shortError(error, "Signal PDU", header->length, kSignalSize + dataBytes);
    return std::nullopt;
  }
  p.data.resize(dataBytes);  // inside the datagram: checked above
  for (std::uint8_t& b : p.data) b = r.u8();
  if (!r.ok()) {
    shortError(error, "Signal PDU", header->length, kSignalSize + dataBytes);
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeSignal(const SignalPdu& p) {
  Writer w;
  const std::size_t announced = (static_cast<std::size_t>(p.dataLength) + 7) / 8;
  const std::size_t dataBytes = std::min({p.data.size(), kMaxSignalData, announced});
  const std::size_t bits = std::min<std::size_t>(p.dataLength, 8 * dataBytes);
  const std::size_t padded = (dataBytes + 3) / 4 * 4;
  writeHeader(w, p.header, PduType::signal, kRadioCommunicationsFamily, kSignalSize + padded);
  radioID(w, p.radio);
  w.u16(p.encodingScheme);
  w.u16(p.tdlType);
  w.u32(p.sampleRate);
  w.u16(static_cast<std::uint16_t>(bits));
  w.u16(p.samples);
  for (std::size_t i = 0; i < padded; ++i) w.u8(i < dataBytes ? p.data[i] : 0);
  return std::move(w.out);
}

std::optional<ReceiverPdu> decodeReceiver(std::span<const std::uint8_t> bytes, std::string* error) {
  const std::optional<PduHeader> header =
      headerOf(bytes, PduType::receiver, "a Receiver PDU", error);
  if (!header) return std::nullopt;
  Reader r(bytes.first(header->length));
  r.skip(12);
  ReceiverPdu p;
  p.header = *header;
  p.radio = radioID(r);
  p.receiverState = r.u16();
  r.skip(2);  // padding
  p.receivedPower = r.f32();
  p.transmitter = radioID(r);
  if (!r.ok()) {
    shortError(error, "Receiver PDU", header->length, kReceiverSize);
    return std::nullopt;
  }
  if (!std::isfinite(p.receivedPower)) {
    if (error) *error = "Receiver PDU with a received power that is not finite";
    return std::nullopt;
  }
  return p;
}

std::vector<std::uint8_t> encodeReceiver(const ReceiverPdu& p) {
  Writer w;
  writeHeader(w, p.header, PduType::receiver, kRadioCommunicationsFamily, kReceiverSize);
  radioID(w, p.radio);
  w.u16(p.receiverState);
  w.u16(0);
  w.f32(p.receivedPower);
  radioID(w, p.transmitter);
  return std::move(w.out);
}

std::optional<Pdu> decodePdu(std::span<const std::uint8_t> bytes, std::string* error) {
  const std::optional<PduHeader> header = decodeHeader(bytes, error);
  if (!header) return std::nullopt;
  switch (header->pduType) {
    case static_cast<std::uint8_t>(PduType::entityState):
      if (auto p = decodeEntityState(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::transmitter):
      if (auto p = decodeTransmitter(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::signal):
      if (auto p = decodeSignal(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::receiver):
      if (auto p = decodeReceiver(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::fire):
      if (auto p = decodeFire(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::detonation):
      if (auto p = decodeDetonation(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::collision):
      if (auto p = decodeCollision(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    case static_cast<std::uint8_t>(PduType::removeEntity):
      if (auto p = decodeRemoveEntity(bytes, error)) return Pdu(std::move(*p));
      return std::nullopt;
    default:
      break;
  }
  if (error)
    *error = "PDU type " + std::to_string(header->pduType) +
             " is not read (only Entity State 1, Fire 2, Detonation 3, Collision 4, "
             "Remove Entity 12, Transmitter 25, Signal 26, Receiver 27)";
  return std::nullopt;
}

glm::dquat eulerToQuaternion(const glm::vec3& e) {
  const glm::dquat psi = glm::angleAxis(static_cast<double>(e.x), glm::dvec3(0, 0, 1));
  const glm::dquat theta = glm::angleAxis(static_cast<double>(e.y), glm::dvec3(0, 1, 0));
  const glm::dquat phi = glm::angleAxis(static_cast<double>(e.z), glm::dvec3(1, 0, 0));
  return psi * theta * phi;
}

glm::vec3 quaternionToEuler(const glm::dquat& q0) {
  const glm::dquat q = glm::normalize(q0);
  // R = Rz(psi) Ry(theta) Rx(phi): the z-y-x Tait-Bryan angles.
  const double psi = std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
  const double theta = std::asin(std::clamp(2.0 * (q.w * q.y - q.z * q.x), -1.0, 1.0));
  const double phi = std::atan2(2.0 * (q.w * q.x + q.y * q.z), 1.0 - 2.0 * (q.x * q.x + q.y * q.y));
  return {static_cast<float>(psi), static_cast<float>(theta), static_cast<float>(phi)};
}

}  // namespace gs::dis
