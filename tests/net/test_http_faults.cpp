// net::Transfer against a server that misbehaves on purpose: every failure ends the
// transfer with a message naming the URL, delivers exactly a prefix of the body, and
// never hangs.
#include "http/fault_server.hpp"
#include "transfer_test_util.hpp"

#include <catch2/catch.hpp>

using gs::net::FetchBudget;
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
  r.stallTimeout = 1.0;
  return r;
}

}  // namespace

TEST_CASE("faults: a well-behaved server", "[net][http][faults]") {
  const std::string body = noiseBytes(100000, 2);
  FaultServer server(body, Behaviour::serve);
  REQUIRE(server.ok());
  auto r = fetch(request(server.url()));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.status.httpStatus == 200);
  CHECK(r.status.expected == 100000);

  FetchRequest q = request(server.url());
  q.offset = 99000;
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(99000));
  CHECK(r.status.httpStatus == 206);
  CHECK(r.status.resourceSize == 100000);
  const auto seen = server.requests();
  REQUIRE(seen.size() == 2);
  CHECK(seen[0].path == "/data.bin");
  CHECK(seen[0].range.empty());
  CHECK(seen[1].range == "bytes=99000-");
}

TEST_CASE("faults: a server that ignores ranges", "[net][http][faults]") {
  const std::string body = noiseBytes(80000, 3);
  FaultServer server(body, Behaviour::ignoreRanges);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.offset = 30000;
  auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(30000));
  CHECK(r.status.rangeIgnored);
  CHECK(r.status.httpStatus == 200);
  CHECK(r.status.expected == 50000);
  CHECK(r.status.resourceSize == 80000);

  q.length = 1234;  // stops once the range is delivered, though the server sends on
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(30000, 1234));
  CHECK(r.status.rangeIgnored);
  CHECK(r.status.expected == 1234);
  REQUIRE(server.requests().size() == 2);
  CHECK(server.requests()[1].range == "bytes=30000-31233");
}

TEST_CASE("faults: a connection reset midway fails after the bytes that came",
          "[net][http][faults]") {
  const std::string body = noiseBytes(50000, 4);
  FaultServer server(body, Behaviour::resetMidway, 12000);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.maxResumes = 0;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.bytes == body.substr(0, 12000));
  CHECK(r.status.received == 12000);
  CHECK(r.status.resumes == 0);
  CHECK_THAT(r.status.error,
             Catch::StartsWith(q.url + ": connection reset after 12000 of 50000 bytes"));
  CHECK(server.requests().size() == 1);
}

TEST_CASE("faults: resets are resumed maxResumes times", "[net][http][faults]") {
  const std::string body = noiseBytes(50000, 5);
  FaultServer server(body, Behaviour::resetMidway, 10000);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.maxResumes = 2;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.bytes == body.substr(0, 30000));
  CHECK(r.status.resumes == 2);
  CHECK_THAT(r.status.error, Catch::StartsWith(q.url + ": connection reset after 30000 of 50000") &&
                                 Catch::EndsWith("(resumed 2 times)"));
  const auto seen = server.requests();
  REQUIRE(seen.size() == 3);
  CHECK(seen[0].range.empty());
  CHECK(seen[1].range == "bytes=10000-");
  CHECK(seen[2].range == "bytes=20000-");
}

TEST_CASE("faults: a reset transfer resumes and completes", "[net][http][faults]") {
  const std::string body = noiseBytes(70000, 6);
  FaultServer server(body, Behaviour::resetOnceThenServe, 25000);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url()));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.status.resumes == 1);
  CHECK(r.status.httpStatus == 206);
  CHECK(r.status.expected == 70000);
  const auto seen = server.requests();
  REQUIRE(seen.size() == 2);
  CHECK(seen[1].range == "bytes=25000-");
}

TEST_CASE("faults: a resumed range request keeps its end", "[net][http][faults]") {
  const std::string body = noiseBytes(70000, 7);
  FaultServer server(body, Behaviour::resetOnceThenServe, 3000);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.offset = 10000;
  q.length = 20000;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(10000, 20000));
  CHECK(r.status.resumes == 1);
  const auto seen = server.requests();
  REQUIRE(seen.size() == 2);
  CHECK(seen[0].range == "bytes=10000-29999");
  CHECK(seen[1].range == "bytes=13000-29999");
}

TEST_CASE("faults: a stalled server fails after stallTimeout", "[net][http][faults]") {
  const std::string body = noiseBytes(40000, 8);
  FaultServer server(body, Behaviour::stall, 5000);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url()));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.bytes == body.substr(0, 5000));
  CHECK(r.status.error == server.url() + ": stalled: no data for 1 s after 5000 of 40000 bytes");
  CHECK(r.seconds >= 0.9);
  CHECK(r.status.resumes == 0);  // a stall is not resumed
}

