// The real window under Xvfb: it opens, draws a few frames through GLFW + ImGui and the
// same SceneRenderer as --snapshot, and closes cleanly. Skips when Xvfb is absent.
#include "baseline.hpp"
#include "http/nginx_server.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

#include <catch2/catch.hpp>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace {

using gs::test::skipWithoutXvfb;
using gs::test::Xvfb;

/// True (after test::missingFixture() named it) when no Xvfb runs: the test then returns.

}  // namespace

TEST_CASE("the window opens a world, draws frames and closes", "[app][window]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  const auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto r = gs::test::runGhostspace({"--frames", "5", "--size", "320x240", world.string()},
                                   {"DISPLAY=" + x.display()});
  INFO(r.err);
  CHECK(r.exitCode == 0);
}

TEST_CASE("without a display the window fails with a clear message", "[app][window]") {
  auto r = gs::test::runGhostspace({"--frames", "1", "x.wrl"}, {"DISPLAY=:7777"});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("window") != std::string::npos);
}

TEST_CASE("a load error is reported in the window, which keeps running", "[app][window]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  auto r = gs::test::runGhostspace({"--frames", "3", "/nonexistent/world.wrl"},
                                   {"DISPLAY=" + x.display()});
  CHECK(r.exitCode == 0);
}

namespace {

std::string fileBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

gs::render::Image half(const gs::render::Image& image, bool right) {
  const int w = image.width / 2;
  gs::render::Image out(w, image.height);
  for (int row = 0; row < image.height; ++row)
    std::copy_n(
        image.rgba.begin() +
            (static_cast<std::ptrdiff_t>(row) * image.width + (right ? image.width - w : 0)) * 4,
        w * 4, out.rgba.begin() + static_cast<std::ptrdiff_t>(row) * w * 4);
  return out;
}

}  // namespace

