// DIS PDUs (IEEE 1278.1; dis/pdu.hpp): the Entity State PDU to bytes and back, and what a
// malformed datagram gives (an error, never a read outside it).
#include "dis/pdu.hpp"
#include "dis/rtp.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <variant>

using namespace gs::dis;

namespace {

EntityStatePdu tank() {
  EntityStatePdu p;
  p.entityID = {1, 2, 3};
  p.forceID = 1;
  p.entityType = {1, 2, 225, 1, 2, 3, 0};
  p.linearVelocity = {1, 2, 3};
  p.location = {1e6, -2.5e6, 6.3e6};
  p.orientation = {0.5f, 0.25f, 0.0f};
  p.marking = "TANK1";
  p.articulationParameters.push_back({0, 0, 0, 4096, 0.75});
  return p;
}

}  // namespace

TEST_CASE("DIS: an Entity State PDU survives encoding and decoding", "[dis]") {
  const std::vector<std::uint8_t> bytes = encodeEntityState(tank());
  REQUIRE(bytes.size() == kEntityStateSize + 16);
  CHECK(bytes[2] == 1);                             // PDU type
  CHECK(((bytes[8] << 8) | bytes[9]) == 144 + 16);  // length, big-endian
  std::string error;
  const std::optional<EntityStatePdu> p = decodeEntityState(bytes, &error);
  REQUIRE(p);
  CHECK(error.empty());
  CHECK(p->entityID == EntityID{1, 2, 3});
  CHECK(p->entityType.country == 225);
  CHECK(p->location == glm::dvec3(1e6, -2.5e6, 6.3e6));
  CHECK(p->linearVelocity == glm::vec3(1, 2, 3));
  CHECK(p->orientation == glm::vec3(0.5f, 0.25f, 0.0f));
  CHECK(p->marking == "TANK1");
  REQUIRE(p->articulationParameters.size() == 1);
  CHECK(p->articulationParameters[0].value == Approx(0.75));
}

TEST_CASE("DIS: short, lying and foreign datagrams are errors", "[dis]") {
  std::vector<std::uint8_t> bytes = encodeEntityState(tank());
  std::string error;
  // Cut short: the header's length says more than there is.
  CHECK_FALSE(decodeEntityState(std::span(bytes).first(100), &error));
  CHECK(error.find("does not fit") != std::string::npos);
  CHECK_FALSE(decodeEntityState(std::span(bytes).first(5), &error));
  CHECK(error.find("header") != std::string::npos);
  // A length that leaves no room for the articulation parameter it announces.
  std::vector<std::uint8_t> lying = bytes;
  lying[8] = 0;
  lying[9] = 144;
  CHECK_FALSE(decodeEntityState(lying, &error));
  CHECK(error.find("articulation") != std::string::npos);
  // Another PDU type.
  std::vector<std::uint8_t> fire = bytes;
  fire[2] = 2;
  CHECK_FALSE(decodeEntityState(fire, &error));
  CHECK(error.find("type 2") != std::string::npos);
  // A location that is not a number.
  std::vector<std::uint8_t> nan = bytes;
  for (int i = 0; i < 8; ++i) nan[48 + i] = 0xff;
  CHECK_FALSE(decodeEntityState(nan, &error));
}

TEST_CASE("DIS: Euler angles psi, theta, phi turn about z, then y, then x", "[dis]") {
  const glm::dquat q = eulerToQuaternion({glm::half_pi<float>(), 0.0f, 0.0f});
  const glm::dvec3 x = q * glm::dvec3(1, 0, 0);
  CHECK(x.y == Approx(1.0).margin(1e-6));  // heading a quarter turn: x onto y
  const glm::dquat pitch = eulerToQuaternion({0.0f, glm::half_pi<float>(), 0.0f});
  CHECK((pitch * glm::dvec3(1, 0, 0)).z == Approx(-1.0).margin(1e-6));
}

