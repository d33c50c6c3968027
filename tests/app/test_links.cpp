// What a clicked link may do (app/pointer_input.hpp decideLink): worlds, documents, and
// the rules that keep content from the network away from local files and programs.
#include "app/pointer_input.hpp"

#include <catch2/catch.hpp>

using gs::app::decideLink;
using gs::app::LinkAction;

TEST_CASE("links: a local world opens worlds and passive local documents", "[app][links]") {
  auto d = decideLink("/data/worlds/a.wrl", {"b.wrl"}, {});
  CHECK(d.action == LinkAction::openWorld);
  CHECK(d.url == "/data/worlds/b.wrl");
  d = decideLink("/data/worlds/a.wrl", {"other.wrl#Top"}, {"target=right"});
  CHECK(d.action == LinkAction::openWorldInNewViewport);
  CHECK(d.url == "/data/worlds/other.wrl#Top");
  CHECK(decideLink("/data/a.wrl", {"manual.pdf"}, {}).action == LinkAction::external);
  CHECK(decideLink("/data/a.wrl", {"https://example.org/page"}, {}).action == LinkAction::external);
  CHECK(decideLink("/data/a.wrl", {"http://example.org/w.wrl"}, {"target=_self"}).action ==
        LinkAction::openWorld);
  // Programs and other schemes are never started.
  CHECK(decideLink("/data/a.wrl", {"run.sh"}, {}).action == LinkAction::refused);
  CHECK(decideLink("/data/a.wrl", {"app.desktop"}, {}).action == LinkAction::refused);
  CHECK(decideLink("/data/a.wrl", {"javascript:alert(1)"}, {}).action == LinkAction::refused);
  CHECK(decideLink("/data/a.wrl", {}, {}).action == LinkAction::refused);
  // The first usable url wins.
  d = decideLink("/data/a.wrl", {"javascript:x", "b.wrl"}, {});
  CHECK(d.action == LinkAction::openWorld);
  CHECK(d.url == "/data/b.wrl");
}

TEST_CASE("links: a world from the network never opens local files", "[app][links]") {
  const std::string world = "http://example.org/worlds/a.wrl";
  auto d = decideLink(world, {"b.wrl"}, {});
  CHECK(d.action == LinkAction::openWorld);
  CHECK(d.url == "http://example.org/worlds/b.wrl");
  CHECK(decideLink(world, {"/etc/passwd"}, {}).url == "http://example.org/etc/passwd");
  d = decideLink(world, {"file:///etc/passwd"}, {});
  CHECK(d.action == LinkAction::refused);
  CHECK(d.reason.find("local files") != std::string::npos);
  CHECK(decideLink(world, {"file:///home/u/w.wrl"}, {}).action == LinkAction::refused);
  CHECK(decideLink(world, {"doc.pdf"}, {}).action == LinkAction::external);  // over http
  CHECK(decideLink(world, {"mailto:a@b.c"}, {}).action == LinkAction::refused);
  CHECK(decideLink("https://example.org/a.wrl", {"https://example.org/b.wrz"}, {}).action ==
        LinkAction::openWorld);
}

TEST_CASE("links: xdg-open takes no option-like argument", "[app][links]") {
  std::string error;
  CHECK_FALSE(gs::app::openExternally("--help", error));
  CHECK(!error.empty());
}
