// DIS protocol data units (IEEE 1278.1-2012, "Distributed Interactive Simulation —
// Application protocols"; X3D 4.0 clause 28 names the PDUs its DIS nodes read): the PDU
// header, the Entity State PDU (type 1), the warfare PDUs (Fire 2, Detonation 3), the
// Collision PDU (4) and the radio communications PDUs (Transmitter 25, Signal 26,
// Receiver 27), decoded from and encoded to their big-endian bytes. Pure
// computation on bytes: no sockets (dis/udp_socket.hpp), no nodes (runtime/). Every
// decoder treats its bytes as untrusted: each length field is checked against the
// datagram before anything is read or allocated by it.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace gs::dis {

/// PDU types this reader knows (IEEE 1278.1 table 7, "DIS PDU type").
enum class PduType : std::uint8_t {
  entityState = 1,
  fire = 2,
  detonation = 3,
  collision = 4,
  removeEntity = 12,
  transmitter = 25,
  signal = 26,
  receiver = 27,
};

/// Protocol families (IEEE 1278.1 table 8, "Protocol family"): the header's
/// protocolFamily of the PDUs this reader knows.
inline constexpr std::uint8_t kEntityInformationFamily = 1;     // Entity State, Collision PDUs
inline constexpr std::uint8_t kWarfareFamily = 2;               // Fire, Detonation PDUs
inline constexpr std::uint8_t kRadioCommunicationsFamily = 4;   // Transmitter, Signal, Receiver
inline constexpr std::uint8_t kSimulationManagementFamily = 5;  // Remove Entity PDU