namespace {

TransmitterPdu radioTransmitter() {
  TransmitterPdu p;
  p.header.timestamp = 1234;
  p.radio = {{1, 2, 3}, 4};
  p.radioEntityType = {7, 1, 225, 2, 1, 300};
  p.transmitState = 2;
  p.inputSource = 1;
  p.antennaLocation = {1e6, -2.5e6, 6.3e6};
  p.relativeAntennaLocation = {0.5f, 1.0f, -2.0f};
  p.antennaPatternType = 1;
  p.frequency = 5'000'000'000ull;  // 5 GHz: more than 32 bits
  p.transmitFrequencyBandwidth = 25000.0f;
  p.power = 40.5f;
  p.modulationType = {3, 2, 1, 4};
  p.cryptoSystem = 5;
  p.cryptoKeyID = 0x8001;
  p.modulationParameters = {1, 2, 3, 4, 5, 6, 7, 8};
  p.antennaPattern = {9, 10, 11, 12};
  return p;
}

/// `bytes` with its 16-bit big-endian field at `at` set to `v`.
std::vector<std::uint8_t> withU16(std::vector<std::uint8_t> bytes, std::size_t at,
                                  std::uint16_t v) {
  bytes[at] = static_cast<std::uint8_t>(v >> 8);
  bytes[at + 1] = static_cast<std::uint8_t>(v);
  return bytes;
}

}  // namespace

TEST_CASE("DIS: a Transmitter PDU survives encoding and decoding", "[dis]") {
  const std::vector<std::uint8_t> bytes = encodeTransmitter(radioTransmitter());
  REQUIRE(bytes.size() == kTransmitterSize + 8 + 4);
  CHECK(bytes[2] == 25);  // PDU type
  CHECK(bytes[3] == 4);   // radio communications family
  CHECK(((bytes[8] << 8) | bytes[9]) == 116);
  std::string error;
  const std::optional<TransmitterPdu> p = decodeTransmitter(bytes, &error);
  REQUIRE(p);
  CHECK(error.empty());
  CHECK(p->header.timestamp == 1234);
  CHECK(p->radio == RadioID{{1, 2, 3}, 4});
  CHECK(p->radioEntityType.kind == 7);
  CHECK(p->radioEntityType.country == 225);
  CHECK(p->radioEntityType.nomenclatureVersion == 1);
  CHECK(p->radioEntityType.nomenclature == 300);
  CHECK(p->transmitState == 2);
  CHECK(p->inputSource == 1);
  CHECK(p->antennaLocation == glm::dvec3(1e6, -2.5e6, 6.3e6));
  CHECK(p->relativeAntennaLocation == glm::vec3(0.5f, 1.0f, -2.0f));
  CHECK(p->antennaPatternType == 1);
  CHECK(p->frequency == 5'000'000'000ull);
  CHECK(p->transmitFrequencyBandwidth == 25000.0f);
  CHECK(p->power == 40.5f);
  CHECK(p->modulationType.spreadSpectrum == 3);
  CHECK(p->modulationType.major == 2);
  CHECK(p->modulationType.detail == 1);
  CHECK(p->modulationType.radioSystem == 4);
  CHECK(p->cryptoSystem == 5);
  CHECK(p->cryptoKeyID == 0x8001);
  CHECK(p->modulationParameters == std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8});
  CHECK(p->antennaPattern == std::vector<std::uint8_t>{9, 10, 11, 12});
  // Through the dispatcher too.
  const std::optional<Pdu> any = decodePdu(bytes, &error);
  REQUIRE(any);
  CHECK(std::holds_alternative<TransmitterPdu>(*any));
}

TEST_CASE("DIS: a Transmitter PDU whose lengths overrun the datagram is an error", "[dis]") {
  const std::vector<std::uint8_t> bytes = encodeTransmitter(radioTransmitter());
  std::string error;
  // Every cut of the datagram, header length fixed up to match: never decodes.
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    if (n >= 10) cut = withU16(cut, 8, static_cast<std::uint16_t>(n));
    CHECK_FALSE(decodeTransmitter(cut, &error));
  }
  // Antenna pattern length (offset 70) beyond the PDU.
  CHECK_FALSE(decodeTransmitter(withU16(bytes, 70, 60000), &error));
  CHECK(error.find("short of") != std::string::npos);
  // Modulation parameter length (offset 100) beyond the PDU.
  std::vector<std::uint8_t> lying = bytes;
  lying[100] = 200;
  CHECK_FALSE(decodeTransmitter(lying, &error));
  CHECK(error.find("short of") != std::string::npos);
  // A power that is not a number.
  std::vector<std::uint8_t> nan = bytes;
  for (int i = 0; i < 4; ++i) nan[84 + i] = 0xff;
  CHECK_FALSE(decodeTransmitter(nan, &error));
  CHECK(error.find("finite") != std::string::npos);
  // Another PDU type.
  CHECK_FALSE(decodeTransmitter(encodeEntityState(tank()), &error));
  CHECK(error.find("type 1") != std::string::npos);
}

