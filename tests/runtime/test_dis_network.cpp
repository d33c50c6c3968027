// X3D DIS (X3D 4.0 clause 28) on the network: a multicast `address` joined as a group, PDUs
// behind RTP headers (rtpHeaderExpected) read and written, and the Remove Entity PDU
// (IEEE 1278.1 clause 7.5.3) removing a DISEntityManager's entity.
#include "dis_test_port.hpp"
#include "runtime_fixture.hpp"

#include "dis/pdu.hpp"
#include "dis/rtp.hpp"
#include "dis/udp_socket.hpp"

#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>

using gs::test::disTestPort;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;

namespace {

/// A multicast group of the organisation-local scope (RFC 2365) for this process.
std::string testGroup() {
  return "239.255.77." + std::to_string(1 + ::getpid() % 250);
}

std::vector<std::uint8_t> withRtp(std::uint16_t sequence, const std::vector<std::uint8_t>& pdu) {
  std::vector<std::uint8_t> d = gs::dis::rtpHeader(sequence, 1234, 99);
  d.insert(d.end(), pdu.begin(), pdu.end());
  return d;
}

}  // namespace

TEST_CASE("DIS: a Remove Entity PDU removes a DISEntityManager's entity", "[runtime][x3d][dis]") {
  const int port = disTestPort(40 + 1);
  RunningWorld w(x3dWorld("DEF M DISEntityManager { port " + std::to_string(port) + " }\n"), 0.0);
  w.model->advanceTo(0.1);
  gs::dis::EntityStatePdu a;
  a.entityID = {1, 2, 3};
  using gs::dis::UdpReceiver;
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeEntityState(a)));
  w.model->advanceTo(0.2);
  const gs::vrml::Node& m = w.node("M");
  REQUIRE(m.mfnode("addedEntities").size() == 1);
  const gs::vrml::NodePtr added = m.mfnode("addedEntities")[0];
  w.take();
  // Another entity's removal changes nothing; its own removes it at once.
  gs::dis::RemoveEntityPdu remove;
  remove.originatingID = {9, 9, 9};
  remove.receivingID = {1, 2, 4};
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeRemoveEntity(remove)));
  w.model->advanceTo(0.3);
  const auto none = w.take();
  CHECK(std::none_of(none.begin(), none.end(),
                     [](const std::string& e) { return e.starts_with("M.removedEntities"); }));
  remove.receivingID = {1, 2, 3};
  REQUIRE(UdpReceiver::sendToLoopback(port, gs::dis::encodeRemoveEntity(remove)));
  w.model->advanceTo(0.4);
  REQUIRE(m.mfnode("removedEntities").size() == 1);
  CHECK(m.mfnode("removedEntities")[0] == added);
  CHECK_FALSE(added->get<FieldType::SFBool>("enabled", true));
}

TEST_CASE("DIS: a reader on a multicast group hears PDUs, bare or behind RTP headers",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(40 + 2);
  const std::string group = testGroup();
  RunningWorld w(x3dWorld("DEF E EspduTransform { networkMode \"networkReader\" readInterval 0.001"
                          " address \"" +
                          group + "\" port " + std::to_string(port) +
                          " siteID 1 applicationID 2 entityID 3 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  for (const auto& d : w.model->diagnostics().items) FAIL_CHECK(d.message);  // joined
  gs::dis::EntityStatePdu p;
  p.entityID = {1, 2, 3};
  p.location = {5, 6, 7};
  std::string error;
  REQUIRE(gs::dis::UdpReceiver::sendTo(group, port, gs::dis::encodeEntityState(p), error));
  w.model->advanceTo(0.2);
  CHECK(w.node("E").get<FieldType::SFVec3f>("translation", glm::vec3(0)) == glm::vec3(5, 6, 7));
  // The same entity behind an RTP header (rtpHeaderExpected is the writer's: a reader
  // tells an RTP header from a PDU by its first byte).
  p.location = {8, 9, 10};
  REQUIRE(
      gs::dis::UdpReceiver::sendTo(group, port, withRtp(1, gs::dis::encodeEntityState(p)), error));
  w.model->advanceTo(0.3);
  CHECK(w.node("E").get<FieldType::SFVec3f>("translation", glm::vec3(0)) == glm::vec3(8, 9, 10));
}

TEST_CASE("DIS: a writer with rtpHeaderExpected puts a numbered RTP header before each PDU",
          "[runtime][x3d][dis]") {
  const int port = disTestPort(40 + 3);
  const std::string group = testGroup();
  gs::dis::UdpReceiver listener;  // another simulation, a member of the group
  std::string error;
  REQUIRE(listener.open(port, group, error));
  RunningWorld w(x3dWorld("DEF W EspduTransform { networkMode \"networkWriter\" writeInterval 0.5"
                          " rtpHeaderExpected TRUE address \"" +
                          group + "\" port " + std::to_string(port) +
                          " siteID 4 applicationID 5 entityID 6 translation 1 2 3 }\n"),
                 0.0);
  w.model->advanceTo(0.1);
  w.model->advanceTo(0.7);
  const std::vector<std::vector<std::uint8_t>> got = listener.receive(16);
  REQUIRE(got.size() == 2);
  for (std::size_t i = 0; i < got.size(); ++i) {
    REQUIRE(got[i].size() == 12 + 144);
    CHECK(got[i][0] == 0x80);  // RTP version 2, nothing more
    CHECK(got[i][1] == 96);    // the first dynamic payload type
    CHECK(got[i][3] == i);     // numbered from 0
    CHECK(got[i][8] == 0);     // SSRC: site 4, application 5
    CHECK(got[i][9] == 4);
    CHECK(got[i][11] == 5);
    const auto pdu = gs::dis::decodeEntityState(gs::dis::withoutRtpHeader(got[i]), nullptr);
    REQUIRE(pdu);
    CHECK(pdu->entityID == gs::dis::EntityID{4, 5, 6});
    CHECK(pdu->location == glm::dvec3(1, 2, 3));
  }
}
