// net::Transfer on local files and FetchBudget (mayReference and isHttpUrl: tests/base).
#include "transfer_test_util.hpp"

#include <catch2/catch.hpp>

#include <thread>

using gs::net::FetchBudget;
using gs::net::FetchRequest;
using gs::net::TransferState;
using gs::test::fetch;
using gs::test::noiseBytes;
using gs::test::TempDir;

namespace {

FetchRequest request(const std::string& url) {
  FetchRequest r;
  r.url = url;
  return r;
}

}  // namespace

TEST_CASE("a local file arrives whole, in 64 KiB chunks", "[net][file]") {
  TempDir dir;
  const std::string body = noiseBytes(200000);
  const std::string path = dir.write("big.bin", body);
  const auto r = fetch(request(path));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.status.error.empty());
  CHECK(r.bytes == body);
  CHECK(r.status.received == body.size());
  CHECK(r.status.expected == 200000);
  CHECK(r.status.resourceSize == 200000);
  CHECK(r.status.httpStatus == 0);
  CHECK(r.status.effectiveUrl == path);
}

TEST_CASE("a local file honours offset and length", "[net][file]") {
  TempDir dir;
  const std::string body = noiseBytes(100000, 7);
  const std::string path = dir.write("part.bin", body);
  FetchRequest q = request(path);
  q.offset = 70000;
  q.length = 20000;
  auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(70000, 20000));
  CHECK(r.status.expected == 20000);
  CHECK(r.status.resourceSize == 100000);

  q.length = 0;  // to the end
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body.substr(70000));
  CHECK(r.status.expected == 30000);

  q.offset = 100001;  // past the end
  r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::Contains("offset 100001 is past its end (100000 bytes)"));
}

TEST_CASE("a file:// URL is percent-decoded", "[net][file]") {
  TempDir dir;
  const std::string path = dir.write("a world.wrl", "#VRML V2.0 utf8\n");
  auto r = fetch(request("file://" + dir.path.string() + "/a%20world.wrl"));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == "#VRML V2.0 utf8\n");
  r = fetch(request("FILE://localhost" + dir.path.string() + "/a%20world.wrl"));
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == "#VRML V2.0 utf8\n");
  r = fetch(request("file://elsewhere/etc/hosts"));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::Contains("another host ('elsewhere')"));
}

TEST_CASE("maxRate slows a local file down and delivers it in many chunks", "[net][file]") {
  TempDir dir;
  const std::string body = noiseBytes(16000, 3);
  FetchRequest q = request(dir.write("slow.bin", body));
  q.maxRate = 16000.0;  // one second's worth
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  CHECK(r.seconds >= 0.5);
  CHECK(r.deliveries >= 5);
  CHECK(r.status.bytesPerSecond < 40000.0);
}

TEST_CASE("a missing file fails naming the path and the reason", "[net][file]") {
  TempDir dir;
  const std::string path = (dir.path / "nowhere.wrl").string();
  const auto r = fetch(request(path));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == "cannot open '" + path + "': No such file or directory");
  CHECK(r.bytes.empty());
}

TEST_CASE("local files are refused when allowLocal is false", "[net][file]") {
  TempDir dir;
  const std::string path = dir.write("secret.txt", "secret");
  FetchRequest q = request(path);
  q.allowLocal = false;
  const auto t = gs::net::startTransfer(q);
  const auto s = t->status();  // fails at once, before any thread runs
  REQUIRE(s.state == TransferState::failed);
  CHECK(s.error == "local file '" + path + "' may not be read by content from the network");
  std::string out;
  CHECK(t->take(out) == 0);

  q.url = "file://" + path;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK_THAT(r.status.error, Catch::StartsWith("local file 'file://"));
}

TEST_CASE("other URL schemes fail at once", "[net]") {
  const auto r = fetch(request("ftp://example.org/x.wrl"));
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error ==
        "ftp://example.org/x.wrl: unsupported URL scheme 'ftp' (only http, https and file are "
        "read)");
}

TEST_CASE("maxBytes stops a local file", "[net][file]") {
  TempDir dir;
  FetchRequest q = request(dir.write("big.bin", noiseBytes(300000)));
  q.maxBytes = 100000;
  const auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == q.url + ": larger than the limit of 100000 bytes");
  CHECK(r.bytes.size() <= 100000);
  CHECK(r.bytes == noiseBytes(300000).substr(0, r.bytes.size()));
}

TEST_CASE("cancel() ends a slow local transfer promptly", "[net][file]") {
  TempDir dir;
  FetchRequest q = request(dir.write("slow.bin", noiseBytes(100000)));
  q.maxRate = 1000.0;  // 100 s worth
  const auto t = gs::net::startTransfer(q);
  t->wait(1.0);
  const auto before = std::chrono::steady_clock::now();
  t->cancel();
  CHECK(t->status().state == TransferState::cancelled);
  t->wait(5.0);  // returns at once: finished
  const double waited =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count();
  CHECK(waited < 1.0);
  CHECK(t->status().received < 100000);
}

TEST_CASE("destroying a running transfer cancels and joins it", "[net][file]") {
  TempDir dir;
  FetchRequest q = request(dir.write("slow.bin", noiseBytes(100000)));
  q.maxRate = 1000.0;
  const auto before = std::chrono::steady_clock::now();
  { const auto t = gs::net::startTransfer(q); }
  CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - before).count() < 1.0);
}

TEST_CASE("FetchBudget counts requests and bytes", "[net][budget]") {
  FetchBudget b(1000, 2);
  CHECK(b.startRequest());
  CHECK(b.startRequest());
  CHECK_FALSE(b.startRequest());
  CHECK(b.requests() == 2);
  CHECK(b.addBytes(600));
  CHECK(b.addBytes(400));
  CHECK_FALSE(b.addBytes(1));
  CHECK(b.totalBytes() == 1001);
}

TEST_CASE("FetchBudget is safe from many threads", "[net][budget]") {
  FetchBudget b(1u << 30, 500);
  std::vector<std::thread> threads;
  std::atomic<int> granted{0};
  for (int i = 0; i < 8; ++i)
    threads.emplace_back([&] {
      for (int k = 0; k < 100; ++k)
        if (b.startRequest()) ++granted;
    });
  for (auto& t : threads) t.join();
  CHECK(granted == 500);
  CHECK(b.requests() == 500);
}

TEST_CASE("a budget refuses local transfers past its limits", "[net][budget]") {
  TempDir dir;
  const std::string body = noiseBytes(200000, 5);
  FetchRequest q = request(dir.write("a.bin", body));
  q.budget = std::make_shared<FetchBudget>(300000, 2);
  auto r = fetch(q);
  REQUIRE(r.status.state == TransferState::done);
  CHECK(r.bytes == body);
  r = fetch(q);  // the second request passes 300000 bytes in all
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error ==
        q.url + ": refused: more than the limit of 300000 bytes per session were fetched");
  CHECK(r.bytes == body.substr(0, r.bytes.size()));
  r = fetch(q);  // a third request
  REQUIRE(r.status.state == TransferState::failed);
  CHECK(r.status.error == q.url + ": refused: the limit of 2 requests per session was reached");
  CHECK(r.bytes.empty());
  CHECK(q.budget->requests() == 2);
}
