// MovieTexture through the command line (docs/media.md): --snapshot --time T shows the
// frame of the movie's media time, and --trace-events shows duration_changed and isActive.
#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using gs::test::runGhostspace;

namespace {

std::string movieWorld() {
  return (gs::test::sourceDir() / "assets/media/movie.wrl").string();
}

}  // namespace

TEST_CASE("MovieTexture: --time T shows the frame of T, forwards and backwards",
          "[app][media][baseline]") {
  // 0.1 s: the looping movie on its red frames, the backwards one on its white ones.
  gs::test::checkBaseline("movie_t0.1", {"--size", "200x150", "--time", "0.1", movieWorld()});
  // 0.6 s: blue and green.
  gs::test::checkBaseline("movie_t0.6", {"--size", "200x150", "--time", "0.6", movieWorld()});
  // 1.6 s: a second cycle of the loop shows the same frames as 0.6 s.
  const std::string a =
      gs::test::snapshot("movie_a", {"--size", "200x150", "--time", "0.6", movieWorld()});
  const std::string b =
      gs::test::snapshot("movie_b", {"--size", "200x150", "--time", "1.6", movieWorld()});
  const std::string c =
      gs::test::snapshot("movie_c", {"--size", "200x150", "--time", "0.1", movieWorld()});
  CHECK(gs::test::fractionDiffering(a, b) < 0.01);
  CHECK(gs::test::fractionDiffering(a, c) > 0.05);
}

TEST_CASE("MovieTexture: duration_changed and isActive in the event trace", "[app][media]") {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "media-cli";
  fs::create_directories(dir);
  const fs::path trace = dir / "trace.jsonl";
  auto r = runGhostspace({"--snapshot", (dir / "t.png").string(), "--size", "32x32", "--time", "2",
                          "--trace-events", trace.string(), movieWorld()});
  REQUIRE(r.exitCode == 0);
  std::ifstream in(trace);
  std::stringstream text;
  text << in.rdbuf();
  const std::string t = text.str();
  for (const char* node : {"Forwards", "Backwards"}) {
    INFO(node);
    const std::string prefix = std::string(R"({"time":2.000,"node":")") + node + "\",";
    CHECK(t.find(prefix + R"("field":"duration_changed","value":"1.000"})") != std::string::npos);
    CHECK(t.find(prefix + R"("field":"isActive","value":"TRUE"})") != std::string::npos);
  }
}

TEST_CASE("MovieTexture: a movie that is not one is a warning naming it", "[app][media]") {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "media-cli";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "broken.mpg") << "this is no MPEG";
    std::ofstream(dir / "broken.wrl")
        << "#VRML V2.0 utf8\nShape { appearance Appearance { texture MovieTexture { url "
           "\"broken.mpg\" loop TRUE } } geometry Box {} }\n";
  }
  auto r = runGhostspace(
      {"--snapshot", (dir / "b.png").string(), "--size", "32x32", (dir / "broken.wrl").string()});
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("broken.mpg") != std::string::npos);
  CHECK(r.err.find("MovieTexture") != std::string::npos);
}

TEST_CASE("the window's frame-stats: frame times and the movie frames each viewport showed",
          "[app][media][window]") {
  gs::test::Xvfb x;
  if (gs::test::skipWithoutXvfb(x)) return;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "test_media_cli";
  fs::create_directories(dir);
  const fs::path script = dir / "stats.script", first = dir / "stats-1.txt",
                 second = dir / "stats-2.txt";
  // The movie world on the left, a world without movies on the right.
  std::ofstream(script) << "layout 2x1\nviewport 1\nopen "
                        << (gs::test::sourceDir() / "assets/worlds/welcome.wrl").string()
                        << "\nwait-loaded\nframe-stats " << first.string()
                        << "\nframes 6\nframe-stats " << second.string() << "\nquit\n";
  auto r = runGhostspace(
      {"--size", "320x240", "--new-instance", "--script", script.string(), movieWorld()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::ifstream in(second);
  std::string word;
  std::size_t frames = 0;
  double mean = -1.0, median = -1.0, p95 = -1.0, max = -1.0;
  REQUIRE(in >> word >> frames);
  CHECK(word == "frames");
  CHECK(frames == 6);  // the frames drawn since the first frame-stats
  REQUIRE(in >> word >> mean >> word >> median >> word >> p95 >> word >> max);
  CHECK(mean > 0.0);
  CHECK(median <= max);
  CHECK(p95 <= max);
  std::uint64_t movieFrames[2] = {99999, 99999}, uploads[2] = {99999, 99999};
  for (int i = 0; i < 2; ++i) {
    int index = -1;
    REQUIRE(in >> word >> index >> word >> movieFrames[i]);
    CHECK(index == i);
    CHECK(word == "movie_frames");
    REQUIRE(in >> word >> uploads[i]);
    CHECK(word == "movie_uploads");
  }
  // Two looping movies: at most one new frame each per frame drawn so far; none without.
  CHECK(movieFrames[0] <= 2 * 40);
  CHECK(movieFrames[1] == 0);
  // The frames shown were copied by this viewport (it alone shows the movie world).
  CHECK(uploads[0] == movieFrames[0]);
  CHECK(uploads[1] == 0);
}
