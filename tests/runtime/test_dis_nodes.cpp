// X3D DIS (X3D 4.0 clause 28) in the execution model: an EspduTransform in networkReader
// mode takes the Entity State PDUs of its entity sent to its UDP port on the loopback; the
// TransmitterPdu, SignalPdu and ReceiverPdu nodes the radio PDUs of their radio; a
// DISEntityManager makes an EspduTransform for each new entity.
#include "dis_test_port.hpp"
#include "runtime_fixture.hpp"

#include "dis/pdu.hpp"
#include "dis/udp_socket.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using gs::test::disTestPort;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;

TEST_CASE("DIS: an EspduTransform follows the Entity State PDUs of its entity",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(0);
  RunningWorld w(
      x3dWorld("DEF E EspduTransform { networkMode \"networkReader\" readInterval 0.001\n"
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

namespace {

std::size_t disEventCount(const std::vector<std::string>& events, const std::string& prefix) {
  return static_cast<std::size_t>(std::count_if(
      events.begin(), events.end(), [&](const std::string& e) { return e.starts_with(prefix); }));
}

}  // namespace

TEST_CASE("DIS: radio PDU nodes follow the Transmitter, Signal and Receiver PDUs of their radio",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(1);
  const std::string ids = " port " + std::to_string(port) +
                          " siteID 1 applicationID 2 entityID 3 radioID 4"
                          " networkMode \"networkReader\" readInterval 0.001 }\n";
  RunningWorld w(x3dWorld("DEF T TransmitterPdu {" + ids + "DEF S SignalPdu {" + ids +
                          "DEF R ReceiverPdu {" + ids +
                          "DEF E EspduTransform { networkMode \"networkReader\" readInterval 0.001"
                          " port " +
                          std::to_string(port) + " siteID 1 applicationID 2 entityID 3 }\n"),
                 0.0);
  w.model->advanceTo(0.1);  // opens the socket
  gs::dis::TransmitterPdu t;
  t.radio = {{1, 2, 3}, 4};
  t.radioEntityType = {7, 1, 225, 2, 1, 300};
  t.transmitState = 2;
  t.inputSource = 3;
  t.antennaLocation = {100, 200, 300};
  t.relativeAntennaLocation = {1, 2, 3};
  t.antennaPatternType = 1;
  t.frequency = 5'000'000'000ull;
  t.transmitFrequencyBandwidth = 25000.0f;
  t.power = 40.5f;
  t.modulationType = {3, 2, 1, 4};
  t.cryptoSystem = 5;
  t.cryptoKeyID = 6;
  t.modulationParameters = {1, 2, 3};
  t.antennaPattern = {4, 5};
  gs::dis::TransmitterPdu otherRadio = t;  // the same entity's radio 5, sent after
  otherRadio.radio.radio = 5;
  otherRadio.power = -1.0f;
  gs::dis::SignalPdu s;
  s.radio = {{1, 2, 3}, 4};
  s.encodingScheme = 0x4001;
  s.tdlType = 7;
  s.sampleRate = 8000;
  s.samples = 5;
  s.dataLength = 37;
  s.data = {10, 20, 30, 40, 250};
  gs::dis::ReceiverPdu r;
  r.radio = {{1, 2, 3}, 4};
  r.receiverState = 2;
  r.receivedPower = -60.5f;
  r.transmitter = {{5, 6, 7}, 8};
  using gs::dis::UdpReceiver;
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeTransmitter(t)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeTransmitter(otherRadio)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeSignal(s)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeReceiver(r)));
  w.model->advanceTo(0.2);

  const gs::vrml::Node& tn = w.node("T");
  CHECK(tn.get<FieldType::SFBool>("isNetworkReader", false));
  CHECK(tn.get<FieldType::SFBool>("isActive", false));
  CHECK(tn.get<FieldType::SFTime>("timestamp", 0.0) == Approx(0.2));
  CHECK(tn.get<FieldType::SFFloat>("power", 0.0f) == 40.5f);        // radio 4's, not radio 5's
  CHECK(tn.get<FieldType::SFInt32>("frequency", 0) == 2147483647);  // 5 GHz, clamped
  CHECK(tn.get<FieldType::SFVec3f>("antennaLocation", glm::vec3(0.0f)) == glm::vec3(100, 200, 300));
  CHECK(tn.get<FieldType::SFVec3f>("relativeAntennaLocation", glm::vec3(0.0f)) ==
        glm::vec3(1, 2, 3));
  CHECK(tn.get<FieldType::SFInt32>("antennaPatternType", 0) == 1);
  CHECK(tn.get<FieldType::SFInt32>("antennaPatternLength", 0) == 2);
  CHECK(tn.get<FieldType::SFInt32>("lengthOfModulationParameters", 0) == 3);
  CHECK(tn.get<FieldType::SFInt32>("transmitState", 0) == 2);
  CHECK(tn.get<FieldType::SFInt32>("inputSource", 0) == 3);
  CHECK(tn.get<FieldType::SFInt32>("radioEntityTypeKind", 0) == 7);
  CHECK(tn.get<FieldType::SFInt32>("radioEntityTypeCountry", 0) == 225);
  CHECK(tn.get<FieldType::SFInt32>("radioEntityTypeNomenclature", 0) == 300);
  CHECK(tn.get<FieldType::SFInt32>("radioEntityTypeNomenclatureVersion", 0) == 1);
  CHECK(tn.get<FieldType::SFInt32>("modulationTypeSpreadSpectrum", 0) == 3);
  CHECK(tn.get<FieldType::SFInt32>("modulationTypeMajor", 0) == 2);
  CHECK(tn.get<FieldType::SFInt32>("modulationTypeDetail", 0) == 1);
  CHECK(tn.get<FieldType::SFInt32>("modulationTypeSystem", 0) == 4);
  CHECK(tn.get<FieldType::SFInt32>("cryptoSystem", 0) == 5);
  CHECK(tn.get<FieldType::SFInt32>("cryptoKeyID", 0) == 6);
  CHECK(tn.get<FieldType::SFFloat>("transmitFrequencyBandwidth", 0.0f) == 25000.0f);

  const gs::vrml::Node& sn = w.node("S");
  CHECK(sn.get<FieldType::SFBool>("isActive", false));
  CHECK(sn.get<FieldType::MFInt32>("data", std::vector<std::int32_t>{}) ==
        std::vector<std::int32_t>{10, 20, 30, 40, 250});
  CHECK(sn.get<FieldType::SFInt32>("dataLength", 0) == 37);
  CHECK(sn.get<FieldType::SFInt32>("encodingScheme", 0) == 0x4001);
  CHECK(sn.get<FieldType::SFInt32>("tdlType", 0) == 7);
  CHECK(sn.get<FieldType::SFInt32>("sampleRate", 0) == 8000);
  CHECK(sn.get<FieldType::SFInt32>("samples", 0) == 5);

  const gs::vrml::Node& rn = w.node("R");
  CHECK(rn.get<FieldType::SFBool>("isActive", false));
  CHECK(rn.get<FieldType::SFFloat>("receivedPower", 0.0f) == -60.5f);
  CHECK(rn.get<FieldType::SFInt32>("receiverState", 0) == 2);
  CHECK(rn.get<FieldType::SFInt32>("transmitterSiteID", 0) == 5);
  CHECK(rn.get<FieldType::SFInt32>("transmitterApplicationID", 0) == 6);
  CHECK(rn.get<FieldType::SFInt32>("transmitterEntityID", 0) == 7);
  CHECK(rn.get<FieldType::SFInt32>("transmitterRadioID", 0) == 8);

  // The EspduTransform of the same entity on the same port reads no radio PDU.
  CHECK_FALSE(w.node("E").get<FieldType::SFBool>("isActive", false));
}

TEST_CASE("DIS: a PDU arriving between two reads is sent at the next read", "[runtime][x3d][dis]") {
  const int port = disTestPort(2);
  RunningWorld w(x3dWorld("DEF R ReceiverPdu { networkMode \"networkReader\" readInterval 1"
                          " port " +
                          std::to_string(port) + " siteID 1 applicationID 2 entityID 3 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  gs::dis::ReceiverPdu r;
  r.radio = {{1, 2, 3}, 0};
  r.receivedPower = -10.0f;
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeReceiver(r)));
  w.model->advanceTo(0.2);  // the first read
  const gs::vrml::Node& rn = w.node("R");
  CHECK(rn.get<FieldType::SFFloat>("receivedPower", 0.0f) == -10.0f);
  r.receivedPower = -20.0f;
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeReceiver(r)));
  w.model->advanceTo(0.3);  // arrives, waits: readInterval 1
  CHECK(rn.get<FieldType::SFFloat>("receivedPower", 0.0f) == -10.0f);
  w.model->advanceTo(0.7);  // nothing more arrives
  CHECK(rn.get<FieldType::SFFloat>("receivedPower", 0.0f) == -10.0f);
  w.model->advanceTo(1.3);
  CHECK(rn.get<FieldType::SFFloat>("receivedPower", 0.0f) == -20.0f);
  CHECK(rn.get<FieldType::SFTime>("timestamp", 0.0) == Approx(1.3));
}

