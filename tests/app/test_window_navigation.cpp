// The window's navigation against the world under Xvfb (issue 11 points 6 and 7): a
// scripted WALK stops at a wall and sends the Collision's collideTime, walks off a
// ledge onto the floor; Anchor links keep a Back / Forward history per viewport.
#include "process.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

std::string fileText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<float> position(const fs::path& p) {
  std::istringstream in(fileText(p));
  std::vector<float> v(3, -999.0f);
  in >> v[0] >> v[1] >> v[2];
  return v;
}

/// The world URL of viewport 0 in a `status` file.
std::string worldOf(const fs::path& status) {
  std::istringstream in(fileText(status));
  std::string index, url;
  in >> index >> url;
  return url;
}

}  // namespace

TEST_CASE("a scripted walk stops at a Collision's wall, sends collideTime and falls off a ledge",
          "[app][window][collision]") {
  gs::test::Xvfb x;
  if (!x.running()) {
    WARN("SKIPPED: /usr/bin/Xvfb is absent (install xvfb)");
    return;
  }
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-navigation";
  fs::create_directories(dir);
  const fs::path world = dir / "walls.wrl", script = dir / "walk.script",
                 trace = dir / "walk.jsonl";
  // A floor (top at y = 0), a wall inside a Collision (near face at z = -4.9), a 1 m high
  // platform east of the start (x from 3 to 7, z from -2 to 2).
  std::ofstream(world) << R"(#VRML V2.0 utf8
NavigationInfo { type "WALK" avatarSize [ 0.25 1.6 0.75 ] }
Viewpoint { position 0 1.6 0 }
Transform { translation 0 -0.05 0 children Shape { geometry Box { size 40 0.1 40 } } }
DEF WALL Collision { children
  Transform { translation 0 5 -5 children Shape { geometry Box { size 20 10 0.2 } } } }
Transform { translation 5 0.5 0 children Shape { geometry Box { size 4 1 4 } } }
)";
  std::vector<fs::path> at;
  auto camera = [&](const char* name) {
    at.push_back(dir / (std::string(name) + ".txt"));
    return "camera " + at.back().string() + "\n";
  };
  std::ofstream(script) << "wait-loaded\ntime 20\n"
                        << "walk 10 0 0 5\n"
                        << camera("wall")  // stopped by the wall
                        << "walk -4.65 0 0\nwalk 0 5 0\n"
                        << camera("platform-side")  // 1 m: blocks
                        << "navigation FLY\nwalk 0 0 3\nwalk 0 2.25 0\nnavigation WALK\n"
                        << "walk 0 0 0\n"
                        << camera("on-platform")  // fell onto it
                        << "walk 0 5 0\nframes 2\n"
                        << camera("off-ledge") << "quit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "320x240", "--new-instance", "--time", "10", "--trace-events", trace.string(),
       "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  auto check = [&](std::size_t i, float px, float py, float pz) {
    const auto p = position(at[i]);
    INFO(at[i].filename().string() << ": " << p[0] << " " << p[1] << " " << p[2]);
    CHECK(p[0] == Approx(px).margin(1e-3));
    CHECK(p[1] == Approx(py).margin(1e-3));
    CHECK(p[2] == Approx(pz).margin(1e-3));
  };
  check(0, 0.0f, 1.6f, -4.65f);
  check(1, 2.75f, 1.6f, 0.0f);
  check(2, 5.0f, 2.6f, 0.0f);
  check(3, 10.0f, 1.6f, 0.0f);
  const std::string events = fileText(trace);
  INFO(events);
  CHECK(events.find(R"({"time":20.000,"node":"WALL","field":"collideTime","value":"20.000"})") !=
        std::string::npos);
  // Only the wall is in a Collision: one collideTime for each of the steps that met it.
  std::size_t count = 0;
  for (std::size_t p = events.find("collideTime"); p != std::string::npos;
       p = events.find("collideTime", p + 1))
    ++count;
  CHECK(count >= 1);
  CHECK(count <= 5);
}

TEST_CASE("Anchor links keep a Back / Forward history in their viewport", "[app][window][links]") {
  gs::test::Xvfb x;
  if (!x.running()) {
    WARN("SKIPPED: /usr/bin/Xvfb is absent (install xvfb)");
    return;
  }
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-history";
  fs::create_directories(dir);
  const fs::path a = dir / "a.wrl", b = dir / "b.wrl", script = dir / "history.script";
  std::ofstream(a) << R"(#VRML V2.0 utf8
Viewpoint { position 0 0 5 }
NavigationInfo { type "EXAMINE" }
Anchor { url "b.wrl" description "to b" children Shape { geometry Box { size 3 3 3 } } }
)";
  std::ofstream(b) << "#VRML V2.0 utf8\nShape { geometry Sphere {} }\n";
  std::vector<fs::path> statuses;
  auto status = [&] {
    statuses.push_back(dir / ("status-" + std::to_string(statuses.size()) + ".txt"));
    return "status " + statuses.back().string() + "\n";
  };
  std::ofstream(script) << "wait-loaded\n"
                        << status() << "click 160 110\nframes 3\nwait-loaded\n"
                        << status() << "back\nframes 2\n"
                        << status() << "forward\nframes 2\n"
                        << status() << "forward\nback\nback\nframes 2\n"
                        << status() << "quit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "320x240", "--new-instance", "--script", script.string(), a.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  REQUIRE(statuses.size() == 5);
  auto endsWith = [](const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
  };
  const char* expected[] = {"a.wrl", "b.wrl", "a.wrl", "b.wrl", "a.wrl"};
  for (std::size_t i = 0; i < statuses.size(); ++i) {
    INFO(i << ": " << worldOf(statuses[i]));
    CHECK(endsWith(worldOf(statuses[i]), expected[i]));
  }
}