TEST_CASE("DIS: a Signal PDU survives encoding and decoding", "[dis]") {
  SignalPdu s;
  s.radio = {{1, 2, 3}, 4};
  s.encodingScheme = 0x4001;
  s.tdlType = 7;
  s.sampleRate = 8000;
  s.samples = 5;
  s.dataLength = 37;  // 5 bytes, the last one partly used
  s.data = {10, 20, 30, 40, 50};
  const std::vector<std::uint8_t> bytes = encodeSignal(s);
  REQUIRE(bytes.size() == kSignalSize + 8);  // 5 data bytes padded to 8
  CHECK(bytes[2] == 26);
  std::string error;
  const std::optional<SignalPdu> p = decodeSignal(bytes, &error);
  REQUIRE(p);
  CHECK(p->radio == RadioID{{1, 2, 3}, 4});
  CHECK(p->encodingScheme == 0x4001);
  CHECK(p->tdlType == 7);
  CHECK(p->sampleRate == 8000);
  CHECK(p->samples == 5);
  CHECK(p->dataLength == 37);
  CHECK(p->data == std::vector<std::uint8_t>{10, 20, 30, 40, 50});
  // More data than dataLength announces: cut to what it announces.
  s.dataLength = 16;
  const std::optional<SignalPdu> cut = decodeSignal(encodeSignal(s), &error);
  REQUIRE(cut);
  CHECK(cut->data == std::vector<std::uint8_t>{10, 20});
  const std::optional<Pdu> any = decodePdu(bytes, &error);
  REQUIRE(any);
  CHECK(std::holds_alternative<SignalPdu>(*any));
}

TEST_CASE("DIS: a Signal PDU whose data overruns the datagram is an error", "[dis]") {
  SignalPdu s;
  s.dataLength = 64;
  s.data = {1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<std::uint8_t> bytes = encodeSignal(s);
  std::string error;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    if (n >= 10) cut = withU16(cut, 8, static_cast<std::uint16_t>(n));
    CHECK_FALSE(decodeSignal(cut, &error));
  }
  // dataLength (offset 28) announcing 65535 bits in a 40-byte PDU.
  CHECK_FALSE(decodeSignal(withU16(bytes, 28, 65535), &error));
  CHECK(error.find("8224") != std::string::npos);  // 32 + 8192 bytes needed
}

TEST_CASE("DIS: a Receiver PDU survives encoding and decoding", "[dis]") {
  ReceiverPdu r;
  r.radio = {{1, 2, 3}, 4};
  r.receiverState = 2;
  r.receivedPower = -60.5f;
  r.transmitter = {{5, 6, 7}, 8};
  const std::vector<std::uint8_t> bytes = encodeReceiver(r);
  REQUIRE(bytes.size() == kReceiverSize);
  CHECK(bytes[2] == 27);
  std::string error;
  const std::optional<ReceiverPdu> p = decodeReceiver(bytes, &error);
  REQUIRE(p);
  CHECK(p->radio == RadioID{{1, 2, 3}, 4});
  CHECK(p->receiverState == 2);
  CHECK(p->receivedPower == -60.5f);
  CHECK(p->transmitter == RadioID{{5, 6, 7}, 8});
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    if (n >= 10) cut = withU16(cut, 8, static_cast<std::uint16_t>(n));
    CHECK_FALSE(decodeReceiver(cut, &error));
  }
  std::vector<std::uint8_t> nan = bytes;
  for (int i = 0; i < 4; ++i) nan[24 + i] = 0xff;
  CHECK_FALSE(decodeReceiver(nan, &error));
  const std::optional<Pdu> any = decodePdu(bytes, &error);
  REQUIRE(any);
  CHECK(std::holds_alternative<ReceiverPdu>(*any));
}