TEST_CASE("DIS: a DISEntityManager makes an EspduTransform for each new entity",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(3);
  RunningWorld w(
      x3dWorld("DEF M DISEntityManager { port " + std::to_string(port) +
               " siteID 1 children [\n"
               "  DISEntityTypeMapping { kind 1 url \"generic.x3d\" }\n"
               "  DISEntityTypeMapping { kind 1 domain 2 country 225 url \"usTank.x3d\" }\n"
               "  DISEntityTypeMapping { kind 1 domain 2 country 222 url \"other.x3d\" }\n"
               "] }\n"
               "DEF G Group { }\n"
               "ROUTE M.addedEntities TO G.addChildren\n"),
      0.0);
  w.model->advanceTo(0.1);  // opens the socket
  gs::dis::EntityStatePdu tank;
  tank.entityID = {1, 2, 3};
  tank.entityType = {1, 2, 225, 1, 2, 3, 0};
  tank.location = {10, 20, 30};
  tank.marking = "TANK1";
  gs::dis::EntityStatePdu foreign = tank;  // another site: not this manager's
  foreign.entityID = {9, 2, 3};
  using gs::dis::UdpReceiver;
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(tank)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(foreign)));
  w.model->advanceTo(0.2);
  const gs::vrml::Node& m = w.node("M");
  const std::vector<gs::vrml::NodePtr> added = m.mfnode("addedEntities");
  REQUIRE(added.size() == 1);
  const gs::vrml::Node& t = *added[0];
  CHECK(t.typeName() == "EspduTransform");
  CHECK(t.get<FieldType::SFString>("networkMode", std::string()) == "networkReader");
  CHECK(t.get<FieldType::SFInt32>("port", 0) == port);
  CHECK(t.get<FieldType::SFInt32>("siteID", 0) == 1);
  CHECK(t.get<FieldType::SFInt32>("applicationID", 0) == 2);
  CHECK(t.get<FieldType::SFInt32>("entityID", 0) == 3);
  // It reads its entity's PDUs at once: the PDU that made it placed it.
  CHECK(t.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)) == glm::vec3(10, 20, 30));
  CHECK(t.get<FieldType::SFString>("marking", std::string()) == "TANK1");
  // Its model: an Inline of the mapping matching kind, domain and country.
  REQUIRE(t.mfnode("children").size() == 1);
  const gs::vrml::Node& model = *t.mfnode("children")[0];
  CHECK(model.typeName() == "Inline");
  CHECK(model.get<FieldType::MFString>("url", std::vector<std::string>{}) ==
        std::vector<std::string>{"usTank.x3d"});
  // addedEntities routed to a Group's addChildren puts it in the scene.
  REQUIRE(w.node("G").mfnode("children").size() == 1);
  CHECK(w.node("G").mfnode("children")[0] == added[0]);
  CHECK(disEventCount(w.take(), "M.addedEntities") == 1);

  // The same entity again is no new entity; another one matches the generic mapping.
  gs::dis::EntityStatePdu truck = tank;
  truck.entityID = {1, 2, 4};
  truck.entityType = {1, 3, 225, 0, 0, 0, 0};
  tank.location = {11, 21, 31};
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(tank)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(truck)));
  w.model->advanceTo(0.4);
  CHECK(disEventCount(w.take(), "M.addedEntities") == 1);
  REQUIRE(m.mfnode("addedEntities").size() == 1);
  const gs::vrml::NodePtr truckNode = m.mfnode("addedEntities")[0];
  CHECK(truckNode->get<FieldType::SFInt32>("entityID", 0) == 4);
  REQUIRE(truckNode->mfnode("children").size() == 1);
  CHECK(truckNode->mfnode("children")[0]->get<FieldType::MFString>(
            "url", std::vector<std::string>{}) == std::vector<std::string>{"generic.x3d"});
  CHECK(t.get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)) == glm::vec3(11, 21, 31));
}

