// A scripted fly-through of a QNV tileset in the window under Xvfb (issue 13, "viewer
// memory stays under its budget during a scripted fly-through"; docs/tilesets.md): a VRML
// world binds four Viewpoints in turn, each looking into one quarter of a 64^3 ball's box,
// then the first again, with --tileset-memory well under the whole tileset. After each
// view has loaded, the script's `status` line of the tileset gives its decoded vectors
// now and at most so far: they never exceed the budget, bricks are dropped as the view
// moves, and the first view's bricks are fetched again when it comes back.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "process.hpp"
#include "qnv/tileset.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

namespace fs = std::filesystem;

namespace {

struct TilesetStatus {
  std::uint64_t resident = 0, peak = 0, evicted = 0, requests = 0, bytes = 0, chosen = 0;
  bool found = false;
};

/// The "tileset ..." line of a status file (app/window_script.hpp).
TilesetStatus tilesetStatus(const fs::path& file) {
  std::ifstream in(file);
  TilesetStatus s;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line);
    std::string tag, url, k1, k2, k3, k4, k5, k6;
    if (!(words >> tag >> url) || tag != "tileset") continue;
    s.found = static_cast<bool>(words >> k1 >> s.resident >> k2 >> s.peak >> k3 >> s.evicted >>
                                k4 >> s.requests >> k5 >> s.bytes >> k6 >> s.chosen);
  }
  return s;
}

}  // namespace

TEST_CASE("a scripted fly-through keeps a tileset's decoded vectors under --tileset-memory",
          "[heavy][app][window][tileset]") {
  gs::test::Xvfb xvfb;
  if (gs::test::skipWithoutXvfb(xvfb)) return;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "tileset-flythrough";
  fs::create_directories(dir);
  // A 64^3 ball whose gradient grows towards its centre (as in test_tileset.cpp), as a
  // depth-2 tileset of 16-voxel leaves.
  const fs::path raw = dir / "ball64.raw", tileset = dir / "ball64";
  {
    std::string v(64 * 64 * 64, '\0');
    for (int z = 0; z < 64; ++z)
      for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
          const double r = std::hypot(x - 32.0, y - 32.0, z - 32.0) / 32.0;
          v[static_cast<std::size_t>((z * 64 + y) * 64 + x)] = static_cast<char>(
              static_cast<unsigned char>(std::clamp(180.0 * (1.2 - r) * (1.2 - r), 0.0, 255.0)));
        }
    std::ofstream(raw, std::ios::binary) << v;
  }
  fs::remove_all(tileset);
  auto encoded =
      gs::test::runGhostspace({"encode", raw.string(), "--raw-dims", "64,64,64", "--no-progress",
                               "--tileset", tileset.string() + "/", "--brick-voxels", "16"});
  INFO(encoded.err);
  REQUIRE(encoded.exitCode == 0);
  std::string error;
  const auto index =
      gs::qnv::parseTilesetIndex(gs::test::readBytes(tileset / "index.qnvt"), "index.qnvt", error);
  INFO(error);
  REQUIRE(index);
  // A budget of a third of the whole tileset's decoded vectors (32 bytes each).
  const std::uint64_t total = index->header.vectorCount;
  const std::uint64_t budgetVectors = total / 3;
  const double budgetMb = static_cast<double>(budgetVectors * 32) / 1048576.0;

  // Four views from z = -12 looking along +z, each at the middle of one quarter of x, y.
  const fs::path world = dir / "fly.wrl", script = dir / "fly.script";
  {
    std::ofstream w(world);
    w << "#VRML V2.0 utf8\n";
    for (const auto& [vx, vy] : {std::pair{16, 16}, {48, 16}, {48, 48}, {16, 48}})
      w << "Viewpoint { position " << vx << " " << vy
        << " -12 orientation 0 1 0 3.14159265 fieldOfView 0.6 }\n";
    w << "QuantizedNormalVectors { url \"ball64/index.qnvt\" }\n";
  }
  std::vector<fs::path> statuses;
  {
    std::ofstream s(script);
    s << "wait-loaded\n";
    for (int v : {0, 1, 2, 3, 0}) {
      statuses.push_back(dir / ("status-" + std::to_string(statuses.size()) + ".txt"));
      s << "viewpoint " << v << "\nframes 2\nwait-loaded\nstatus " << statuses.back().string()
        << "\n";
    }
    s << "quit\n";
  }
  const std::ostringstream mb = [&] {
    std::ostringstream o;
    o.precision(17);
    o << budgetMb;
    return o;
  }();
  auto r = gs::test::runGhostspace({"--size", "320x240", "--new-instance", "--tileset-memory",
                                    mb.str(), "--script", script.string(), world.string()},
                                   {"DISPLAY=" + xvfb.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  std::vector<TilesetStatus> at;
  for (const fs::path& p : statuses) {
    at.push_back(tilesetStatus(p));
    const TilesetStatus& s = at.back();
    INFO(p.filename().string() << ": resident " << s.resident << " peak " << s.peak << " evicted "
                               << s.evicted << " requests " << s.requests << " bytes " << s.bytes
                               << " chosen " << s.chosen << " of " << total << ", budget "
                               << budgetVectors);
    REQUIRE(s.found);
    CHECK(s.resident > 0);
    CHECK(s.peak <= budgetVectors);
    CHECK(s.chosen > 0);
  }
  // Each view alone fits; the four together do not: bricks were dropped on the way.
  CHECK(at[0].evicted == 0);
  CHECK(at[3].evicted > 0);
  // Back at the first view: some of its bricks were dropped and are fetched again.
  CHECK(at[4].requests > at[3].requests);
  CHECK(at[4].bytes > at[3].bytes);
  CHECK(at[4].evicted >= at[3].evicted);
}
