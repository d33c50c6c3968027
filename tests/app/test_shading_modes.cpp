// The browser option Shading's FLAT, WIREFRAME and POINT modes, and a world's Scripts
// reading and setting it (Browser.getBrowserOption / setBrowserOption; --shading;
// render/browser_options.hpp, docs/rendering.md "Browser options").
#include <catch2/catch.hpp>

#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "baseline.hpp"
#include "http/fault_server.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

namespace {

// A grey sphere lit by one white DirectionalLight from the upper left, on black.
constexpr const char* kLitSphere = R"(#X3D V4.0 utf8
PROFILE Interchange
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 3.2 }
DirectionalLight { direction 1 -1 -1 }
Shape {
  appearance Appearance { material Material { diffuseColor 0.8 0.8 0.8 } }
  geometry Sphere { }
}
)";

struct Coverage {
  double lit = 0.0;         // share of the picture's pixels that are not black
  double sameAsLeft = 0.0;  // of the lit pixels whose left neighbour is lit: equal to it
};

Coverage coverage(const std::string& png) {
  const gs::render::Image image = gs::render::readPng(png);
  const auto at = [&](int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * image.width + x) * 4;
    return std::uint32_t(image.rgba[i]) << 16 | std::uint32_t(image.rgba[i + 1]) << 8 |
           image.rgba[i + 2];
  };
  double lit = 0.0, pairs = 0.0, same = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (at(x, y) == 0) continue;
      lit += 1.0;
      if (x == 0 || at(x - 1, y) == 0) continue;
      pairs += 1.0;
      if (at(x - 1, y) == at(x, y)) same += 1.0;
    }
  return {lit / (static_cast<double>(image.width) * image.height),
          pairs > 0.0 ? same / pairs : 0.0};
}

/// The lit sphere written in `dir`, and a function that snapshots it at 160x160 with a
/// --shading value and measures the picture.
std::function<Coverage(const std::string&)> litSphere(const gs::test::TempDir& dir) {
  return [world = dir.write("lit_sphere.x3dv", kLitSphere)](const std::string& shading) {
    return coverage(gs::test::snapshot("shading_mode_" + shading,
                                       {"--size", "160x160", "--shading", shading, world}));
  };
}

}  // namespace

TEST_CASE("the option Shading FLAT lights each triangle by its own normal, PHONG smoothly",
          "[app][render]") {
  const gs::test::TempDir dir("shading_flat");
  const auto shot = litSphere(dir);
  const Coverage phong = shot("phong"), flat = shot("flat");
  INFO("lit: phong " << phong.lit << ", flat " << flat.lit << "; equal to the left neighbour: "
                     << "phong " << phong.sameAsLeft << ", flat " << flat.sameAsLeft);
  // The same sphere covers the same pixels; a facet is one colour, a smooth surface a ramp.
  CHECK(flat.lit == Approx(phong.lit).margin(0.01));
  CHECK(flat.sameAsLeft > 0.7);
  CHECK(phong.sameAsLeft < flat.sameAsLeft - 0.3);
}

TEST_CASE("the option Shading WIREFRAME draws polygons as their edges, POINT as vertices",
          "[app][render]") {
  const gs::test::TempDir dir("shading_wire");
  const auto shot = litSphere(dir);
  const Coverage phong = shot("phong"), wireframe = shot("wireframe"), point = shot("point");
  INFO("lit: phong " << phong.lit << ", wireframe " << wireframe.lit << ", point " << point.lit);
  CHECK(phong.lit > 0.3);
  CHECK(wireframe.lit > 0.03);
  CHECK(wireframe.lit < 0.8 * phong.lit);
  CHECK(point.lit > 0.002);
  CHECK(point.lit < 0.5 * wireframe.lit);
}

TEST_CASE("a Script reads and sets the browser option Shading", "[app][render][script]") {
  const gs::test::TempDir dir("shading_script");
  const std::string world = dir.write("scripted.x3dv", std::string(kLitSphere) + R"(
DEF S Script {
  url "ecmascript:
function initialize () {
  print ('before ' + Browser .getBrowserOption ('Shading'));
  print ('wireframe ' + Browser .setBrowserOption ('Shading', 'WIREFRAME'));
  print ('smooth ' + Browser .setBrowserOption ('Shading', 'smooth'));
  print ('unknown ' + Browser .setBrowserOption ('NoSuchOption', 'TRUE'));
  print ('unknown is ' + Browser .getBrowserOption ('NoSuchOption'));
  print ('after ' + Browser .getBrowserOption ('Shading'));
}"
}
)");
  const std::string plain = dir.write("plain.x3dv", kLitSphere);
  const std::string png = (dir.path / "scripted.png").string();
  const gs::test::ProcessResult r =
      gs::test::runGhostspace({"--snapshot", png, "--size", "160x160", world});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("before PHONG") != std::string::npos);
  CHECK(r.err.find("wireframe true") != std::string::npos);
  CHECK(r.err.find("smooth false") != std::string::npos);
  CHECK(r.err.find("unknown false") != std::string::npos);
  CHECK(r.err.find("unknown is undefined") != std::string::npos);
  CHECK(r.err.find("after WIREFRAME") != std::string::npos);
  // The world is drawn as --shading wireframe draws it, not as the command line's phong.
  const std::string wireframe = gs::test::snapshot(
      "shading_script_wireframe", {"--size", "160x160", "--shading", "wireframe", plain});
  const std::string phong =
      gs::test::snapshot("shading_script_phong", {"--size", "160x160", plain});
  CHECK(gs::test::fractionDiffering(png, wireframe) == 0.0);
  CHECK(gs::test::fractionDiffering(png, phong) > 0.1);
}