TEST_CASE("two viewports at their own levels of detail; a scripted LOD change fetches more",
          "[app][window][http]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-actual";
  fs::create_directories(dir);
  // A 40^3 ball with a soft edge: about 30,000 vectors, several times the first slice.
  const fs::path raw = dir / "ball.raw", qnv = dir / "ball.qnv";
  {
    std::string v(40 * 40 * 40, '\0');
    for (int i = 0; i < 40 * 40 * 40; ++i) {
      const double dx = i % 40 - 20.0, dy = i / 40 % 40 - 20.0, dz = i / 1600 - 20.0;
      v[static_cast<std::size_t>(i)] = static_cast<char>(static_cast<unsigned char>(
          std::clamp(255.0 - 10.0 * std::sqrt(dx * dx + dy * dy + dz * dz), 0.0, 255.0)));
    }
    std::ofstream(raw, std::ios::binary) << v;
  }
  REQUIRE(gs::test::runGhostspace({"encode", raw.string(), "--raw-dims", "40,40,40", "-o",
                                   qnv.string(), "--no-progress", "--packet-bytes", "48"})
              .exitCode == 0);
  const std::string bytes = fileBytes(qnv);
  nginx.writeFile("ball.qnv", bytes);
  const fs::path script = dir / "lod.script", before = dir / "before.png",
                 after = dir / "after.png", right = dir / "right.png";
  std::ofstream(script) << "wait-loaded\nscreenshot " << before.string()
                        << "\nviewport 1\nlod 1\nwait-loaded\nscreenshot " << after.string()
                        << "\nscreenshot-viewport " << right.string() << "\nquit\n";
  const auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto r =
      gs::test::runGhostspace({"--size", "400x220", "--layout", "2x1", "--lod", "1,0.05",
                               "--script", script.string(), world.string(), nginx.url("/ball.qnv")},
                              {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const auto a = gs::render::readPng(before.string()), b = gs::render::readPng(after.string());
  // The left viewport did not change; the right one did, with its level of detail.
  CHECK(gs::render::compareImages(half(a, false), half(b, false), 0).fractionDiffering == 0.0);
  CHECK(gs::render::compareImages(half(a, true), half(b, true), 16).fractionDiffering > 0.01);
  // The right viewport at full detail looks as a snapshot of the stream does.
  const auto rightImage = gs::render::readPng(right.string());
  const fs::path snap = dir / "snapshot.png";
  REQUIRE(gs::test::runGhostspace(
              {"--snapshot", snap.string(), "--size",
               std::to_string(rightImage.width) + "x" + std::to_string(rightImage.height),
               "--no-progress", qnv.string()})
              .exitCode == 0);
  CHECK(gs::render::compareImages(rightImage, gs::render::readPng(snap.string()), 16)
            .fractionDiffering < 0.02);
  // Fetched once: range requests only, each byte once, several requests as LOD grew.
  const auto log = nginx.accessLog(2);
  for (const std::string& line : log) {
    INFO(line);
    CHECK(line.find(" 206 ") != std::string::npos);
  }
  CHECK(log.size() >= 2);
  CHECK(gs::test::NginxServer::bodyBytes(log) == bytes.size());
}

TEST_CASE("a bad window script is a usage error naming its line", "[app][window]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  const auto path = std::filesystem::path(GS_BINARY_DIR) / "bad.script";
  std::ofstream(path) << "frames 2\nlod 7\n";
  auto r = gs::test::runGhostspace({"--script", path.string()}, {"DISPLAY=" + x.display()});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("bad.script:2: expected lod F") != std::string::npos);
}

TEST_CASE("a second launch hands its file to the running window", "[app][window][helper]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-actual";
  const fs::path runtime = dir / ("xdg-helper-" + std::to_string(::getpid()));
  fs::create_directories(runtime);
  fs::permissions(runtime, fs::perms::owner_all, fs::perm_options::replace);
  const fs::path script = dir / "helper.script", shot = dir / "helper.png";
  // The first window waits (at most 60 s) until a second viewport shows a world.
  std::ofstream(script) << "wait-viewports 2\nwait-loaded\nscreenshot " << shot.string()
                        << "\nquit\n";
  const auto welcome = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  const auto part = gs::test::sourceDir() / "assets/meshes/tetra.glb";
  const std::vector<std::string> env = {"DISPLAY=" + x.display(),
                                        "XDG_RUNTIME_DIR=" + runtime.string()};
  gs::test::ProcessResult first;
  std::thread window([&] {
    first = gs::test::runGhostspace(
        {"--size", "400x220", "--script", script.string(), welcome.string()}, env);
  });
  // The first window's socket appears once it is up.
  const fs::path socket = runtime / "ghostspace.sock";
  for (int i = 0; i < 400 && !fs::exists(socket); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  CHECK(fs::exists(socket));
  const auto second = gs::test::runGhostspace({part.string()}, env);
  window.join();
  INFO(first.err);
  CHECK(second.exitCode == 0);
  CHECK(second.out.find("running window") != std::string::npos);
  REQUIRE(first.exitCode == 0);
  // The window grew to two viewports: the welcome world left, the green glTF asset (its
  // metallic green material, dark without an environment light) right.
  const auto image = gs::render::readPng(shot.string());
  const auto right = half(image, true);
  std::size_t green = 0;
  for (std::size_t i = 0; i < right.rgba.size(); i += 4)
    green += right.rgba[i + 1] > 40 && right.rgba[i] * 2 < right.rgba[i + 1] &&
                     right.rgba[i + 2] * 2 < right.rgba[i + 1]
                 ? 1
                 : 0;
  CHECK(green > right.rgba.size() / 4 / 50);
  fs::remove_all(runtime);
}

TEST_CASE("the automatic level of detail lowers the fraction to hold the frame time",
          "[app][window]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-actual";
  fs::create_directories(dir);
  const fs::path qnv = dir / "auto.qnv";
  REQUIRE(gs::test::runGhostspace({"encode",
                                   (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string(),
                                   "-o", qnv.string(), "--no-progress"})
              .exitCode == 0);
  const fs::path script = dir / "auto.script", before = dir / "auto-before.txt",
                 after = dir / "auto-after.txt", budget = dir / "auto-budget.txt";
  // A frame-time target of 0.01 ms cannot be met: the level of detail must fall.
  std::ofstream(script) << "layout 2x1\nwait-loaded\nstatus " << before.string()
                        << "\nviewport 1\nauto-lod on\nframe-target 0.01\nframes 15\nstatus "
                        << after.string() << "\nviewport 0\nbudget 100\nframes 2\nstatus "
                        << budget.string() << "\nquit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "300x200", "--script", script.string(), "--new-instance", qnv.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  auto lodOf = [](const fs::path& status, int viewport) {
    std::ifstream in(status);
    int index = -1;
    std::string url, mode, navigation;
    double lod = -1.0;
    std::size_t splats = 0;
    while (in >> index >> url >> lod >> mode >> navigation >> splats)
      if (index == viewport) return lod;
    return -1.0;
  };
  CHECK(lodOf(before, 0) == 1.0);
  CHECK(lodOf(before, 1) == 1.0);
  CHECK(lodOf(after, 0) == 1.0);  // not automatic
  CHECK(lodOf(after, 1) < 0.01);  // 15 frames of at most halving each
  CHECK(lodOf(after, 1) > 0.0);
  // A vector budget of 100 draws at most 100 vectors, and about that many.
  std::ifstream in(budget);
  int index = -1;
  std::string url, mode, navigation;
  double lod = -1.0;
  std::size_t splats = 0;
  REQUIRE(in >> index >> url >> lod >> mode >> navigation >> splats);
  CHECK(index == 0);
  CHECK(splats <= 100);
  CHECK(splats >= 90);
  CHECK(mode == "polygons");
  CHECK(navigation == "EXAMINE");
}

TEST_CASE("a scripted click on a TouchSensor starts an animation; a drag moves a PlaneSensor",
          "[app][window][pointer]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-pointer";
  fs::create_directories(dir);
  const fs::path world = dir / "touch.wrl", script = dir / "touch.script",
                 trace = dir / "touch.jsonl", before = dir / "before.png",
                 after = dir / "after.png";
  // A click turns the red box blue over half a second (touchTime starts the TimeSensor);
  // the small box beside it follows a PlaneSensor.
  std::ofstream(world) << R"(#VRML V2.0 utf8
Viewpoint { position 0 0 5 }
NavigationInfo { type "EXAMINE" }
Group { children [
  DEF TS TouchSensor {}
  Shape { appearance Appearance { material DEF M Material { diffuseColor 1 0 0 } }
          geometry Box { size 2 2 2 } }
] }
Group { children [
  DEF PS PlaneSensor {}
  DEF MOVED Transform { translation 2.5 0 0 children
    Shape { appearance Appearance { material Material { diffuseColor 0 1 0 } }
            geometry Box { size 0.5 0.5 0.5 } } }
] }
DEF CLOCK TimeSensor { cycleInterval 0.5 }
DEF CI ColorInterpolator { key [ 0 1 ] keyValue [ 1 0 0, 0 0 1 ] }
ROUTE TS.touchTime TO CLOCK.set_startTime
ROUTE CLOCK.fraction_changed TO CI.set_fraction
ROUTE CI.value_changed TO M.set_diffuseColor
ROUTE PS.translation_changed TO MOVED.set_translation
)";
  // 320 x 240 window: the scene area below the menu bar is about 320 x 220; the big box
  // covers its centre, the small one lies right of it.
  std::ofstream(script) << "wait-loaded\ntime 110\nscreenshot " << before.string()
                        << "\nclick 160 110\nadvance 1\nframes 2\nscreenshot " << after.string()
                        << "\ndrag 160 110 200 110 4\nkey a\nquit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "320x240", "--new-instance", "--time", "100", "--trace-events", trace.string(),
       "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::string events = fileBytes(trace);
  INFO(events);
  for (const char* line :
       {R"({"time":110.000,"node":"TS","field":"isOver","value":"TRUE"})",
        R"({"time":110.000,"node":"TS","field":"isActive","value":"TRUE"})",
        R"({"time":110.000,"node":"TS","field":"isActive","value":"FALSE"})",
        R"({"time":110.000,"node":"TS","field":"touchTime","value":"110.000"})",
        R"({"time":110.500,"node":"M","field":"diffuseColor_changed","value":"0 0 1"})"})
    CHECK(events.find(line) != std::string::npos);
  // The drag began on the big box: it held the TouchSensor, not the PlaneSensor (the
  // lowest sensors under the pointer), and did not navigate.
  CHECK(events.find(R"("node":"PS")") == std::string::npos);
  const auto a = gs::render::readPng(before.string()), b = gs::render::readPng(after.string());
  auto pixel = [](const gs::render::Image& im, int px, int py) {
    const auto* p = &im.rgba[(static_cast<std::size_t>(py) * im.width + px) * 4];
    return std::array<int, 3>{p[0], p[1], p[2]};
  };
  const auto redish = pixel(a, a.width / 2, a.height / 2);
  const auto blueish = pixel(b, b.width / 2, b.height / 2);
  CHECK(redish[0] > 128);
  CHECK(redish[2] < 32);
  CHECK(blueish[0] < 32);
  CHECK(blueish[2] > 128);
}

TEST_CASE("a scripted drag on a PlaneSensor moves its Transform", "[app][window][pointer]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-pointer";
  fs::create_directories(dir);
  const fs::path world = dir / "drag.wrl", script = dir / "drag.script", trace = dir / "drag.jsonl";
  std::ofstream(world) << R"(#VRML V2.0 utf8
Viewpoint { position 0 0 5 }
Group { children [
  DEF PS PlaneSensor { maxPosition 10 0 }
  DEF MOVED Transform { children Shape { geometry Box { size 2 2 2 } } }
] }
ROUTE PS.translation_changed TO MOVED.set_translation
)";
  std::ofstream(script) << "wait-loaded\ntime 50\ndrag 160 110 200 110 2\nquit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "320x240", "--new-instance", "--time", "40", "--trace-events", trace.string(),
       "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::string events = fileBytes(trace);
  INFO(events);
  CHECK(events.find(R"({"time":50.000,"node":"PS","field":"isActive","value":"TRUE"})") !=
        std::string::npos);
  CHECK(events.find(R"({"time":50.000,"node":"PS","field":"isActive","value":"FALSE"})") !=
        std::string::npos);
  // 40 pixels to the right at the box's front (z = 1, 4 m from the eye): a positive x
  // translation with y clamped to 0 (minPosition 0 0, maxPosition 10 0).
  const std::size_t at = events.rfind(R"("node":"MOVED","field":"translation_changed","value":")");
  REQUIRE(at != std::string::npos);
  const std::string value = events.substr(at + 54, events.find('"', at + 54) - at - 54);
  std::istringstream v(value);
  float tx = 0, ty = 1, tz = 1;
  v >> tx >> ty >> tz;
  CHECK(tx > 0.3f);
  CHECK(tx < 1.0f);
  CHECK(ty == 0.0f);
  CHECK(tz == 0.0f);
  CHECK(events.find(R"("node":"PS","field":"offset_changed")") != std::string::npos);
}