TEST_CASE("DIS: a DISEntityManager removes silent and deactivated entities",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(4);
  RunningWorld w(x3dWorld("DEF M DISEntityManager { port " + std::to_string(port) + " }\n"), 0.0);
  w.model->advanceTo(0.1);
  gs::dis::EntityStatePdu a;
  a.entityID = {1, 2, 3};
  gs::dis::EntityStatePdu b = a;
  b.entityID = {1, 2, 4};
  using gs::dis::UdpReceiver;
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(a)));
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(b)));
  w.model->advanceTo(0.2);
  const gs::vrml::Node& m = w.node("M");
  REQUIRE(m.mfnode("addedEntities").size() == 2);
  const gs::vrml::NodePtr nodeA = m.mfnode("addedEntities")[0];
  const gs::vrml::NodePtr nodeB = m.mfnode("addedEntities")[1];
  CHECK(nodeA->get<FieldType::SFInt32>("entityID", 0) == 3);
  CHECK(nodeA->mfnode("children").empty());  // no mapping: no model
  // A keeps sending; B falls silent for more than 12 s.
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(a)));
  w.model->advanceTo(10.0);
  w.take();
  w.model->advanceTo(12.0);  // B silent 11.8 s: kept
  CHECK(disEventCount(w.take(), "M.removedEntities") == 0);
  w.model->advanceTo(12.5);
  CHECK(disEventCount(w.take(), "M.removedEntities") == 1);
  REQUIRE(m.mfnode("removedEntities").size() == 1);
  CHECK(m.mfnode("removedEntities")[0] == nodeB);
  // A says it is deactivated (appearance bit 23): removed at once.
  a.appearance = 1u << 23;
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(a)));
  w.model->advanceTo(12.6);
  CHECK(disEventCount(w.take(), "M.removedEntities") == 1);
  REQUIRE(m.mfnode("removedEntities").size() == 1);
  CHECK(m.mfnode("removedEntities")[0] == nodeA);
  // B back: a new entity, a new EspduTransform.
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(b)));
  w.model->advanceTo(12.7);
  REQUIRE(m.mfnode("addedEntities").size() == 1);
  CHECK(m.mfnode("addedEntities")[0] != nodeB);
}