TEST_CASE("DIS: decodePdu reads the PDU its header names and no other type", "[dis]") {
  std::string error;
  const std::optional<Pdu> es = decodePdu(encodeEntityState(tank()), &error);
  REQUIRE(es);
  CHECK(std::get<EntityStatePdu>(*es).marking == "TANK1");
  std::vector<std::uint8_t> serviceRequest = encodeEntityState(tank());
  serviceRequest[2] = 5;  // a Service Request PDU: not read
  CHECK_FALSE(decodePdu(serviceRequest, &error));
  CHECK(error.find("not read") != std::string::npos);
  CHECK_FALSE(decodePdu(std::vector<std::uint8_t>{7, 1}, &error));
}

TEST_CASE("DIS: Fire, Detonation and Collision PDUs survive encoding and decoding", "[dis]") {
  std::string error;
  FirePdu fire;
  fire.firingEntityID = {1, 2, 3};
  fire.targetEntityID = {4, 5, 6};
  fire.munitionID = {1, 2, 77};
  fire.eventID = {1, 2, 500};
  fire.fireMissionIndex = 9;
  fire.location = {1e6, -2e6, 3e6};
  fire.descriptor = {{2, 9, 225, 1, 2, 3, 4}, 1000, 2000, 3, 600};
  fire.velocity = {100, 0, -5};
  fire.range = 1500.0f;
  const std::vector<std::uint8_t> fireBytes = encodeFire(fire);
  REQUIRE(fireBytes.size() == kFireSize);
  CHECK(fireBytes[2] == 2);  // PDU type
  CHECK(fireBytes[3] == 2);  // the warfare family
  const std::optional<Pdu> anyFire = decodePdu(fireBytes, &error);
  REQUIRE(anyFire);
  const FirePdu& f = std::get<FirePdu>(*anyFire);
  CHECK(f.targetEntityID == EntityID{4, 5, 6});
  CHECK(f.eventID == EventID{1, 2, 500});
  CHECK(f.location == fire.location);
  CHECK(f.descriptor.munitionType.country == 225);
  CHECK(f.descriptor.rate == 600);
  CHECK(f.velocity == fire.velocity);
  CHECK(f.range == 1500.0f);

  DetonationPdu detonation;
  detonation.firingEntityID = {1, 2, 3};
  detonation.location = {1e6, -2e6, 3e6};
  detonation.locationInEntity = {0.5f, 1, 2};
  detonation.detonationResult = 5;
  detonation.articulationParameters.push_back({1, 0, 0, 4096, 2.5});
  const std::vector<std::uint8_t> detonationBytes = encodeDetonation(detonation);
  REQUIRE(detonationBytes.size() == kDetonationSize + 16);
  const std::optional<DetonationPdu> d = decodeDetonation(detonationBytes, &error);
  REQUIRE(d);
  CHECK(d->locationInEntity == detonation.locationInEntity);
  CHECK(d->detonationResult == 5);
  REQUIRE(d->articulationParameters.size() == 1);
  CHECK(d->articulationParameters[0].value == 2.5);
  // A record announced past the datagram's length.
  std::vector<std::uint8_t> lying = detonationBytes;
  lying[9] = static_cast<std::uint8_t>(kDetonationSize);
  CHECK_FALSE(decodeDetonation(std::span(lying).first(kDetonationSize), &error));
  CHECK(error.find("short of the 120") != std::string::npos);

  CollisionPdu collision;
  collision.issuingEntityID = {1, 2, 3};
  collision.collidingEntityID = {1, 2, 4};
  collision.collisionType = 1;
  collision.mass = 12000.0f;
  const std::vector<std::uint8_t> collisionBytes = encodeCollision(collision);
  REQUIRE(collisionBytes.size() == kCollisionSize);
  const std::optional<CollisionPdu> c = decodeCollision(collisionBytes, &error);
  REQUIRE(c);
  CHECK(c->collidingEntityID == EntityID{1, 2, 4});
  CHECK(c->mass == 12000.0f);
  // Every cut of each PDU is an error, never a read past it.
  for (const std::vector<std::uint8_t>* bytes : {&fireBytes, &detonationBytes, &collisionBytes})
    for (std::size_t n = 0; n < bytes->size(); ++n) {
      std::vector<std::uint8_t> cut(bytes->begin(), bytes->begin() + static_cast<long>(n));
      if (n >= 10) {
        cut[8] = static_cast<std::uint8_t>(n >> 8);
        cut[9] = static_cast<std::uint8_t>(n);
      }
      CHECK_FALSE(decodePdu(cut, &error));
    }
  // A number that is not finite.
  std::vector<std::uint8_t> nan = collisionBytes;
  for (int i = 0; i < 4; ++i) nan[44 + i] = 0xff;  // the mass
  CHECK_FALSE(decodeCollision(nan, &error));
  CHECK(error.find("not finite") != std::string::npos);
}

