// DIS PDUs (IEEE 1278.1-2012) to and from their big-endian bytes (dis/pdu.hpp).
#include "dis/pdu.hpp"

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
  const std::optional<PduHeader> header = decodeHeader(bytes, error);
  if (!header) return std::nullopt;
  if (header->pduType != static_cast<std::uint8_t>(PduType::entityState)) {
    if (error)
      *error = "PDU type " + std::to_string(header->pduType) + ", not an Entity State PDU (1)";
    return std::nullopt;
  }
  Reader r(bytes.first(header->length));
  r.skip(12);
  EntityStatePdu p;
  p.header = *header;
  p.entityID.site = r.u16();
  p.entityID.application = r.u16();
  p.entityID.entity = r.u16();
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
  w.u8(p.header.protocolVersion);
  w.u8(p.header.exerciseID);
  w.u8(static_cast<std::uint8_t>(PduType::entityState));
  w.u8(p.header.protocolFamily);
  w.u32(p.header.timestamp);
  w.u16(static_cast<std::uint16_t>(kEntityStateSize + 16 * parameters));
  w.u16(0);
  w.u16(p.entityID.site);
  w.u16(p.entityID.application);
  w.u16(p.entityID.entity);
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

glm::dquat eulerToQuaternion(const glm::vec3& e) {
  const glm::dquat psi = glm::angleAxis(static_cast<double>(e.x), glm::dvec3(0, 0, 1));
  const glm::dquat theta = glm::angleAxis(static_cast<double>(e.y), glm::dvec3(0, 1, 0));
  const glm::dquat phi = glm::angleAxis(static_cast<double>(e.z), glm::dvec3(1, 0, 0));
  return psi * theta * phi;
}

}  // namespace gs::dis
