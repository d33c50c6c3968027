// net::Transfer against a real HTTP server (nginx): whole files, ranges, gzip
// Content-Encoding, errors.
#include "http/nginx_server.hpp"
#include "transfer_test_util.hpp"

#include <catch2/catch.hpp>

using gs::net::FetchRequest;
using gs::net::TransferState;
using gs::test::fetch;
using gs::test::NginxServer;
using gs::test::noiseBytes;
using gs::test::vrmlText;

namespace {

FetchRequest request(const std::string& url) {
  FetchRequest r;
  r.url = url;
  r.connectTimeout = 2.0;
  r.stallTimeout = 5.0;
  return r;
}

}  // namespace

TEST_CASE("nginx: a whole .wrl file", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string body = vrmlText(300000);
  server.writeFile("worlds/a.wrl", body);
  const auto r = fetch(request(server.url("/worlds/a.wrl")));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.status.error.empty());
  CHECK(r.bytes == body);
  CHECK(r.status.httpStatus == 200);
  CHECK(r.status.received == body.size());
  CHECK(r.status.expected == static_cast<std::int64_t>(body.size()));
  CHECK(r.status.resourceSize == static_cast<std::int64_t>(body.size()));
  CHECK_FALSE(r.status.rangeIgnored);
  CHECK(r.status.resumes == 0);
  CHECK(r.status.effectiveUrl == server.url("/worlds/a.wrl"));
  CHECK(r.status.bytesPerSecond > 0.0);
  const auto log = server.accessLog(1);
  REQUIRE(log.size() == 1);
  CHECK(log[0] == "GET /worlds/a.wrl 200 " + std::to_string(body.size()) + " \"-\" \"-\"");
}

TEST_CASE("nginx: a .qnv range arrives exactly", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string body = noiseBytes(500000, 11);
  server.writeFile("m.qnv", body);
  FetchRequest q = request(server.url("/m.qnv"));
  q.offset = 123456;
  q.length = 1000;
  auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(123456, 1000));
  CHECK(r.status.httpStatus == 206);
  CHECK(r.status.expected == 1000);
  CHECK(r.status.resourceSize == 500000);
  CHECK_FALSE(r.status.rangeIgnored);

  q.length = 0;  // from the offset to the end
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(123456));
  CHECK(r.status.httpStatus == 206);
  CHECK(r.status.expected == 500000 - 123456);

  q.offset = 0;  // only a length: a range from 0
  q.length = 10;
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(0, 10));
  CHECK(r.status.httpStatus == 206);

  const auto log = server.accessLog(3);
  REQUIRE(log.size() == 3);
  CHECK(log[0] == "GET /m.qnv 206 1000 \"bytes=123456-124455\" \"-\"");
  CHECK(log[1] == "GET /m.qnv 206 " + std::to_string(500000 - 123456) + " \"bytes=123456-\" \"-\"");
  CHECK(log[2] == "GET /m.qnv 206 10 \"bytes=0-9\" \"-\"");
}

TEST_CASE("nginx: a range past the end fails with 416", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  server.writeFile("small.qnv", "0123456789");
  FetchRequest q = request(server.url("/small.qnv"));
  q.offset = 50;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::StartsWith(q.url + ": HTTP 416"));
  CHECK(r.status.httpStatus == 416);
  CHECK(r.bytes.empty());
}

TEST_CASE("nginx: gzip Content-Encoding is decoded", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string body = vrmlText(400000);
  server.writeFile("w.wrl", body);
  const auto r = fetch(request(server.url("/gz/w.wrl")));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.status.httpStatus == 200);
  CHECK(r.status.received == body.size());
  CHECK(r.status.expected == -1);  // the decoded size is unknown in advance
  // nginx did compress: far fewer bytes went over the wire.
  const auto log = server.accessLog(1);
  REQUIRE(log.size() == 1);
  CHECK_THAT(log[0], Catch::StartsWith("GET /gz/w.wrl 200 ") && Catch::EndsWith("\"gzip\""));
  const std::size_t sent = std::stoul(log[0].substr(std::string("GET /gz/w.wrl 200 ").size()));
  CHECK(sent < body.size() / 3);
}

TEST_CASE("nginx: a range is never content-encoded", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string body = vrmlText(100000);
  server.writeFile("w.wrl", body);
  FetchRequest q = request(server.url("/gz/w.wrl"));
  q.offset = 5000;
  q.length = 2000;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(5000, 2000));
  CHECK(r.status.httpStatus == 206);
  const auto log = server.accessLog(1);
  REQUIRE(log.size() == 1);
  CHECK(log[0] == "GET /gz/w.wrl 206 2000 \"bytes=5000-6999\" \"-\"");
}

TEST_CASE("nginx: 404 names the URL and the status", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string url = server.url("/missing.wrl");
  const auto r = fetch(request(url));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == url + ": HTTP 404 Not Found");
  CHECK(r.status.httpStatus == 404);
  CHECK(r.bytes.empty());  // the error page is not delivered
}

TEST_CASE("nginx: maxRate slows an HTTP transfer down", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string body = noiseBytes(60000, 4);
  server.writeFile("slow.bin", body);
  FetchRequest q = request(server.url("/slow.bin"));
  q.maxRate = 30000.0;  // two seconds' worth
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.seconds >= 1.0);
  CHECK(r.deliveries >= 3);
}

TEST_CASE("nginx: many transfers at once", "[net][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  std::vector<std::string> bodies;
  std::vector<std::unique_ptr<gs::net::Transfer>> transfers;
  for (int i = 0; i < 6; ++i) {
    bodies.push_back(
        noiseBytes(50000 + 1000 * static_cast<std::size_t>(i), static_cast<std::uint32_t>(i + 20)));
    server.writeFile("f" + std::to_string(i) + ".bin", bodies.back());
  }
  for (int i = 0; i < 6; ++i)
    transfers.push_back(
        gs::net::startTransfer(request(server.url("/f" + std::to_string(i) + ".bin"))));
  for (std::size_t i = 0; i < transfers.size(); ++i) {
    const auto r = gs::test::drain(*transfers[i]);
    REQUIRE(r.status.state == TransferState::done);
    CHECK(r.bytes == bodies[i]);
  }
}