TEST_CASE("the Viewpoints menu binds through the stack", "[app][window][bind]") {
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-bind";
  fs::create_directories(dir);
  const fs::path world = dir / "two.wrl", script = dir / "two.script", trace = dir / "two.jsonl";
  std::ofstream(world) << R"(#VRML V2.0 utf8
DEF FRONT Viewpoint { position 0 0 5 description "front" }
DEF SIDE Viewpoint { position 5 0 0 orientation 0 1 0 1.5708 description "side" }
Shape { geometry Box {} }
)";
  std::ofstream(script) << "wait-loaded\ntime 50\nviewpoint 1\nframes 2\nviewpoint 0\nframes 2\n"
                           "quit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "200x150", "--new-instance", "--time", "40", "--trace-events", trace.string(),
       "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::string events = fileBytes(trace);
  INFO(events);
  const auto at = [&](const char* line) { return events.find(line); };
  const auto sideBound = at(R"({"time":50.000,"node":"SIDE","field":"isBound","value":"TRUE"})");
  const auto frontUnbound =
      at(R"({"time":50.000,"node":"FRONT","field":"isBound","value":"FALSE"})");
  const auto frontBound =
      events.find(R"({"time":50.000,"node":"FRONT","field":"isBound","value":"TRUE"})", sideBound);
  CHECK(at(R"({"time":40.000,"node":"FRONT","field":"isBound","value":"TRUE"})") !=
        std::string::npos);
  CHECK(frontUnbound != std::string::npos);
  REQUIRE(sideBound != std::string::npos);
  CHECK(frontBound != std::string::npos);
}

