// One URL rule over real HTTP (base/url.hpp, issue 14): an EXTERNPROTO named by an
// absolute path ("/protos/a.wrl") in a world served over HTTP is fetched from that host,
// through the loader's one policy, and `..` segments are removed (RFC 3986 section 5.2).
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>

#include "http/nginx_server.hpp"
#include "net/loader.hpp"
#include "transfer_test_util.hpp"

using gs::test::NginxServer;
using namespace gs;

namespace {

/// Opens `url` in a fresh loader and pumps until everything settled (or 20 s pass).
std::shared_ptr<const vrml::Scene> loadWorld(const std::string& url) {
  net::Loader loader;
  std::string error;
  auto w = loader.world(url, "", error);
  REQUIRE(w);
  REQUIRE(gs::test::settle(loader, 20.0));
  CHECK(w->progress().state == net::StreamState::done);
  return w->scene();
}

}  // namespace

TEST_CASE("an EXTERNPROTO \"/protos/a.wrl\" of an HTTP world loads from that host",
          "[net][url][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  const std::string proto =
      "#VRML V2.0 utf8\nPROTO Red [ field SFFloat size 1 ] {\n"
      "  Shape { geometry Sphere { radius IS size } }\n}\n";
  server.writeFile("protos/a.wrl", proto);
  server.writeFile("worlds/deep/w.wrl",
                   "#VRML V2.0 utf8\n"
                   "EXTERNPROTO Red [ field SFFloat size ] \"/protos/a.wrl\"\n"
                   "EXTERNPROTO Red2 [ field SFFloat size ] [ \"../../protos/./a.wrl#Red\" ]\n"
                   "Red { size 2 }\nRed2 { size 3 }\n");
  const auto scene = loadWorld(server.url("/worlds/deep/w.wrl"));
  for (const auto& d : scene->diagnostics.items) UNSCOPED_INFO(d.format());
  CHECK(scene->diagnostics.errorCount() == 0);
  CHECK(scene->rootNodes.size() == 2);
  const auto log = server.accessLog(2);
  CHECK(std::any_of(log.begin(), log.end(), [](const std::string& l) {
    return l.rfind("GET /worlds/deep/w.wrl 200 ", 0) == 0;
  }));
  CHECK(std::count_if(log.begin(), log.end(), [&](const std::string& l) {
          return l.rfind("GET /protos/a.wrl 200 " + std::to_string(proto.size()), 0) == 0;
        }) >= 1);
  CHECK(std::none_of(log.begin(), log.end(), [](const std::string& l) {
    return l.find(" 404 ") != std::string::npos || l.find("..") != std::string::npos;
  }));
}

TEST_CASE("an HTTP world may not name a local EXTERNPROTO file", "[net][url][http][nginx]") {
  NginxServer server;
  if (!server.ok()) return;
  server.writeFile("w.wrl",
                   "#VRML V2.0 utf8\n"
                   "EXTERNPROTO P [] \"file:///etc/passwd\"\nP {}\n");
  const auto scene = loadWorld(server.url("/w.wrl"));
  REQUIRE(scene->diagnostics.items.size() >= 1);
  bool named = false;
  for (const auto& d : scene->diagnostics.items)
    named = named || d.format().find("file:///etc/passwd") != std::string::npos;
  CHECK(named);
  const auto log = server.accessLog(1);
  CHECK(log.size() == 1);  // the world only
}