/// The 12-byte PDU header (IEEE 1278.1 clause 6.2.66).
struct PduHeader {
  std::uint8_t protocolVersion = 7;  // 6: IEEE 1278.1a-1998, 7: IEEE 1278.1-2012
  std::uint8_t exerciseID = 1;
  std::uint8_t pduType = 1;         // PduType
  std::uint8_t protocolFamily = 1;  // 1: entity information/interaction, 4: radio
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

/// An event's identity (IEEE 1278.1 clause 6.2.33): the site and application that issued
/// it and its event number there.
struct EventID {
  std::uint16_t site = 0, application = 0, eventNumber = 0;
  bool operator==(const EventID&) const = default;
};

/// A Munition Descriptor record (IEEE 1278.1 clause 6.2.19.2; DIS 6's Burst Descriptor,
/// 16 bytes): what was fired or detonated.
struct MunitionDescriptor {
  EntityType munitionType;
  std::uint16_t warhead = 0;   // SISO-REF-010 warhead enumeration
  std::uint16_t fuse = 0;      // SISO-REF-010 fuse enumeration
  std::uint16_t quantity = 0;  // rounds in the burst
  std::uint16_t rate = 0;      // rounds per minute
};

/// The Fire PDU (IEEE 1278.1 clause 7.3.2; 96 bytes): an entity fired a munition.
struct FirePdu {
  PduHeader header;
  EntityID firingEntityID;
  EntityID targetEntityID;  // 0 0 0: no target
  EntityID munitionID;      // the munition entity, 0 0 0 when it is not tracked
  EventID eventID;
  std::uint32_t fireMissionIndex = 0;
  glm::dvec3 location{0.0};  // where it was fired, metres, world (geocentric) coordinates
  MunitionDescriptor descriptor;
  glm::vec3 velocity{0.0f};  // the munition's at launch, metres per second, world axes
  float range = 0.0f;        // metres the fire control assumed, 0 if none
};

/// The Detonation PDU (IEEE 1278.1 clause 7.3.3; 104 bytes plus 16 per variable
/// parameter record): a munition detonated or hit.
struct DetonationPdu {
  PduHeader header;
  EntityID firingEntityID;
  EntityID targetEntityID;
  EntityID munitionID;       // DIS 7's exploding entity
  EventID eventID;           // the Fire PDU's event
  glm::vec3 velocity{0.0f};  // the munition's before impact, metres per second, world axes
  glm::dvec3 location{0.0};  // metres, world (geocentric) coordinates
  MunitionDescriptor descriptor;
  glm::vec3 locationInEntity{0.0f};   // metres, the target entity's body axes
  std::uint8_t detonationResult = 0;  // SISO-REF-010 detonation result
  std::vector<ArticulationParameter> articulationParameters;
};

/// The Collision PDU (IEEE 1278.1 clause 7.2.3; 60 bytes): an entity collided with another
/// entity or with an object.
struct CollisionPdu {
  PduHeader header;
  EntityID issuingEntityID;    // the entity that reports the collision
  EntityID collidingEntityID;  // what it collided with, 0 0 0 when not an entity
  EventID eventID;
  std::uint8_t collisionType = 0;  // 0: inelastic, 1: elastic, 55: boom nozzle
  glm::vec3 velocity{0.0f};        // the issuing entity's, metres per second, world axes
  float mass = 0.0f;               // kilograms
  glm::vec3 location{0.0f};        // metres, the issuing entity's body axes
};

/// The Remove Entity PDU (IEEE 1278.1 clause 7.5.3; 28 bytes): simulation application
/// `originatingID` asks that the entity `receivingID` be removed from the exercise.
struct RemoveEntityPdu {
  PduHeader header;
  EntityID originatingID;  // who asks (a simulation manager)
  EntityID receivingID;    // the entity to remove
  std::uint32_t requestID = 0;
};

/// The Remove Entity PDU's size, in bytes.
inline constexpr std::size_t kRemoveEntitySize = 28;
/// The Fire PDU's size, in bytes.
inline constexpr std::size_t kFireSize = 96;
/// The Detonation PDU's fixed part, in bytes.
inline constexpr std::size_t kDetonationSize = 104;
/// The Collision PDU's size, in bytes.
inline constexpr std::size_t kCollisionSize = 60;

/// A radio's identity (IEEE 1278.1 clause 7.7.1): the entity (or object) it belongs to,
/// the Radio Reference ID, and its Radio Number within that entity.
struct RadioID {
  EntityID entity;
  std::uint16_t radio = 0;
  bool operator==(const RadioID&) const = default;
};

/// A Radio Entity Type record (IEEE 1278.1 clause 6.2.71, 8 bytes): what kind of radio.
struct RadioEntityType {
  std::uint8_t kind = 0, domain = 0;
  std::uint16_t country = 0;
  std::uint8_t category = 0, nomenclatureVersion = 0;
  std::uint16_t nomenclature = 0;
};

/// A Modulation Type record (IEEE 1278.1 clause 6.2.59, 8 bytes).
struct ModulationType {
  std::uint16_t spreadSpectrum = 0;  // a bit field of spread spectrum techniques
  std::uint16_t major = 0;           // major modulation (amplitude, angle, ...)
  std::uint16_t detail = 0;          // detail within the major modulation
  std::uint16_t radioSystem = 0;     // radio system (generic, HQ, SINCGARS, ...)
};

/// The Transmitter PDU (IEEE 1278.1 clause 7.7.2; 104 bytes, then the modulation
/// parameters and the antenna pattern, whose lengths the fixed part gives). The
/// Variable Transmitter Parameters records IEEE 1278.1-2012 allows after them are skipped
/// on decoding and not written on encoding (their count is written as 0).
struct TransmitterPdu {
  PduHeader header;
  RadioID radio;
  RadioEntityType radioEntityType;
  std::uint8_t transmitState = 0;   // 0: off, 1: on but not transmitting, 2: on and transmitting
  std::uint8_t inputSource = 0;     // 0: other, 1: pilot, 2: copilot, ...
  glm::dvec3 antennaLocation{0.0};  // metres, world (geocentric) coordinates
  glm::vec3 relativeAntennaLocation{0.0f};  // metres, the entity's body axes
  std::uint16_t antennaPatternType = 0;     // 0: omnidirectional, 1: beam, ...
  std::uint64_t frequency = 0;              // centre frequency, hertz
  float transmitFrequencyBandwidth = 0.0f;  // hertz
  float power = 0.0f;                       // average power, decibel-milliwatts (dBm)
  ModulationType modulationType;
  std::uint16_t cryptoSystem = 0;                  // 0: none
  std::uint16_t cryptoKeyID = 0;                   // bit 15: baseband encryption; bits 0-14 key
  std::vector<std::uint8_t> modulationParameters;  // at most 255 bytes
  std::vector<std::uint8_t> antennaPattern;        // at most kMaxAntennaPattern bytes
};

/// The Signal PDU (IEEE 1278.1 clause 7.7.3; 32 bytes, then the data: dataLength bits,
/// padded with zeros to a 32-bit boundary).
struct SignalPdu {
  PduHeader header;
  RadioID radio;
  std::uint16_t encodingScheme = 0;  // bits 14-15: encoding class, bits 0-13: type or TDL
  std::uint16_t tdlType = 0;         // tactical data link type, 0: other
  std::uint32_t sampleRate = 0;      // samples per second (audio) or bits per second (data)
  std::uint16_t dataLength = 0;      // bits of data (0..65535)
  std::uint16_t samples = 0;         // samples in this PDU (encoded audio), else 0
  std::vector<std::uint8_t> data;    // ceil(dataLength / 8) bytes
};

/// The Receiver PDU (IEEE 1278.1 clause 7.7.4; 36 bytes).
struct ReceiverPdu {
  PduHeader header;
  RadioID radio;
  std::uint16_t receiverState = 0;  // 0: off, 1: on but not receiving, 2: on and receiving
  float receivedPower = 0.0f;       // decibel-milliwatts (dBm), after losses and gains
  RadioID transmitter;              // the transmitter it receives
};

/// The Transmitter PDU's fixed part, in bytes.
inline constexpr std::size_t kTransmitterSize = 104;
/// The Signal PDU's fixed part, in bytes.
inline constexpr std::size_t kSignalSize = 32;
/// The Receiver PDU's size, in bytes.
inline constexpr std::size_t kReceiverSize = 36;
/// Most antenna pattern bytes a Transmitter PDU may carry: what its 16-bit length field
/// leaves after the fixed part and the longest modulation parameters.
inline constexpr std::size_t kMaxAntennaPattern = 65535 - kTransmitterSize - 255;
/// Most data bytes a Signal PDU may carry (65535 bits, rounded up to whole bytes).
inline constexpr std::size_t kMaxSignalData = 8192;

/// Any PDU this reader decodes (decodePdu).
using Pdu = std::variant<EntityStatePdu, TransmitterPdu, SignalPdu, ReceiverPdu, FirePdu,
                         DetonationPdu, CollisionPdu, RemoveEntityPdu>;

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

/// The Transmitter PDU in `bytes` (one datagram), or nothing and `error` (when not null)
/// says why: too short for the header (see decodeHeader), another PDU type, a length
/// short of 104 bytes plus the modulation parameter and antenna pattern lengths the PDU
/// gives, a location, power or bandwidth that is not finite. Never reads outside `bytes`;
/// allocates at most the bytes the datagram holds (IEEE 1278.1 clause 7.7.2).
std::optional<TransmitterPdu> decodeTransmitter(std::span<const std::uint8_t> bytes,
                                                std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.7.2): header type 25, family 4, length set to
/// what is written; at most 255 modulation parameter bytes and kMaxAntennaPattern
/// antenna pattern bytes (longer ones are cut); no Variable Transmitter Parameters.
std::vector<std::uint8_t> encodeTransmitter(const TransmitterPdu& pdu);

/// The Signal PDU in `bytes` (one datagram), or nothing and `error` (when not null) says
/// why: too short for the header, another PDU type, a length short of 32 bytes plus the
/// ceil(dataLength / 8) data bytes its dataLength field announces. The padding after the
/// data may be absent. Never reads outside `bytes`; allocates at most the data bytes the
/// datagram holds (IEEE 1278.1 clause 7.7.3).
std::optional<SignalPdu> decodeSignal(std::span<const std::uint8_t> bytes, std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.7.3): header type 26, family 4; the data cut
/// to kMaxSignalData bytes and to ceil(dataLength / 8) bytes, the dataLength written cut
/// to the data's bits (8 x data.size()), the data padded with zeros to a 32-bit boundary.
std::vector<std::uint8_t> encodeSignal(const SignalPdu& pdu);

/// The Receiver PDU in `bytes` (one datagram), or nothing and `error` (when not null) says
/// why: too short for the header, another PDU type, a length short of 36 bytes, a received
/// power that is not finite. Never reads outside `bytes` (IEEE 1278.1 clause 7.7.4).
std::optional<ReceiverPdu> decodeReceiver(std::span<const std::uint8_t> bytes, std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.7.4): header type 27, family 4, 36 bytes.
std::vector<std::uint8_t> encodeReceiver(const ReceiverPdu& pdu);

/// The Fire PDU in `bytes` (one datagram), or nothing and `error` (when not null) says
/// why: too short for the header (see decodeHeader), another PDU type, a length short of
/// 96 bytes, a location, velocity or range that is not finite. Never reads outside `bytes`
/// (IEEE 1278.1 clause 7.3.2).
std::optional<FirePdu> decodeFire(std::span<const std::uint8_t> bytes, std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.3.2): header type 2, family 2, 96 bytes.
std::vector<std::uint8_t> encodeFire(const FirePdu& pdu);

/// The Detonation PDU in `bytes` (one datagram), or nothing and `error` (when not null)
/// says why: too short for the header, another PDU type, a length short of 104 + 16 x its
/// variable parameter records, a number that is not finite. Never reads outside `bytes`;
/// allocates at most the records the datagram holds (IEEE 1278.1 clause 7.3.3).
std::optional<DetonationPdu> decodeDetonation(std::span<const std::uint8_t> bytes,
                                              std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.3.3): header type 3, family 2, at most
/// kMaxArticulationParameters records.
std::vector<std::uint8_t> encodeDetonation(const DetonationPdu& pdu);

/// The Collision PDU in `bytes` (one datagram), or nothing and `error` (when not null)
/// says why: too short for the header, another PDU type, a length short of 60 bytes, a
/// number that is not finite. Never reads outside `bytes` (IEEE 1278.1 clause 7.2.3).
std::optional<CollisionPdu> decodeCollision(std::span<const std::uint8_t> bytes,
                                            std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.2.3): header type 4, family 1, 60 bytes.
std::vector<std::uint8_t> encodeCollision(const CollisionPdu& pdu);

/// The Remove Entity PDU in `bytes` (one datagram), or nothing and `error` (when not null)
/// says why: too short for the header, another PDU type, a length short of 28 bytes. Never
/// reads outside `bytes` (IEEE 1278.1 clause 7.5.3).
std::optional<RemoveEntityPdu> decodeRemoveEntity(std::span<const std::uint8_t> bytes,
                                                  std::string* error);

/// The bytes of `pdu` (IEEE 1278.1 clause 7.5.3): header type 12, family 5, 28 bytes.
std::vector<std::uint8_t> encodeRemoveEntity(const RemoveEntityPdu& pdu);

/// The PDU in `bytes` (one datagram) by its header's type: an Entity State, Transmitter,
/// Signal, Receiver, Fire, Detonation, Collision or Remove Entity PDU, decoded as the
/// functions above do;
/// nothing, and `error` (when not null) says why, for a PDU that does not decode or of a
/// type not listed (Service Request, Data, ... are not read).
std::optional<Pdu> decodePdu(std::span<const std::uint8_t> bytes, std::string* error);

/// The rotation (axis and angle, radians) of DIS Euler angles (psi about z, then theta
/// about the new y, then phi about the new x: IEEE 1278.1 annex B, the body's x forward,
/// y right, z down), as a quaternion (x, y, z, w).
glm::dquat eulerToQuaternion(const glm::vec3& psiThetaPhi);
/// The inverse of eulerToQuaternion: the DIS Euler angles (psi, theta, phi; radians, psi
/// and phi in [-pi, pi], theta in [-pi/2, pi/2]) of rotation `q` (any length but 0).
glm::vec3 quaternionToEuler(const glm::dquat& q);

}  // namespace gs::dis
