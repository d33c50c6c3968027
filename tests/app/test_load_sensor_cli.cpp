// X3D LoadSensor (X3D 4.0 clause 9.4.3) end to end: ghostspace --snapshot loads a world
// whose LoadSensor watches an Inline; its isLoaded, through a BooleanFilter and
// IntegerTriggers, picks the Switch choice drawn at the centre, and --trace-events shows
// the sensor's events.
#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>
#include <string>

namespace {

/// The world: a LoadSensor L watching Inline `inlineUrl` (a red box off to the left);
/// isLoaded TRUE shows the Switch's green box at the centre, FALSE its blue box; before
/// either the centre is the black background.
std::string loadSensorCliWorld(const std::string& inlineUrl) {
  return "#X3D V4.0 utf8\n"
         "PROFILE Immersive\n"
         "Viewpoint { position 0 0 12 }\n"
         "Transform { translation -4 0 0 children DEF I Inline { url \"" +
         inlineUrl +
         "\" } }\n"
         "DEF SW Switch { whichChoice -1 children [\n"
         "  Shape { appearance Appearance { material Material { diffuseColor 0 1 0 } }\n"
         "          geometry Box { size 3 3 3 } }\n"
         "  Shape { appearance Appearance { material Material { diffuseColor 0 0 1 } }\n"
         "          geometry Box { size 3 3 3 } } ] }\n"
         "DEF L LoadSensor { children USE I }\n"
         "DEF F BooleanFilter {}\n"
         "DEF Yes IntegerTrigger { integerKey 0 }\n"
         "DEF No IntegerTrigger { integerKey 1 }\n"
         "ROUTE L.isLoaded TO F.set_boolean\n"
         "ROUTE F.inputTrue TO Yes.set_boolean\n"
         "ROUTE F.inputNegate TO No.set_boolean\n"
         "ROUTE Yes.triggerValue TO SW.whichChoice\n"
         "ROUTE No.triggerValue TO SW.whichChoice\n";
}

std::string readLoadSensorTrace(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

TEST_CASE("load sensor: --snapshot shows what isLoaded chose for an Inline that loads",
          "[app][x3d][load_sensor]") {
  gs::test::TempDir dir("load-sensor-cli");
  dir.write("part.x3dv",
            "#X3D V4.0 utf8\n"
            "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
            "        geometry Box { size 1 1 1 } }\n");
  const std::string world = dir.write("main.x3dv", loadSensorCliWorld("part.x3dv"));
  const std::string trace = (dir.path / "trace.jsonl").string();
  const std::string png = gs::test::snapshot(
      "load_sensor_loaded", {"--size", "64x64", "--time", "2", "--trace-events", trace, world});
  const auto c = gs::test::centrePixel(png);
  INFO("centre " << c[0] << " " << c[1] << " " << c[2]);
  CHECK(c[1] > 100);  // green: loaded
  CHECK(c[2] < 60);
  const std::string t = readLoadSensorTrace(trace);
  INFO(t);
  CHECK(t.find(R"({"time":2.000,"node":"L","field":"isActive","value":"TRUE"})") !=
        std::string::npos);
  CHECK(t.find(R"({"time":2.000,"node":"L","field":"isLoaded","value":"TRUE"})") !=
        std::string::npos);
  CHECK(t.find(R"({"time":2.000,"node":"L","field":"loadTime","value":"2.000"})") !=
        std::string::npos);
  CHECK(t.find(R"({"time":2.000,"node":"L","field":"progress","value":"1"})") != std::string::npos);
  CHECK(t.find(R"({"time":2.000,"node":"L","field":"isActive","value":"FALSE"})") !=
        std::string::npos);
}

TEST_CASE("load sensor: --snapshot shows what isLoaded chose for a missing Inline",
          "[app][x3d][load_sensor]") {
  gs::test::TempDir dir("load-sensor-cli");
  const std::string world = dir.write("main.x3dv", loadSensorCliWorld("missing.x3dv"));
  const std::string trace = (dir.path / "trace.jsonl").string();
  const std::string png = (dir.path / "missing.png").string();
  // Exit code 3: a picture from an incomplete input (the Inline's file is missing).
  const auto r = gs::test::runGhostspace(
      {"--snapshot", png, "--size", "64x64", "--time", "2", "--trace-events", trace, world});
  INFO("stderr: " << r.err);
  REQUIRE(r.exitCode == 3);
  const auto c = gs::test::centrePixel(png);
  INFO("centre " << c[0] << " " << c[1] << " " << c[2]);
  CHECK(c[2] > 100);  // blue: failed
  CHECK(c[1] < 60);
  const std::string t = readLoadSensorTrace(trace);
  INFO(t);
  CHECK(t.find(R"("node":"L","field":"isLoaded","value":"FALSE")") != std::string::npos);
  CHECK(t.find(R"("node":"L","field":"loadTime")") == std::string::npos);
}
