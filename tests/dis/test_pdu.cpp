// DIS PDUs (IEEE 1278.1; dis/pdu.hpp): the Entity State PDU to bytes and back, and what a
// malformed datagram gives (an error, never a read outside it).
#include "dis/pdu.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

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
