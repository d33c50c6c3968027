// X3D DIS (X3D 4.0 clause 28.4.3): an EspduTransform reader's events of the Fire,
// Detonation and Collision PDUs of its entity, and its geoCoords from the Entity State
// PDU's geocentric location.
#include "dis_test_port.hpp"
#include "runtime_fixture.hpp"

#include "dis/pdu.hpp"
#include "dis/udp_socket.hpp"

#include <catch2/catch.hpp>

using gs::test::disTestPort;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;

namespace {

/// An EspduTransform reader of entity 1 2 3 on `port`, DEF E, with `extra` fields.
std::string warfareReader(int port, const std::string& extra) {
  return "DEF E EspduTransform { networkMode \"networkReader\" readInterval 0.001 port " +
         std::to_string(port) + " siteID 1 applicationID 2 entityID 3 " + extra + " }\n";
}

}  // namespace

TEST_CASE("DIS: an EspduTransform sends the Fire, Detonation and Collision PDUs of its entity",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(20 + 1);
  RunningWorld w(x3dWorld(warfareReader(port, "")), 0.0);
  w.model->advanceTo(0.1);  // opens the socket
  const gs::vrml::Node& e = w.node("E");
  CHECK_FALSE(e.get<FieldType::SFBool>("fired1", true));
  gs::dis::FirePdu fire;
  fire.firingEntityID = {1, 2, 3};
  fire.munitionID = {1, 2, 77};
  fire.eventID = {1, 2, 500};
  fire.fireMissionIndex = 9;
  fire.location = {10, 20, 30};
  fire.descriptor.warhead = 1000;
  fire.descriptor.fuse = 2000;
  fire.descriptor.quantity = 3;
  fire.descriptor.rate = 600;
  fire.range = 1500.0f;
  gs::dis::FirePdu othersFire = fire;  // another entity's: not this node's
  othersFire.firingEntityID = {1, 2, 4};
  othersFire.fireMissionIndex = 1;
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeFire(fire)));
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeFire(othersFire)));
  w.model->advanceTo(0.2);
  CHECK(e.get<FieldType::SFBool>("fired1", false));
  CHECK(e.get<FieldType::SFTime>("firedTime", 0.0) == Approx(0.2));
  CHECK(e.get<FieldType::SFVec3f>("munitionStartPoint", glm::vec3(0)) == glm::vec3(10, 20, 30));
  CHECK(e.get<FieldType::SFInt32>("munitionEntityID", 0) == 77);
  CHECK(e.get<FieldType::SFInt32>("eventNumber", 0) == 500);
  CHECK(e.get<FieldType::SFInt32>("fireMissionIndex", 0) == 9);
  CHECK(e.get<FieldType::SFInt32>("warhead", 0) == 1000);
  CHECK(e.get<FieldType::SFInt32>("fuse", 0) == 2000);
  CHECK(e.get<FieldType::SFInt32>("munitionQuantity", 0) == 3);
  CHECK(e.get<FieldType::SFInt32>("firingRate", 0) == 600);
  CHECK(e.get<FieldType::SFFloat>("firingRange", 0.0f) == 1500.0f);
  CHECK_FALSE(e.get<FieldType::SFBool>("isDetonated", true));

  gs::dis::DetonationPdu detonation;
  detonation.firingEntityID = {1, 2, 3};
  detonation.munitionID = {1, 2, 77};
  detonation.eventID = {1, 2, 500};
  detonation.location = {110, 20, 30};
  detonation.locationInEntity = {0.5f, 0, 0};
  detonation.detonationResult = 5;
  gs::dis::CollisionPdu collision;
  collision.issuingEntityID = {1, 2, 3};
  collision.collidingEntityID = {1, 2, 4};
  collision.eventID = {1, 2, 501};
  collision.collisionType = 1;
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeDetonation(detonation)));
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeCollision(collision)));
  w.model->advanceTo(0.3);
  CHECK(e.get<FieldType::SFBool>("isDetonated", false));
  CHECK(e.get<FieldType::SFTime>("detonateTime", 0.0) == Approx(0.3));
  CHECK(e.get<FieldType::SFVec3f>("munitionEndPoint", glm::vec3(0)) == glm::vec3(110, 20, 30));
  CHECK(e.get<FieldType::SFVec3f>("detonationLocation", glm::vec3(0)) == glm::vec3(110, 20, 30));
  CHECK(e.get<FieldType::SFVec3f>("detonationRelativeLocation", glm::vec3(0)) ==
        glm::vec3(0.5f, 0, 0));
  CHECK(e.get<FieldType::SFInt32>("detonationResult", 0) == 5);
  CHECK(e.get<FieldType::SFBool>("isCollided", false));
  CHECK(e.get<FieldType::SFTime>("collideTime", 0.0) == Approx(0.3));
  CHECK(e.get<FieldType::SFInt32>("collisionType", 0) == 1);
  CHECK(e.get<FieldType::SFInt32>("eventNumber", 0) == 501);  // the collision's, sent last
  // The fire was sent once: its time stays that of its frame.
  CHECK(e.get<FieldType::SFTime>("firedTime", 0.0) == Approx(0.2));
}

