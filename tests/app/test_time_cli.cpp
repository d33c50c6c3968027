// The virtual clock on the command line (docs/runtime.md): --time T renders a world as it
// stands at T, --time T0:DT:N writes a strip, --trace-events writes every event; the same
// command gives the same pixels (baselines under docs/rendering-tests.md's metric).
#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;
using gs::test::runGhostspace;

namespace {

std::string animationWorld() {
  return (gs::test::sourceDir() / "assets/worlds/animation.wrl").string();
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "time-cli";
  fs::create_directories(dir);
  return dir / name;
}

}  // namespace

TEST_CASE("time: --time renders the animation as it stands at T", "[app][time][baseline]") {
  // fraction 0.125: the box a quarter of the way, purple-red, the face a quarter morphed.
  gs::test::checkBaseline("animation_t0.5",
                          {"--size", "300x300", "--time", "0.5", animationWorld()});
  // fraction 0.375: the box right of centre, mostly blue, the Inline's cone turned.
  gs::test::checkBaseline("animation_t1.5",
                          {"--size", "300x300", "--time", "1.5", animationWorld()});
  // The two times are different pictures (so the baselines can tell times apart).
  const std::string a =
      gs::test::snapshot("animation_a", {"--size", "300x300", "--time", "0.5", animationWorld()});
  const std::string b =
      gs::test::snapshot("animation_b", {"--size", "300x300", "--time", "1.5", animationWorld()});
  CHECK(gs::test::fractionDiffering(a, b) > 0.02);
}

TEST_CASE("time: --trace-events writes the cascade of the world and its Inline", "[app][time]") {
  const fs::path trace = scratch("trace.jsonl");
  const fs::path png = scratch("trace.png");
  auto r = runGhostspace({"--snapshot", png.string(), "--size", "64x64", "--time", "1",
                          "--trace-events", trace.string(), animationWorld()});
  REQUIRE(r.exitCode == 0);
  std::ifstream in(trace);
  std::stringstream text;
  text << in.rdbuf();
  const std::string t = text.str();
  CHECK(t.find(R"({"time":1.000,"node":"Clock","field":"fraction_changed","value":"0.25"})") !=
        std::string::npos);
  CHECK(t.find(R"({"time":1.000,"node":"Mover","field":"translation_changed","value":"0 1 0"})") !=
        std::string::npos);
  // The Inline's own TimeSensor (cycle 2 s) at fraction 0.5: half a turn.
  CHECK(t.find(R"("node":"Spin","field":"fraction_changed","value":"0.5")") != std::string::npos);
  CHECK(t.find(R"("node":"Spinner","field":"rotation_changed")") != std::string::npos);
}

TEST_CASE("time: --time T0:DT:N writes N frames; bad values are refused", "[app][time]") {
  const fs::path png = scratch("strip.png");
  for (int i = 0; i < 3; ++i) fs::remove(scratch("strip-000" + std::to_string(i) + ".png"));
  auto r = runGhostspace(
      {"--snapshot", png.string(), "--size", "32x32", "--time", "0:0.5:3", animationWorld()});
  REQUIRE(r.exitCode == 0);
  for (int i = 0; i < 3; ++i) CHECK(fs::exists(scratch("strip-000" + std::to_string(i) + ".png")));
  CHECK_FALSE(fs::exists(scratch("strip-0003.png")));
  for (const char* bad : {"-1", "abc", "0:0:3", "0:1:0", "1:2"}) {
    INFO(bad);
    auto b = runGhostspace({"--snapshot", png.string(), "--time", bad, animationWorld()});
    CHECK(b.exitCode == 2);
    CHECK(b.err.find("--time") != std::string::npos);
  }
}
