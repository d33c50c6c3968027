// DIS PDUs (IEEE 1278.1-2012) to and from their big-endian bytes (dis/pdu.hpp).
#include "dis/pdu.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace gs::dis {

namespace {

/// Reads big-endian values from a span; past its end every read gives 0 and ok() is false.
class Reader {
 public:
  explicit Reader(std::span<const std::uint8_t> b) : b_(b) {}
  bool ok() const { return ok_; }
  std::uint64_t unsignedOf(std::size_t n) {
    if (at_ + n > b_.size()) {
      ok_ = false;
      return 0;
    }
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < n; ++i) v = (v << 8) | b_[at_ + i];
    at_ += n;
    return v;
  }
  std::uint8_t u8() { return static_cast<std::uint8_t>(unsignedOf(1)); }
  std::uint16_t u16() { return static_cast<std::uint16_t>(unsignedOf(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(unsignedOf(4)); }
  float f32() { return std::bit_cast<float>(u32()); }
  double f64() { return std::bit_cast<double>(unsignedOf(8)); }
  glm::vec3 vec3f() {
    const float x = f32(), y = f32(), z = f32();
    return {x, y, z};
  }
  void skip(std::size_t n) {
    if (at_ + n > b_.size())
      ok_ = false;
    else
      at_ += n;
  }

 private:
  std::span<const std::uint8_t> b_;
  std::size_t at_ = 0;
  bool ok_ = true;
};

class Writer {
 public:
  void unsignedOf(std::uint64_t v, std::size_t n) {
    for (std::size_t i = n; i-- > 0;) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  void u8(std::uint8_t v) { unsignedOf(v, 1); }
  void u16(std::uint16_t v) { unsignedOf(v, 2); }
  void u32(std::uint32_t v) { unsignedOf(v, 4); }
  void f32(float v) { u32(std::bit_cast<std::uint32_t>(v)); }
  void f64(double v) { unsignedOf(std::bit_cast<std::uint64_t>(v), 8); }
  void vec3f(const glm::vec3& v) {
    f32(v.x);
    f32(v.y);
    f32(v.z);
  }
  std::vector<std::uint8_t> out;
};

EntityType entityType(Reader& r) {
  EntityType t;
  t.kind = r.u8();
  t.domain = r.u8();
  t.country = r.u16();
  t.category = r.u8();
  t.subcategory = r.u8();
  t.specific = r.u8();
  t.extra = r.u8();
  return t;
}

void entityType(Writer& w, const EntityType& t) {
  w.u8(t.kind);
  w.u8(t.domain);
  w.u16(t.country);
  w.u8(t.category);
  w.u8(t.subcategory);
  w.u8(t.specific);
  w.u8(t.extra);
}

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

EntityID entityID(Reader& r) {
  EntityID e;
  e.site = r.u16();
  e.application = r.u16();
  e.entity = r.u16();
  return e;
}

void entityID(Writer& w, const EntityID& e) {
  w.u16(e.site);
  w.u16(e.application);
  w.u16(e.entity);
}

RadioID radioID(Reader& r) {
  RadioID id;
  id.entity = entityID(r);
  id.radio = r.u16();
  return id;
}

void radioID(Writer& w, const RadioID& id) {
  entityID(w, id.entity);
  w.u16(id.radio);
}

/// The header of `bytes` when it decodes and names PDU type `type`, else nothing and
/// `error` says why (`name`: the PDU's name for the message).
std::optional<PduHeader> headerOf(std::span<const std::uint8_t> bytes, PduType type,
                                  const char* name, std::string* error) {
  std::optional<PduHeader> header = decodeHeader(bytes, error);
  if (header && header->pduType != static_cast<std::uint8_t>(type)) {
    if (error)
      *error = "PDU type " + std::to_string(header->pduType) + ", not " + name + " (" +
               std::to_string(static_cast<int>(type)) + ")";
    return std::nullopt;
  }
  return header;
}

void writeHeader(Writer& w, const PduHeader& h, PduType type, std::uint8_t family,
                 std::size_t length) {
  w.u8(h.protocolVersion);
  w.u8(h.exerciseID);
  w.u8(static_cast<std::uint8_t>(type));
  w.u8(family);
  w.u32(h.timestamp);
  w.u16(static_cast<std::uint16_t>(length));
  w.u16(0);
}

void shortError(std::string* error, const char* name, std::size_t length, std::size_t needed) {
  if (error)
    *error = std::string(name) + " of " + std::to_string(length) + " bytes, short of the " +
             std::to_string(needed) + " its fields announce";
}

}  // namespace

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
  p.location.x = r.f64();
  p.location.y = r.f64();
  p.location.z = r.f64();
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
  for (std::size_t i = 0; i < parameters; ++i) {
    ArticulationParameter a;
    a.typeDesignator = r.u8();
    a.changeIndicator = r.u8();
    a.idAttachedTo = r.u16();
    a.parameterType = r.u32();
    a.value = a.typeDesignator == 0 ? static_cast<double>(r.f32()) : r.f64();
    if (a.typeDesignator == 0) r.skip(4);
    p.articulationParameters.push_back(a);
  }
  if (!r.ok() || !finite(p.linearVelocity) || !finite(p.orientation) ||
      !std::isfinite(p.location.x) || !std::isfinite(p.location.y) ||
      !std::isfinite(p.location.z) || !finite(p.linearAcceleration) || !finite(p.angularVelocity)) {
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
  w.f64(p.location.x);
  w.f64(p.location.y);
  w.f64(p.location.z);
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
  for (std::size_t i = 0; i < parameters; ++i) {
    const ArticulationParameter& a = p.articulationParameters[i];
    w.u8(a.typeDesignator);
    w.u8(a.changeIndicator);
    w.u16(a.idAttachedTo);
    w.u32(a.parameterType);
    if (a.typeDesignator == 0) {
      w.f32(static_cast<float>(a.value));
      w.u32(0);
    } else {
      w.f64(a.value);
    }
  }
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
  p.antennaLocation.x = r.f64();
  p.antennaLocation.y = r.f64();
  p.antennaLocation.z = r.f64();
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
  w.f64(p.antennaLocation.x);
  w.f64(p.antennaLocation.y);
  w.f64(p.antennaLocation.z);
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
    default:
      break;
  }
  if (error)
    *error = "PDU type " + std::to_string(header->pduType) +
             " is not read (only Entity State 1, Transmitter 25, Signal 26, Receiver 27)";
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