TEST_CASE("the window runs the same frame step as --snapshot: a Script-chosen Inline shows",
          "[app][window][inline]") {
  // The window's viewports are session::WorldViews (the owners issue): the Inline a Switch
  // shows after a Script's initialize() is fetched and drawn, as --snapshot draws it.
  Xvfb x;
  if (skipWithoutXvfb(x)) return;
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-chosen";
  fs::create_directories(dir);
  std::ofstream(dir / "part.wrl") << R"(#VRML V2.0 utf8
Shape { appearance Appearance { material Material { diffuseColor 1 0 0 emissiveColor 1 0 0 } }
        geometry Box { size 4 4 4 } }
)";
  const fs::path world = dir / "chosen.wrl", script = dir / "chosen.script",
                 png = dir / "chosen.png";
  std::ofstream(world) << R"(#VRML V2.0 utf8
Viewpoint { position 0 0 12 }
DEF SW Switch { whichChoice -1 choice [ Inline { url "part.wrl" } ] }
DEF S Script { eventOut SFInt32 choice url "javascript: function initialize() { choice = 0; }" }
ROUTE S.choice TO SW.set_whichChoice
)";
  std::ofstream(script) << "wait-loaded\nframes 3\nwait-loaded\nscreenshot " << png.string()
                        << "\nquit\n";
  fs::remove(png);
  auto r = gs::test::runGhostspace(
      {"--size", "160x120", "--new-instance", "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const auto c = gs::test::centrePixel(png.string());
  CHECK(c[0] > 200);
  CHECK(c[1] < 60);
  CHECK(c[2] < 60);
}