TEST_CASE("DIS: a Remove Entity PDU survives encoding and decoding; every cut is an error",
          "[dis]") {
  RemoveEntityPdu remove;
  remove.originatingID = {9, 8, 7};
  remove.receivingID = {1, 2, 3};
  remove.requestID = 0xDEADBEEF;
  const std::vector<std::uint8_t> bytes = encodeRemoveEntity(remove);
  REQUIRE(bytes.size() == kRemoveEntitySize);
  CHECK(bytes[2] == 12);  // PDU type
  CHECK(bytes[3] == 5);   // the simulation management family
  std::string error;
  const std::optional<Pdu> any = decodePdu(bytes, &error);
  REQUIRE(any);
  const RemoveEntityPdu& r = std::get<RemoveEntityPdu>(*any);
  CHECK(r.originatingID == EntityID{9, 8, 7});
  CHECK(r.receivingID == EntityID{1, 2, 3});
  CHECK(r.requestID == 0xDEADBEEF);
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
    if (n >= 10) {
      cut[8] = 0;
      cut[9] = static_cast<std::uint8_t>(n);
    }
    CHECK_FALSE(decodePdu(cut, &error));
  }
  CHECK(error.find("short of the 28") != std::string::npos);
}

TEST_CASE("DIS: an RTP header is told from a PDU and taken off, CSRCs, extension, padding",
          "[dis]") {
  const std::vector<std::uint8_t> pdu = encodeEntityState(tank());
  CHECK_FALSE(startsWithRtpHeader(pdu));  // version 7 in the first byte
  CHECK(withoutRtpHeader(pdu).size() == pdu.size());
  std::vector<std::uint8_t> d = rtpHeader(0x0102, 0x03040506, 0x0708090A, 96);
  REQUIRE(d.size() == 12);
  CHECK(d == std::vector<std::uint8_t>{0x80, 96, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10});
  d.insert(d.end(), pdu.begin(), pdu.end());
  std::span<const std::uint8_t> payload = withoutRtpHeader(d);
  REQUIRE(payload.size() == pdu.size());
  CHECK(decodeEntityState(payload, nullptr)->marking == "TANK1");
  // Two CSRCs, an extension of one word, four bytes of padding.
  std::vector<std::uint8_t> full{0x80 | 0x20 | 0x10 | 2, 96, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0};
  full.resize(full.size() + 8, 0xAA);                       // the CSRCs
  full.insert(full.end(), {0xBE, 0xDE, 0, 1, 1, 2, 3, 4});  // extension, one word
  full.insert(full.end(), pdu.begin(), pdu.end());
  full.insert(full.end(), {0, 0, 0, 4});
  payload = withoutRtpHeader(full);
  REQUIRE(payload.size() == pdu.size());
  CHECK(std::equal(payload.begin(), payload.end(), pdu.begin()));
  // Headers that run past the datagram give nothing.
  for (std::size_t n = 1; n < 12 + 8 + 8; ++n)
    CHECK(withoutRtpHeader(std::span(full).first(n)).empty());
  std::vector<std::uint8_t> overPadded = full;
  overPadded.back() = 255;
  CHECK(withoutRtpHeader(overPadded).empty());
  overPadded.back() = 0;
  CHECK(withoutRtpHeader(overPadded).empty());
}
