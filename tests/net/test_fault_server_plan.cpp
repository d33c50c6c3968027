// The fault server as the soak test runs it (gs_fault_server): files of a folder, a plan
// of faults, one per connection in turn, and a paced drip. net::Transfer resumes the
// faults it may resume and fails, naming why, on those it may not.
#include "http/fault_server.hpp"
#include "test_support.hpp"
#include "transfer_test_util.hpp"

#include <catch2/catch.hpp>

using gs::net::FetchRequest;
using gs::net::TransferState;
using gs::test::fetch;
using gs::test::noiseBytes;
using Behaviour = gs::test::FaultServer::Behaviour;
using FaultServer = gs::test::FaultServer;

namespace {

FetchRequest request(const std::string& url) {
  FetchRequest r;
  r.url = url;
  r.connectTimeout = 2.0;
  r.stallTimeout = 2.0;
  return r;
}

}  // namespace

TEST_CASE("fault plan: a reset, a short stall and a truncated body are resumed",
          "[net][http][faults]") {
  gs::test::TempDir dir("faultplan");
  const std::string body = noiseBytes(90000, 21);
  dir.write("a.qnv", body);
  FaultServer::Config config;
  config.root = dir.path.string();
  config.plan = {Behaviour::resetMidway, Behaviour::stall, Behaviour::truncate, Behaviour::serve};
  config.stallSeconds = 0.05;  // then closed: shorter than the client's stall timeout
  config.cutAfter = 20000;
  config.bytesPerSecond = 4e6;  // paced in pieces of 200000 / s: the bytes stay the same
  FaultServer server(config);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url("/a.qnv?soak=1"));
  q.maxResumes = 3;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.status.resumes == 3);
  const auto seen = server.requests();
  REQUIRE(seen.size() == 4);
  CHECK(seen[0].range.empty());
  CHECK(seen[1].range == "bytes=20000-");
  CHECK(seen[2].range == "bytes=40000-");
  CHECK(seen[3].range == "bytes=60000-");
}

TEST_CASE("fault plan: a wrong Content-Range fails the transfer", "[net][http][faults]") {
  gs::test::TempDir dir("faultplan");
  const std::string body = noiseBytes(30000, 22);
  dir.write("b.bin", body);
  FaultServer::Config config;
  config.root = dir.path.string();
  config.plan = {Behaviour::resetMidway, Behaviour::wrongContentRange};
  config.cutAfter = 5000;
  FaultServer server(config);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url("/b.bin")));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.bytes == body.substr(0, 5000));
  CHECK_THAT(r.status.error, Catch::Contains("bytes from 10000"));
}

TEST_CASE("fault plan: missing files are 404", "[net][http][faults]") {
  gs::test::TempDir dir("faultplan");
  dir.write("c.bin", "c");
  FaultServer::Config config;
  config.root = dir.path.string();
  FaultServer server(config);
  REQUIRE(server.ok());
  // (libcurl removes ".." segments before sending: the server's own refusal of ".." is
  // not reachable from here.)
  for (const char* path : {"/missing.bin", "/sub/c.bin", "/c.bin/", "/"}) {
    INFO(path);
    const auto r = fetch(request(server.url(path)));
    REQUIRE(r.status.state == TransferState::failed);
    CHECK(r.status.httpStatus == 404);
  }
  CHECK(fetch(request(server.url("/c.bin"))).bytes == "c");
}

TEST_CASE("fault plan: behaviours by name", "[net][http][faults]") {
  for (Behaviour b : {Behaviour::serve, Behaviour::resetMidway, Behaviour::truncate,
                      Behaviour::stall, Behaviour::wrongContentRange, Behaviour::redirectToFile}) {
    Behaviour back = Behaviour::notFound;
    REQUIRE(FaultServer::behaviourFromName(FaultServer::behaviourName(b), back));
    CHECK(back == b);
  }
  Behaviour unused;
  CHECK_FALSE(FaultServer::behaviourFromName("explode", unused));
}
