// net::QnvStream and net::WorldStream (docs/progressive-loading.md): a QNV stream fetches
// with range requests only the prefix of vectors wanted and more when more is wanted; a
// world grows node by node; the Loader's byte cap stops everything.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <thread>

#include "http/fault_server.hpp"
#include "http/nginx_server.hpp"
#include "net/loader.hpp"
#include "qnv/encoder.hpp"
#include "qnv/stream.hpp"
#include "transfer_test_util.hpp"

using gs::test::FaultServer;
using gs::test::NginxServer;
using namespace gs;

namespace {

/// A .qnv of a 40^3 ball: about 40,000 vectors in 48-byte packets (the paper's cell).
std::string ballStream() {
  qnv::Volume v;
  v.dims = {40, 40, 40};
  v.samples.resize(v.voxelCount());
  for (std::uint32_t z = 0; z < 40; ++z)
    for (std::uint32_t y = 0; y < 40; ++y)
      for (std::uint32_t x = 0; x < 40; ++x) {
        const float r = std::sqrt(
            float((x - 20.0) * (x - 20.0) + (y - 20.0) * (y - 20.0) + (z - 20.0) * (z - 20.0)));
        v.samples[x + 40 * (y + 40 * z)] = std::max(0.0f, 255.0f - 10.0f * r);
      }
  qnv::WriteOptions w;
  w.packetBytes = 48;
  return qnv::writeStream(qnv::encodeVolume(v, {}), w);
}

/// Pumps until `stream` settles (or 20 s pass); returns whether it settled.
template <class Stream>
bool settle(Stream& stream, net::Allowance& allowance) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (std::chrono::steady_clock::now() < end) {
    stream.pump(allowance);
    if (stream.progress().settled()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return false;
}

}  // namespace

TEST_CASE("a QNV stream fetches the wanted prefix by ranges, and more when asked",
          "[net][streams][http]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  const std::string bytes = ballStream();
  nginx.writeFile("ball.qnv", bytes);
  std::uint64_t received = 0;  // vectors given to the sink
  net::FetchRequest r;
  r.url = nginx.url("/ball.qnv");
  net::QnvStream stream(
      r, [&](std::uint64_t, std::span<const qnv::DecodedVector> v) { received += v.size(); }, 4096);
  net::Allowance allowance;
  REQUIRE(settle(stream, allowance));
  REQUIRE(stream.header());
  const std::uint64_t total = stream.header()->vectorCount;
  REQUIRE(total > 20000);
  CHECK(stream.progress().state == net::StreamState::idle);
  const std::uint64_t first = stream.progress().bytes;
  CHECK(first == qnv::kHeaderBytes + 4096);

  stream.want(total / 10);
  REQUIRE(settle(stream, allowance));
  CHECK(received >= total / 10);
  // Whole packets, and at least 64 KiB per request (1024 packets of 6 vectors).
  CHECK(received <= std::max<std::uint64_t>(total / 10 + 6, (4096 + 65536) / 64 * 6));
  const std::uint64_t tenth = stream.progress().bytes;
  CHECK(tenth < bytes.size() / 5);

  stream.want(total / 2);
  REQUIRE(settle(stream, allowance));
  CHECK(received >= total / 2);
  CHECK(stream.progress().bytes < bytes.size() * 6 / 10);

  stream.want(total);
  REQUIRE(settle(stream, allowance));
  CHECK(stream.progress().state == net::StreamState::done);
  CHECK(received == total);
  CHECK(stream.progress().bytes == bytes.size());
  // Every request after the first continued where the last ended.
  const auto log = nginx.accessLog(4);
  REQUIRE(log.size() >= 4);
  for (const std::string& line : log) {
    INFO(line);
    CHECK(line.find(" 206 ") != std::string::npos);
  }
  CHECK(log[0].find("\"bytes=0-" + std::to_string(first - 1) + "\"") != std::string::npos);
  CHECK(log[1].find("\"bytes=" + std::to_string(first) + "-") != std::string::npos);
  CHECK(log[2].find("\"bytes=" + std::to_string(tenth) + "-") != std::string::npos);
}

TEST_CASE("a QNV stream from a server that ignores ranges streams to the end",
          "[net][streams][http]") {
  const std::string bytes = ballStream();
  FaultServer server(bytes, FaultServer::Behaviour::ignoreRanges);
  REQUIRE(server.ok());
  std::uint64_t received = 0;
  net::FetchRequest r;
  r.url = server.url("/ball.qnv");
  net::QnvStream stream(
      r, [&](std::uint64_t, std::span<const qnv::DecodedVector> v) { received += v.size(); }, 4096);
  stream.want(10);
  net::Allowance allowance;
  REQUIRE(settle(stream, allowance));
  stream.want(UINT64_MAX);
  REQUIRE(settle(stream, allowance));
  CHECK(stream.progress().state == net::StreamState::done);
  REQUIRE(stream.header());
  CHECK(received == stream.header()->vectorCount);
  CHECK(server.requests().size() <= 3);
}

TEST_CASE("a QNV stream cut mid-way keeps its vectors and says why", "[net][streams][http]") {
  const std::string bytes = ballStream();
  FaultServer server(bytes, FaultServer::Behaviour::stall, bytes.size() / 3);
  REQUIRE(server.ok());
  std::uint64_t received = 0;
  net::FetchRequest r;
  r.url = server.url("/ball.qnv");
  r.stallTimeout = 0.5;
  net::QnvStream stream(
      r, [&](std::uint64_t, std::span<const qnv::DecodedVector> v) { received += v.size(); });
  stream.want(UINT64_MAX);
  net::Allowance allowance;
  REQUIRE(settle(stream, allowance));
  CHECK(stream.progress().state == net::StreamState::failed);
  CHECK(stream.progress().error.find(server.url("/ball.qnv")) != std::string::npos);
  CHECK(received > 0);
  REQUIRE(stream.header());
  CHECK(received < stream.header()->vectorCount / 2);
}

TEST_CASE("the loader's byte cap stops every stream with a valid prefix", "[net][streams]") {
  const std::string world =
      "#VRML V2.0 utf8\nGroup {}\nGroup {}\nGroup { children [ Group {} ] }\nGroup {}\n";
  FaultServer server(world, FaultServer::Behaviour::serve);
  REQUIRE(server.ok());
  net::LoaderOptions o;
  o.stopAfterBytes = world.find("Group { children");  // two nodes, then the cap
  net::Loader loader(o);
  std::string error;
  auto w = loader.world(server.url("/w.wrl"), "", error);
  REQUIRE(w);
  REQUIRE(gs::test::settle(loader));
  CHECK(w->progress().state == net::StreamState::stopped);
  CHECK(w->scene()->rootNodes.size() == 2);
  CHECK(loader.progress().front().error.find("stopped") != std::string::npos);
}

TEST_CASE("the loader refuses local files named by remote content", "[net][streams]") {
  net::Loader loader;
  std::string error;
  CHECK_FALSE(loader.world("/etc/passwd", "http://example.com/a.wrl", error));
  CHECK(error.find("http(s)") != std::string::npos);
  error.clear();
  std::string bytes;
  CHECK_FALSE(
      loader.fetchInBackground("file:///etc/passwd", "http://example.com/a.wrl", bytes, error));
  CHECK_FALSE(error.empty());
  // The same URL twice is one stream.
  auto a = loader.world("/nonexistent/a.wrl", "", error);
  auto b = loader.world("/nonexistent/a.wrl", "", error);
  CHECK(a == b);
  CHECK(loader.progress().size() == 1);
}

TEST_CASE("net::Loader as the session's base::Fetcher: whole, background, the rules",
          "[net][streams][fetch]") {
  const std::string body = "#VRML V2.0 utf8\nPROTO P [] { Group { } }\n";
  FaultServer server(body, FaultServer::Behaviour::serve);
  REQUIRE(server.ok());
  net::Loader loader;
  base::Fetcher& fetcher = loader;
  // Whole: waits for the bytes.
  base::Fetched got = fetcher.fetch(server.url("/p.wrl"), "", base::FetchMode::whole);
  CHECK(got.ready());
  CHECK(got.bytes == body);
  // Background: pending at first, ready after pumps, never waiting in fetch().
  got = fetcher.fetch(server.url("/q.wrl"), "http://h.org/w.wrl", base::FetchMode::background);
  CHECK(got.pending());
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (got.pending() && std::chrono::steady_clock::now() < end) {
    loader.pump();
    loader.wait(0.01);
    got = fetcher.fetch(server.url("/q.wrl"), "http://h.org/w.wrl", base::FetchMode::background);
  }
  CHECK(got.ready());
  CHECK(got.bytes == body);
  // Local files and data: URLs at once, under the rules.
  CHECK(fetcher.fetch("data:,abc", "http://h.org/w.wrl", base::FetchMode::background).bytes ==
        "abc");
  got = fetcher.fetch("/etc/passwd", "http://h.org/w.wrl", base::FetchMode::whole);
  CHECK(got.state == base::FetchState::refused);
  CHECK(got.error.find("may only reference http(s) URLs") != std::string::npos);
}

TEST_CASE("a streamed world's EXTERNPROTO arrives in the background; the world ends after it",
          "[net][streams][proto]") {
  NginxServer server;
  if (!server.ok()) return;
  server.writeFile(
      "lib.wrl", "#VRML V2.0 utf8\nPROTO Ball [ field SFFloat r 1 ] { Sphere { radius IS r } }\n");
  server.writeFile("w.wrl",
                   "#VRML V2.0 utf8\nEXTERNPROTO Ball [ field SFFloat r ] \"lib.wrl\"\n"
                   "Shape { geometry Ball { r 2 } }\nGroup { }\n");
  net::Loader loader;
  std::string error;
  auto w = loader.world(server.url("/w.wrl"), "", error);
  REQUIRE(w);
  REQUIRE(gs::test::settle(loader));
  CHECK(w->progress().state == net::StreamState::done);
  const vrml::Scene& s = *w->scene();
  CHECK(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 2);
  const vrml::NodePtr ball = s.rootNodes[0]->sfnode("geometry");
  REQUIRE(ball);
  CHECK_FALSE(ball->unresolved);
}

TEST_CASE("a hostile packet sequence number does not size the consumer's arrays",
          "[net][streams]") {
  // A valid header claiming 2^32 vectors of 8-record packets, then one good packet placed
  // near the end of that count: its vectors would sit at index ~4 billion.
  qnv::StreamHeader h;
  h.packetBytes = 64;
  h.vectorCount = std::uint64_t{1} << 32;
  h.boundsMax = {1, 1, 1};
  std::string bytes = qnv::serializeHeader(h);
  const std::vector<std::uint64_t> records(8, 0x123456789abcdefull);
  qnv::appendPacket(bytes, 0, records, qnv::PacketEncoding::plain);
  qnv::appendPacket(bytes, 0x1fffffff, records, qnv::PacketEncoding::plain);
  FaultServer server(bytes, FaultServer::Behaviour::serve);
  REQUIRE(server.ok());
  std::uint64_t highest = 0, received = 0;
  net::FetchRequest r;
  r.url = server.url("/evil.qnv");
  net::QnvStream stream(r, [&](std::uint64_t first, std::span<const qnv::DecodedVector> v) {
    highest = std::max<std::uint64_t>(highest, first + v.size());
    received += v.size();
  });
  stream.want(UINT64_MAX);
  net::Allowance allowance;
  REQUIRE(settle(stream, allowance));
  CHECK(received == 8);  // the first packet only
  CHECK(highest == 8);
  CHECK(stream.progress().packetsLost >= 1);
}
