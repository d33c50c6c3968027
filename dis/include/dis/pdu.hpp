// DIS protocol data units (IEEE 1278.1-2012, "Distributed Interactive Simulation —
// Application protocols"; X3D 4.0 clause 28 names the PDUs its DIS nodes read): the PDU
// header and the Entity State PDU (type 1), decoded from and encoded to their big-endian
// bytes. Pure computation on bytes: no sockets (dis/udp_socket.hpp), no nodes (runtime/).
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace gs::dis {

/// PDU types this reader knows (IEEE 1278.1 table 7, "DIS PDU type").
enum class PduType : std::uint8_t {
  entityState = 1,
  fire = 2,
  detonation = 3,
  collision = 4,
  transmitter = 25,
  signal = 26,
  receiver = 27,
};

/// The 12-byte PDU header (IEEE 1278.1 clause 6.2.66).
struct PduHeader {
  std::uint8_t protocolVersion = 7;  // 6: IEEE 1278.1a-1998, 7: IEEE 1278.1-2012
  std::uint8_t exerciseID = 1;
  std::uint8_t pduType = 1;         // PduType
  std::uint8_t protocolFamily = 1;  // 1: entity information/interaction
  std::uint32_t timestamp = 0;      // DIS time units (2^31 per hour), bit 0: absolute
  std::uint16_t length = 0;         // bytes of the whole PDU, header included
};

/// An entity's identity: site, application and entity numbers (clause 6.2.28).
struct EntityID {
  std::uint16_t site = 0, application = 0, entity = 0;
  bool operator==(const EntityID&) const = default;
};

/// An entity type record (clause 6.2.30): kind, domain, country, category, subcategory,
/// specific, extra.
struct EntityType {
  std::uint8_t kind = 0, domain = 0;
  std::uint16_t country = 0;
  std::uint8_t category = 0, subcategory = 0, specific = 0, extra = 0;
};

/// One articulation parameter record (clause 6.2.94, 16 bytes).
struct ArticulationParameter {
  std::uint8_t typeDesignator = 0;  // 0: articulated part, 1: attached part
  std::uint8_t changeIndicator = 0;
  std::uint16_t idAttachedTo = 0;
  std::uint32_t parameterType = 0;
  double value = 0.0;  // the first 4 bytes as a float32 for an articulated part, as IEEE says
};

/// The Entity State PDU (clause 7.2.2; 144 bytes plus 16 per articulation parameter).
struct EntityStatePdu {
  PduHeader header;
  EntityID entityID;
  std::uint8_t forceID = 0;
  EntityType entityType;
  EntityType alternativeEntityType;
  glm::vec3 linearVelocity{0.0f};  // metres per second, world (geocentric) axes
  glm::dvec3 location{0.0};        // metres, world (geocentric) coordinates
  glm::vec3 orientation{0.0f};     // Euler angles psi, theta, phi (radians)
  std::uint32_t appearance = 0;
  std::uint8_t deadReckoningAlgorithm = 0;
  glm::vec3 linearAcceleration{0.0f};    // metres per second squared
  glm::vec3 angularVelocity{0.0f};       // radians per second, body axes
  std::uint8_t markingCharacterSet = 1;  // 1: ASCII
  std::string marking;                   // at most 11 characters
  std::uint32_t capabilities = 0;
  std::vector<ArticulationParameter> articulationParameters;
};

/// Most articulation parameters a PDU may carry (its count is one byte).
inline constexpr std::size_t kMaxArticulationParameters = 255;
/// The Entity State PDU's fixed part, in bytes.
inline constexpr std::size_t kEntityStateSize = 144;

/// The header of `bytes`, or nothing (and `error` says why) when there are fewer than 12
/// bytes or its length field is below 12 or above the bytes given.
std::optional<PduHeader> decodeHeader(std::span<const std::uint8_t> bytes, std::string* error);

/// The Entity State PDU in `bytes` (one datagram), or nothing and `error` (when not null)
/// says why: another PDU type, a length short of 144 + 16 x its articulation parameters or
/// beyond the bytes, a non-finite number. Never reads outside `bytes`.
std::optional<EntityStatePdu> decodeEntityState(std::span<const std::uint8_t> bytes,
                                                std::string* error);

/// The bytes of `pdu` (header length set to what is written; at most
/// kMaxArticulationParameters parameters, the marking cut to 11 characters).
std::vector<std::uint8_t> encodeEntityState(const EntityStatePdu& pdu);

/// The rotation (axis and angle, radians) of DIS Euler angles (psi about z, then theta
/// about the new y, then phi about the new x: IEEE 1278.1 annex B, the body's x forward,
/// y right, z down), as a quaternion (x, y, z, w).
glm::dquat eulerToQuaternion(const glm::vec3& psiThetaPhi);

}  // namespace gs::dis