TEST_CASE("the window's View > Shading sets the option for the viewport's world",
          "[app][window][render]") {
  // The window script's `shading` runs what the menu runs (WindowState::setShading).
  gs::test::Xvfb x;
  if (gs::test::skipWithoutXvfb(x)) return;
  const gs::test::TempDir dir("shading_window");
  const std::string world = dir.write("lit_sphere.x3dv", kLitSphere);
  const std::string smooth = (dir.path / "window_phong.png").string();
  const std::string edges = (dir.path / "window_wireframe.png").string();
  const std::string script = (dir.path / "shading.script").string();
  std::ofstream(script) << "wait-loaded\nscreenshot-viewport " << smooth
                        << "\nshading wireframe\nframes 2\nscreenshot-viewport " << edges
                        << "\nquit\n";
  const gs::test::ProcessResult r =
      gs::test::runGhostspace({"--size", "160x160", "--new-instance", "--script", script, world},
                              {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const Coverage phong = coverage(smooth), wireframe = coverage(edges);
  INFO("lit in the window: phong " << phong.lit << ", wireframe " << wireframe.lit);
  CHECK(phong.lit > 0.2);
  CHECK(wireframe.lit > 0.02);
  CHECK(wireframe.lit < 0.8 * phong.lit);
}

TEST_CASE("a Script reads the renderer's properties and hears the world's load end",
          "[app][script]") {
  const gs::test::TempDir dir("rendering_properties");
  const std::string world = dir.write("properties.x3dv", std::string(kLitSphere) + R"(
DEF S Script {
  url "ecmascript:
function initialize () {
  print (['Shading', 'MaxTextureSize', 'TextureUnits', 'MaxLights', 'Antialiased', 'ColorDepth'].map (
    function (n) { return n + '=' + Browser .getRenderingProperty (n); }).join (' '));
  Browser .addBrowserCallback ('k', X3DConstants .INITIALIZED_EVENT, function (e) { print ('loaded ' + e); });
}"
}
)");
  for (const char* samples : {"1", "4"}) {
    const std::string png = (dir.path / (std::string("s") + samples + ".png")).string();
    const gs::test::ProcessResult r = gs::test::runGhostspace(
        {"--snapshot", png, "--size", "64x64", "--samples", samples, world});
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    CHECK(r.err.find("Shading=PHONG MaxTextureSize=16384 TextureUnits=4 MaxLights=8 Antialiased=" +
                     std::string(samples[0] == '4' ? "true" : "false") + " ColorDepth=24") !=
          std::string::npos);
    CHECK(r.err.find("loaded 2") != std::string::npos);
  }
}

TEST_CASE("a Script hears INITIALIZED_ERROR when its world's transfer stops short",
          "[app][script][http]") {
  // The Script comes first; the transfer stalls after it, inside the sphere's Shape.
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
DEF S Script {
  url "ecmascript:
function initialize () {
  Browser .addBrowserCallback ('k', function (e) { print ('browser event ' + e); });
}"
}
)" + std::string(kLitSphere).substr(std::string(kLitSphere).find("NavigationInfo"));
  gs::test::FaultServer server(world, gs::test::FaultServer::Behaviour::stall, world.size() - 20);
  REQUIRE(server.ok());
  const gs::test::TempDir dir("initialized_error");
  const gs::test::ProcessResult r =
      gs::test::runGhostspace({"--snapshot", (dir.path / "cut.png").string(), "--size", "64x64",
                               "--stall-timeout", "1", server.url("/cut.x3dv")});
  INFO(r.err);
  CHECK(r.exitCode == 3);  // a picture from an incomplete input
  CHECK(r.err.find("browser event 4") != std::string::npos);
  CHECK(r.err.find("browser event 2") == std::string::npos);
}
