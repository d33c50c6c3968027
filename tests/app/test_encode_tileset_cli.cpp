// `ghostspace encode --tileset` and `ghostspace tileset index` end to end: a split run
// merged is byte-identical to the single run, its merged levels included (docs/qnv-format.md,
// "Tilesets").
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>

#include "process.hpp"
#include "qnv/tileset.hpp"
#include "test_support.hpp"

using gs::test::runGhostspace;
namespace fs = std::filesystem;

namespace {

// Every file under `dir` by relative path, with its bytes.
std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = gs::test::readBytes(entry.path());
  return files;
}

std::vector<std::string> args(std::vector<std::string> first,
                              const std::vector<std::string>& more) {
  first.insert(first.end(), more.begin(), more.end());
  return first;
}

// Encodes `input` whole and in `n` shares (run in the order given), merges, and compares.
void checkSplitMatchesSingle(const std::string& input, const std::vector<std::string>& options,
                             const std::vector<std::uint32_t>& order) {
  gs::test::TempDir dir("tileset");
  const fs::path single = dir.path / "single", split = dir.path / "split";
  const auto whole = runGhostspace(
      args({"encode", input, "--tileset", single.string(), "--no-progress"}, options));
  INFO(whole.err);
  REQUIRE(whole.exitCode == 0);
  CHECK_THAT(whole.out, Catch::Contains("bricks ("));
  const std::string n = std::to_string(order.size());
  for (std::uint32_t i : order) {
    const auto share = runGhostspace(args({"encode", input, "--tileset", split.string(), "--bricks",
                                           std::to_string(i) + "/" + n, "--no-progress"},
                                          options));
    INFO(share.err);
    REQUIRE(share.exitCode == 0);
    CHECK_THAT(share.out, Catch::Contains("share " + std::to_string(i) + " of " + n));
  }
  CHECK_FALSE(fs::exists(split / "index.qnvt"));
  const auto merge = runGhostspace({"tileset", "index", split.string()});
  INFO(merge.err);
  REQUIRE(merge.exitCode == 0);
  CHECK_FALSE(fs::exists(split / "parts"));
  const auto a = tree(single), b = tree(split);
  CHECK(a.size() > 2);
  REQUIRE(a.size() == b.size());
  for (const auto& [path, bytes] : a) {
    INFO(path);
    REQUIRE(b.count(path));
    CHECK(b.at(path) == bytes);
  }
  std::string error;
  const auto index = gs::qnv::parseTilesetIndex(a.at("index.qnvt"), "index.qnvt", error);
  REQUIRE(index);
  // Bricks, the index, and a merged brick (docs/tilesets.md, "Merged levels") beside each
  // interior brick, all byte for byte the same from the shares.
  CHECK(index->mergedCellsLog2 > 0);
  std::size_t interior = 0;
  for (const gs::qnv::TilesetBrick& brick : index->bricks)
    if (index->hasMerged(brick.level)) {
      ++interior;
      CHECK(a.count(brick.mergedPath()) == 1);
    }
  CHECK(interior > 0);
  CHECK(index->bricks.size() + 1 + interior == a.size());
}

}  // namespace

TEST_CASE("a volume tileset split into 3 shares merges to the single run's bytes",
          "[app][encode][tileset]") {
  const std::string sphere = (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string();
  checkSplitMatchesSingle(sphere,
                          {"--brick-voxels", "2", "--brick-vectors", "16", "--packet-bytes", "64",
                           "--coding", "entropy"},
                          {0, 1, 2});
  checkSplitMatchesSingle(
      sphere, {"--brick-voxels", "3", "--brick-vectors", "64", "--fraction", "0.5"}, {2, 0, 1});
}

TEST_CASE("a mesh tileset split into 3 shares merges to the single run's bytes",
          "[app][encode][tileset]") {
  const std::string world = (gs::test::sourceDir() / "assets/worlds/welcome.wrl").string();
  checkSplitMatchesSingle(world, {"--brick-vectors", "8", "--coding", "compact"}, {1, 2, 0});
}

TEST_CASE("tileset encodes and merges refuse bad options and missing shares",
          "[app][encode][tileset]") {
  gs::test::TempDir dir("tileset");
  const std::string sphere = (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string();
  const std::string out = (dir.path / "t").string();
  auto r = runGhostspace({"encode", sphere, "--tileset", out, "--bricks", "3/3"});
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.err, Catch::Contains("--bricks: expected I/N"));
  r = runGhostspace({"encode", sphere, "--tileset", out, "-o", out + ".qnv"});
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.err, Catch::Contains("either -o OUT.qnv or --tileset OUT/"));
  r = runGhostspace({"encode", sphere, "-o", out + ".qnv", "--bricks", "0/2"});
  CHECK(r.exitCode == 2);
  r = runGhostspace({"encode", sphere, "--tileset", out, "--bricks", "0/2", "--brick-voxels", "2",
                     "--no-progress"});
  REQUIRE(r.exitCode == 0);
  r = runGhostspace({"tileset", "index", out});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("share 1 of 2 is missing"));
  r = runGhostspace({"encode", sphere, "--tileset", out, "--bricks", "1/2", "--brick-voxels", "4",
                     "--no-progress"});
  REQUIRE(r.exitCode == 0);
  r = runGhostspace({"tileset", "index", out});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("comes from another encode"));
  r = runGhostspace({"tileset", "index", (dir.path / "none").string()});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("holds no shares to merge"));
}

TEST_CASE("info on a tileset gives its bounds, vectors, bricks and levels", "[app][tileset]") {
  // Issue 42, friction 7: it said "bounding box: empty, triangles: 0".
  const fs::path golden = gs::test::sourceDir() / "tests/qnv/golden/tileset_blob";
  for (const fs::path& input : {golden / "index.qnvt", golden}) {
    const auto r = runGhostspace({"info", input.string()});
    INFO(r.out << r.err);
    CHECK(r.exitCode == 0);
    CHECK(r.out.find("QNV tileset, volume") != std::string::npos);
    CHECK(r.out.find("vectors     120 in 23 bricks, depth 2") != std::string::npos);
    CHECK(r.out.find("level 2") != std::string::npos);
    CHECK(r.out.find("triangles") == std::string::npos);
  }
}