TEST_CASE("DIS: an EspduTransform's geoCoords are its entity's location in its geoSystem",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(20 + 2);
  // Two readers of the same entity: the default GD WE, and GC.
  std::string geocentricReader = warfareReader(port, "geoSystem \"GC\"");
  geocentricReader.replace(0, 5, "DEF C");
  RunningWorld w(x3dWorld(warfareReader(port, "") + geocentricReader), 0.0);
  w.model->advanceTo(0.1);
  gs::dis::EntityStatePdu p;
  p.entityID = {1, 2, 3};
  // On the equator at longitude 90 degrees east, 100 m above the WGS84 ellipsoid.
  p.location = {0.0, 6378137.0 + 100.0, 0.0};
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(p)));
  w.model->advanceTo(0.2);
  const glm::dvec3 gd = w.node("E").get<FieldType::SFVec3d>("geoCoords", glm::dvec3(-1));
  CHECK(gd.x == Approx(0.0).margin(1e-9));  // latitude, degrees
  CHECK(gd.y == Approx(90.0));              // longitude, degrees
  CHECK(gd.z == Approx(100.0).margin(1e-6));
  const glm::dvec3 gc = w.node("C").get<FieldType::SFVec3d>("geoCoords", glm::dvec3(-1));
  CHECK(gc == p.location);
}

TEST_CASE("DIS: a networkWriter EspduTransform sends a Fire PDU when fired1 turns TRUE",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(20 + 3);
  gs::dis::UdpReceiver listener;
  std::string error;
  REQUIRE(listener.open(port, "localhost", error));
  RunningWorld w(x3dWorld("DEF W EspduTransform { networkMode \"networkWriter\" writeInterval 10"
                          " port " +
                          std::to_string(port) +
                          " siteID 4 applicationID 5 entityID 6 munitionEntityID 77"
                          " eventNumber 9 munitionStartPoint 1 2 3 warhead 1000 fuse 2000"
                          " munitionQuantity 2 firingRate 600 firingRange 1500 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  auto kinds = [&]() {
    std::vector<int> types;
    for (const auto& d : listener.receive(16)) types.push_back(d.size() > 2 ? d[2] : -1);
    return types;
  };
  CHECK(kinds() == std::vector<int>{1});  // the Entity State PDU, and no Fire PDU
  w.send("W", "set_fired1", gs::vrml::FieldValue::make<FieldType::SFBool>(true));
  w.model->advanceTo(0.2);
  std::vector<std::vector<std::uint8_t>> got = listener.receive(16);
  REQUIRE(got.size() == 1);  // at once, not at the next writeInterval
  const auto fire = gs::dis::decodeFire(got[0], nullptr);
  REQUIRE(fire);
  CHECK(fire->firingEntityID == gs::dis::EntityID{4, 5, 6});
  CHECK(fire->munitionID.entity == 77);
  CHECK(fire->eventID.eventNumber == 9);
  CHECK(fire->location == glm::dvec3(1, 2, 3));
  CHECK(fire->descriptor.warhead == 1000);
  CHECK(fire->descriptor.rate == 600);
  CHECK(fire->range == 1500.0f);
  CHECK(w.node("W").get<FieldType::SFTime>("firedTime", 0.0) == Approx(0.2));
  // Still TRUE: no second PDU; FALSE then TRUE again: one more.
  w.model->advanceTo(0.3);
  CHECK(kinds().empty());
  w.send("W", "set_fired1", gs::vrml::FieldValue::make<FieldType::SFBool>(false));
  w.model->advanceTo(0.4);
  w.send("W", "set_fired1", gs::vrml::FieldValue::make<FieldType::SFBool>(true));
  w.model->advanceTo(0.5);
  CHECK(kinds() == std::vector<int>{2});
}
