// The big-endian byte reading and writing the PDU codecs share (pdu.cpp,
// warfare_pdu.cpp): a bounds-checked Reader, a Writer, and the records several PDUs hold
// (IEEE 1278.1-2012 clause 6.2: entity and radio IDs, entity types, the PDU header).
// Internal to dis/.
#pragma once

#include "dis/pdu.hpp"

#include <bit>
#include <cmath>
#include <string>

namespace gs::dis::detail {

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

inline EntityType entityType(Reader& r) {
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

inline void entityType(Writer& w, const EntityType& t) {
  w.u8(t.kind);
  w.u8(t.domain);
  w.u16(t.country);
  w.u8(t.category);
  w.u8(t.subcategory);
  w.u8(t.specific);
  w.u8(t.extra);
}

inline bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline EntityID entityID(Reader& r) {
  EntityID e;
  e.site = r.u16();
  e.application = r.u16();
  e.entity = r.u16();
  return e;
}

inline void entityID(Writer& w, const EntityID& e) {
  w.u16(e.site);
  w.u16(e.application);
  w.u16(e.entity);
}

inline RadioID radioID(Reader& r) {
  RadioID id;
  id.entity = entityID(r);
  id.radio = r.u16();
  return id;
}

inline void radioID(Writer& w, const RadioID& id) {
  entityID(w, id.entity);
  w.u16(id.radio);
}

/// The header of `bytes` when it decodes and names PDU type `type`, else nothing and
/// `error` says why (`name`: the PDU's name for the message).
inline std::optional<PduHeader> headerOf(std::span<const std::uint8_t> bytes, PduType type,
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

inline void writeHeader(Writer& w, const PduHeader& h, PduType type, std::uint8_t family,
                        std::size_t length) {
  w.u8(h.protocolVersion);
  w.u8(h.exerciseID);
  w.u8(static_cast<std::uint8_t>(type));
  w.u8(family);
  w.u32(h.timestamp);
  w.u16(static_cast<std::uint16_t>(length));
  w.u16(0);
}

inline void shortError(std::string* error, const char* name, std::size_t length,
                       std::size_t needed) {
  if (error)
    *error = std::string(name) + " of " + std::to_string(length) + " bytes, short of the " +
             std::to_string(needed) + " its fields announce";
}

/// One articulation parameter record (clause 6.2.94, 16 bytes): an articulated part's
/// value is a float32 and 4 bytes of padding, an attached part's a float64.
inline ArticulationParameter articulationParameter(Reader& r) {
  ArticulationParameter a;
  a.typeDesignator = r.u8();
  a.changeIndicator = r.u8();
  a.idAttachedTo = r.u16();
  a.parameterType = r.u32();
  a.value = a.typeDesignator == 0 ? static_cast<double>(r.f32()) : r.f64();
  if (a.typeDesignator == 0) r.skip(4);
  return a;
}

inline void articulationParameter(Writer& w, const ArticulationParameter& a) {
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

inline glm::dvec3 vec3d(Reader& r) {
  const double x = r.f64(), y = r.f64(), z = r.f64();
  return {x, y, z};
}

inline void vec3d(Writer& w, const glm::dvec3& v) {
  w.f64(v.x);
  w.f64(v.y);
  w.f64(v.z);
}

}  // namespace gs::dis::detail