TEST_CASE("DIS: a networkWriter EspduTransform sends its Entity State every writeInterval",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(5);
  gs::dis::UdpReceiver listener;  // what another simulation would hear
  std::string error;
  REQUIRE(listener.open(port, "localhost", error));
  RunningWorld w(x3dWorld("DEF W EspduTransform { networkMode \"networkWriter\" writeInterval 0.5\n"
                          "  port " +
                          std::to_string(port) +
                          " siteID 4 applicationID 5 entityID 6 forceID 2\n"
                          "  entityKind 1 entityDomain 2 entityCountry 225 marking \"WRITER\"\n"
                          "  translation 1 2 3 rotation 0 0 1 0.5 linearVelocity 0 0 7\n"
                          "  articulationParameterCount 1 articulationParameterArray 0.25\n"
                          "  articulationParameterDesignatorArray 0\n"
                          "  articulationParameterChangeIndicatorArray 1\n"
                          "  articulationParameterIdPartAttachedToArray 0\n"
                          "  articulationParameterTypeArray 4096 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  const gs::vrml::Node& writer = w.node("W");
  CHECK(writer.get<FieldType::SFBool>("isNetworkWriter", false));
  CHECK_FALSE(writer.get<FieldType::SFBool>("isStandAlone", true));
  CHECK(writer.get<FieldType::SFBool>("isActive", false));
  std::vector<std::vector<std::uint8_t>> got = listener.receive(16);
  REQUIRE(got.size() == 1);
  const auto pdu = gs::dis::decodeEntityState(got[0], nullptr);
  REQUIRE(pdu);
  CHECK(pdu->entityID == gs::dis::EntityID{4, 5, 6});
  CHECK(pdu->forceID == 2);
  CHECK(pdu->entityType.kind == 1);
  CHECK(pdu->entityType.country == 225);
  CHECK(pdu->marking == "WRITER");
  CHECK(pdu->location == glm::dvec3(1, 2, 3));
  CHECK(pdu->orientation.x == Approx(0.5f));  // psi: about z
  CHECK(pdu->orientation.y == Approx(0.0f).margin(1e-6));
  CHECK(pdu->linearVelocity == glm::vec3(0, 0, 7));
  REQUIRE(pdu->articulationParameters.size() == 1);
  CHECK(pdu->articulationParameters[0].parameterType == 4096);
  CHECK(pdu->articulationParameters[0].value == Approx(0.25));
  // The next PDU half a second later, with the field's new value; none between.
  w.send("W", "set_translation",
         gs::vrml::FieldValue::make<FieldType::SFVec3f>(glm::vec3(8, 0, 0)));
  w.model->advanceTo(0.4);
  CHECK(listener.receive(16).empty());
  w.model->advanceTo(0.6);
  got = listener.receive(16);
  REQUIRE(got.size() == 1);
  CHECK(gs::dis::decodeEntityState(got[0], nullptr)->location == glm::dvec3(8, 0, 0));
}

TEST_CASE("DIS: Euler angles and rotations convert both ways", "[runtime][dis]") {
  for (const glm::vec3 e : {glm::vec3(0.3f, -0.4f, 1.2f), glm::vec3(-2.5f, 1.0f, -0.1f)}) {
    const glm::vec3 back = gs::dis::quaternionToEuler(gs::dis::eulerToQuaternion(e));
    CHECK(back.x == Approx(e.x).margin(1e-5));
    CHECK(back.y == Approx(e.y).margin(1e-5));
    CHECK(back.z == Approx(e.z).margin(1e-5));
  }
}

TEST_CASE("DIS: radio PDU nodes as networkWriters send their Transmitter, Signal, Receiver PDUs",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(6);
  gs::dis::UdpReceiver listener;
  std::string error;
  REQUIRE(listener.open(port, "localhost", error));
  const std::string common = " networkMode \"networkWriter\" writeInterval 0.001 port " +
                             std::to_string(port) +
                             " siteID 1 applicationID 2 entityID 3 radioID 4";
  RunningWorld w(x3dWorld("TransmitterPdu {" + common +
                          " frequency 30000000 power 10 transmitState 2\n"
                          "  antennaLocation 5 6 7 radioEntityTypeCountry 225 }\n"
                          "SignalPdu {" +
                          common +
                          " sampleRate 8000 data [ 1 2 3 ] dataLength 20 }\n"
                          "ReceiverPdu {" +
                          common + " receiverState 2 receivedPower -50 transmitterEntityID 9 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  const auto datagrams = listener.receive(16);
  REQUIRE(datagrams.size() == 3);
  const gs::dis::RadioID radio{{1, 2, 3}, 4};
  const auto t = gs::dis::decodeTransmitter(datagrams[0], nullptr);
  REQUIRE(t);
  CHECK(t->radio == radio);
  CHECK(t->frequency == 30000000u);
  CHECK(t->power == 10.0f);
  CHECK(t->transmitState == 2);
  CHECK(t->antennaLocation == glm::dvec3(5, 6, 7));
  CHECK(t->radioEntityType.country == 225);
  const auto s = gs::dis::decodeSignal(datagrams[1], nullptr);
  REQUIRE(s);
  CHECK(s->radio == radio);
  CHECK(s->sampleRate == 8000u);
  CHECK(s->dataLength == 20);  // 20 of the 24 bits given
  CHECK(s->data == std::vector<std::uint8_t>{1, 2, 3});
  const auto r = gs::dis::decodeReceiver(datagrams[2], nullptr);
  REQUIRE(r);
  CHECK(r->radio == radio);
  CHECK(r->receiverState == 2);
  CHECK(r->receivedPower == -50.0f);
  CHECK(r->transmitter.entity.entity == 9);
}

TEST_CASE("DIS: readInterval 0 reads nothing, writeInterval 0 writes nothing",
          "[runtime][x3d][dis]") {
  // X3D 4.0 clause 28.4.3's field descriptions: "0 means no reading", "no writing".
  const int port = disTestPort(7);
  gs::dis::UdpReceiver listener;
  std::string error;
  REQUIRE(listener.open(port + 1, "localhost", error));
  RunningWorld w(x3dWorld("DEF R EspduTransform { networkMode \"networkReader\" readInterval 0"
                          " port " +
                          std::to_string(port) +
                          " entityID 3 }\n"
                          "DEF W EspduTransform { networkMode \"networkWriter\" writeInterval 0"
                          " port " +
                          std::to_string(port + 1) + " entityID 4 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  gs::dis::EntityStatePdu pdu;
  pdu.entityID = {0, 0, 3};
  pdu.location = {10, 20, 30};
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(pdu)));
  w.model->advanceTo(0.5);
  CHECK(w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1)) == glm::vec3(0.0f));
  CHECK_FALSE(w.node("R").get<FieldType::SFBool>("isActive", true));
  CHECK(listener.receive(16).empty());
}

TEST_CASE("DIS: an EspduTransform dead-reckons its entity between PDUs", "[runtime][x3d][dis]") {
  // IEEE 1278.1 annex E: algorithm 5 (FVW) moves P + V dt + A dt^2 / 2 in world axes;
  // algorithm 3 (RPW) moves P + V dt and turns by the angular velocity.
  const int port = disTestPort(8);
  RunningWorld w(x3dWorld("DEF A EspduTransform { networkMode \"networkReader\" readInterval 0.001"
                          " port " +
                          std::to_string(port) +
                          " entityID 1 }\n"
                          "DEF B EspduTransform { networkMode \"networkReader\" readInterval 0.001"
                          " port " +
                          std::to_string(port) + " entityID 2 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  gs::dis::EntityStatePdu a;
  a.entityID = {0, 0, 1};
  a.deadReckoningAlgorithm = 5;
  a.linearVelocity = {1, 0, 0};
  a.linearAcceleration = {0, 2, 0};
  gs::dis::EntityStatePdu b;
  b.entityID = {0, 0, 2};
  b.deadReckoningAlgorithm = 3;
  b.location = {0, 0, 5};
  b.angularVelocity = {0, 0, 1};
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(a)));
  REQUIRE(gs::dis::UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(b)));
  w.model->advanceTo(0.2);  // read at 0.2
  w.model->advanceTo(1.2);  // one second later, no PDU since
  const glm::vec3 at = w.node("A").get<FieldType::SFVec3f>("translation", glm::vec3(-1));
  CHECK(at.x == Approx(1.0f));
  CHECK(at.y == Approx(1.0f));
  CHECK(w.node("B").get<FieldType::SFVec3f>("translation", glm::vec3(-1)) == glm::vec3(0, 0, 5));
  const gs::vrml::Rotation r =
      w.node("B").get<FieldType::SFRotation>("rotation", gs::vrml::Rotation(0.0f));
  CHECK(r.z == Approx(1.0f));
  CHECK(r.w == Approx(1.0f));  // one radian about z
}
