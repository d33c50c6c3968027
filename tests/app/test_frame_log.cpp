// --frame-log: one CSV line per window frame (app/frame_log.hpp), read by the soak test.
#include "app/frame_log.hpp"
#include "process.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) out.push_back(f);
  return out;
}

}  // namespace

TEST_CASE("frame log lines have the header's columns", "[app][frame-log]") {
  gs::app::FrameSample s;
  s.seconds = 12.5;
  s.frameMs = 16.6667;
  s.workMs = 3.25;
  s.rssKib = 2048000;
  s.vectors[0] = 120000;
  s.vectors[3] = 7;
  s.lod[0] = 0.25;
  s.lod[3] = 1.0;
  const std::string line = gs::app::formatFrameLine(s);
  CHECK(line == "12.500,16.667,3.250,2048000,120000,0,0,7,0.2500,0.0000,0.0000,1.0000");
  CHECK(fields(line).size() == fields(gs::app::frameLogHeader()).size());
  CHECK(gs::app::residentKib() > 0);
}

TEST_CASE("the window writes one frame log line per frame", "[app][window][frame-log]") {
  gs::test::Xvfb x;
  if (gs::test::skipWithoutXvfb(x)) return;
  gs::test::TempDir dir("framelog");
  const std::string log = (dir.path / "frames.csv").string();
  const auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto r = gs::test::runGhostspace(
      {"--frames", "4", "--size", "320x240", "--frame-log", log, world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::ifstream in(log);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  REQUIRE(lines.size() == 5);
  CHECK(lines[0] == gs::app::frameLogHeader());
  double last = -1.0;
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto f = fields(lines[i]);
    REQUIRE(f.size() == 12);
    const double seconds = std::stod(f[0]), frameMs = std::stod(f[1]), workMs = std::stod(f[2]);
    CHECK(seconds > last);
    CHECK(workMs <= frameMs);
    CHECK(std::stoull(f[3]) > 0);  // resident KiB
    last = seconds;
  }

  const auto bad = gs::test::runGhostspace(
      {"--frames", "1", "--frame-log", "/nonexistent/dir/f.csv", world.string()},
      {"DISPLAY=" + x.display()});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("--frame-log") != std::string::npos);
}

TEST_CASE("a snapshot writes the frame log as the window does, a line per frame written",
          "[app][frame-log]") {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path log = dir / "snapshot_frame_log.csv";
  fs::remove(log);
  const auto r = gs::test::runGhostspace(
      {"--snapshot", (dir / "snapshot_frame_log.png").string(), "--size", "64x64", "--layout",
       "2x1", "--lod", "1,0.5", "--time", "0:1:3", "--frame-log", log.string(),
       (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::ifstream in(log);
  std::string line;
  REQUIRE(std::getline(in, line));
  CHECK(line == gs::app::frameLogHeader());
  int lines = 0;
  while (std::getline(in, line)) {
    const auto f = fields(line);
    REQUIRE(f.size() == 12);
    const double all = std::stod(f[4]), half = std::stod(f[5]);
    CHECK(all > 0);
    CHECK(half > 0);
    CHECK(half < all);  // viewport 1 draws half the vectors of viewport 0
    CHECK(std::stod(f[6]) == 0);
    CHECK(std::stod(f[8]) == Approx(1.0));
    CHECK(std::stod(f[9]) == Approx(0.5));
    ++lines;
  }
  CHECK(lines == 3);
  // A log that cannot be written is an error, not a silent success.
  const auto bad =
      gs::test::runGhostspace({"--snapshot", (dir / "snapshot_frame_log_bad.png").string(),
                               "--size", "32x32", "--frame-log", "/nonexistent-dir/log.csv",
                               (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string()});
  CHECK(bad.exitCode == 1);
  CHECK(bad.err.find("--frame-log") != std::string::npos);
}
