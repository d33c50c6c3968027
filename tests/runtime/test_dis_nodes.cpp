// X3D DIS (X3D 4.0 clause 28) in the execution model: an EspduTransform in networkReader
// mode takes the Entity State PDUs of its entity sent to its UDP port on the loopback.
#include "runtime_fixture.hpp"

#include "dis/pdu.hpp"
#include "dis/udp_socket.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;

TEST_CASE("DIS: an EspduTransform follows the Entity State PDUs of its entity",
          "[runtime][x3d][dis]") {
  const int port = 20000 + static_cast<int>(::getpid() % 20000);
  RunningWorld w(x3dWorld("DEF E EspduTransform { networkMode \"networkReader\" readInterval 0\n"
                          "  port " +
                          std::to_string(port) +
                          " siteID 1 applicationID 2 entityID 3\n"
                          "  children Shape { geometry Box { } } }\n"),
                 0.0);
  w.model->advanceTo(0.1);  // opens the socket
  const gs::vrml::Node& e = w.node("E");
  CHECK(e.get<FieldType::SFBool>("isNetworkReader", false));
  gs::dis::EntityStatePdu other;
  other.entityID = {1, 2, 4};
  other.location = {9, 9, 9};
  gs::dis::EntityStatePdu mine;
  mine.entityID = {1, 2, 3};
  mine.location = {10, 20, 30};
  mine.orientation = {1.5707963f, 0.0f, 0.0f};
  mine.marking = "TANK1";
  mine.articulationParameters.push_back({0, 0, 0, 4096, 0.75});
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(mine)));
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(other)));
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, {1, 2, 3}));  // not a PDU
  w.model->advanceTo(0.2);
  CHECK(e.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)) == glm::vec3(10, 20, 30));
  const gs::vrml::Rotation r = e.get<FieldType::SFRotation>("rotation", gs::vrml::Rotation(0.0f));
  CHECK(r.z == Approx(1.0f));
  CHECK(r.w == Approx(1.5707963f));
  CHECK(e.get<FieldType::SFString>("marking", std::string()) == "TANK1");
  CHECK(e.get<FieldType::SFBool>("isActive", false));
  CHECK(e.get<FieldType::SFInt32>("articulationParameterCount", 0) == 1);
  CHECK(e.get<FieldType::SFTime>("timestamp", 0.0) == Approx(0.2));
  bool warned = false;
  for (const auto& d : w.scene->diagnostics.items)
    warned = warned || d.message.find("dropped") != std::string::npos;
  for (const auto& d : w.model->diagnostics().items)
    warned = warned || d.message.find("dropped") != std::string::npos;
  CHECK(warned);
}

TEST_CASE("DIS: a standAlone EspduTransform opens no socket and says so", "[runtime][x3d][dis]") {
  RunningWorld w(x3dWorld("DEF E EspduTransform { translation 1 2 3 }\n"), 0.0);
  w.model->advanceTo(0.1);
  const gs::vrml::Node& e = w.node("E");
  CHECK(e.get<FieldType::SFBool>("isStandAlone", false));
  CHECK_FALSE(e.get<FieldType::SFBool>("isNetworkReader", true));
  CHECK(e.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)) == glm::vec3(1, 2, 3));
}