TEST_CASE("faults: 404 and 500 name the URL and the status", "[net][http][faults]") {
  {
    FaultServer server("x", Behaviour::notFound);
    REQUIRE(server.ok());
    const auto r = fetch(request(server.url("/a.wrl")));
    REQUIRE(r.status.state == TransferState::failed);
    CHECK(r.status.error == server.url("/a.wrl") + ": HTTP 404 Not Found");
    CHECK(r.status.httpStatus == 404);
    CHECK(r.bytes.empty());
  }
  FaultServer server("x", Behaviour::serverError);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url("/b.qnv")));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == server.url("/b.qnv") + ": HTTP 500 Internal Server Error");
  CHECK(r.status.httpStatus == 500);
  CHECK(r.bytes.empty());
}

TEST_CASE("faults: a body shorter than its Content-Length fails", "[net][http][faults]") {
  const std::string body = noiseBytes(30000, 9);
  FaultServer server(body, Behaviour::wrongLengthShort);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url()));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.bytes == body);
  // One resume is tried (a 200 again: the known bytes are dropped, nothing new comes).
  CHECK(r.status.resumes == 1);
  CHECK(r.status.rangeIgnored);
  CHECK(r.status.error ==
        server.url() + ": connection closed after 30000 of 30100 bytes (resumed 1 time)");
  REQUIRE(server.requests().size() == 2);
  CHECK(server.requests()[1].range == "bytes=30000-");
}

TEST_CASE("faults: redirects are followed to http only", "[net][http][faults]") {
  const std::string body = noiseBytes(20000, 10);
  {
    FaultServer server(body, Behaviour::redirect);
    REQUIRE(server.ok());
    const auto r = fetch(request(server.url("/start.wrl")));
    REQUIRE(r.status.state == TransferState::done);
    CHECK(r.bytes == body);
    CHECK(r.status.effectiveUrl == server.url("/target"));
    CHECK(r.status.httpStatus == 200);
    const auto seen = server.requests();
    REQUIRE(seen.size() == 2);
    CHECK(seen[0].path == "/start.wrl");
    CHECK(seen[1].path == "/target");

    FetchRequest q = request(server.url("/start.wrl"));
    q.maxRedirects = 0;
    const auto r0 = fetch(q);
    REQUIRE(r0.status.state == TransferState::failed);
    CHECK_THAT(r0.status.error, Catch::StartsWith(q.url + ": "));
    CHECK(r0.bytes.empty());
  }
  FaultServer server(body, Behaviour::redirectToFile);
  REQUIRE(server.ok());
  const auto r = fetch(request(server.url("/start.wrl")));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::StartsWith(server.url("/start.wrl") + ": "));
  CHECK_THAT(r.status.error, Catch::Contains("file"));
  CHECK(r.bytes.empty());
}

TEST_CASE("faults: maxBytes stops an HTTP transfer", "[net][http][faults]") {
  const std::string body = noiseBytes(200000, 12);
  FaultServer server(body, Behaviour::serve);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.maxBytes = 50000;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == q.url + ": larger than the limit of 50000 bytes");
  CHECK(r.bytes.size() <= 50000);
  CHECK(r.bytes == body.substr(0, r.bytes.size()));
}

TEST_CASE("faults: a budget refuses HTTP requests past its limits", "[net][http][budget]") {
  const std::string body = noiseBytes(60000, 13);
  FaultServer server(body, Behaviour::serve);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.budget = std::make_shared<FetchBudget>(100000, 3);
  auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error ==
        q.url + ": refused: more than the limit of 100000 bytes per session were fetched");
  CHECK(r.bytes == body.substr(0, r.bytes.size()));
  CHECK(r.bytes.size() < 60000);
  r = fetch(q);  // third request: allowed, but the bytes are spent
  REQUIRE(r.status.state == TransferState::failed);
  r = fetch(q);  // fourth: refused before any connection
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == q.url + ": refused: the limit of 3 requests per session was reached");
  CHECK(server.requests().size() == 3);
}

TEST_CASE("faults: cancel() ends a stalled HTTP transfer promptly", "[net][http][faults]") {
  FaultServer server(noiseBytes(40000, 14), Behaviour::stall, 1000);
  REQUIRE(server.ok());
  FetchRequest q = request(server.url());
  q.stallTimeout = 30.0;
  auto t = gs::net::startTransfer(q);
  std::string out;
  const auto start = std::chrono::steady_clock::now();
  while (out.size() < 1000 && std::chrono::steady_clock::now() - start < std::chrono::seconds(10)) {
    t->wait(0.1);
    t->take(out);
  }
  REQUIRE(out.size() == 1000);
  const auto before = std::chrono::steady_clock::now();
  t->cancel();
  CHECK(t->status().state == TransferState::cancelled);
  t.reset();  // joins the worker thread
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  CHECK(took < 2.0);
}

TEST_CASE("faults: nothing listening fails fast naming the URL", "[net][http][faults]") {
  std::string url;
  {
    FaultServer gone("", Behaviour::serve);
    url = gone.url("/x.wrl");
  }  // closed: the port refuses connections now
  const auto r = fetch(request(url));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::StartsWith(url + ": cannot connect: "));
  CHECK(r.seconds < 5.0);
}
