// `ghostspace encode VOLUME --tileset OUT/ --memory MB`: the out-of-core tileset encode
// gives the in-memory tileset encode's files byte for byte (keep all, --fraction with ties
// at the threshold, --count, --window), spills under a tiny bound, and split runs merge
// to the single run's bytes; inputs made at test time as a multi-file NRRD and a folder
// of PNG slices (docs/out-of-core.md, "Tileset encoding"). The same for a Gaussian
// splatting scene (.ply, .splat, .compressed.ply, .spz, SOG and glTF read piecewise), and its
// errors.
#include <catch2/catch.hpp>

#include <png.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include "process.hpp"
#include "qnv/tileset.hpp"
#include "test_support.hpp"

using gs::test::runGhostspace;
namespace fs = std::filesystem;

namespace {

constexpr std::uint32_t kX = 21, kY = 17, kZ = 23;

// Integer samples (a ball, a slab and hashed noise), so that many gradient magnitudes
// tie exactly and the selection's tie rule is exercised.
std::uint16_t sample(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  const int dx = static_cast<int>(x) - 9, dy = static_cast<int>(y) - 8,
            dz = static_cast<int>(z) - 12;
  int v = dx * dx + dy * dy + dz * dz < 40 ? 900 : 100;
  if (z > 17 && x < 10) v += 300;
  const std::uint32_t h = (x * 73856093u) ^ (y * 19349663u) ^ (z * 83492791u);
  return static_cast<std::uint16_t>(v + 2 * static_cast<int>(h % 3));
}

// A detached NRRD header naming one raw file per slice (teem's "data file: FORMAT MIN MAX
// STEP" form), little-endian uint16.
fs::path writeMultiFileNrrd(const fs::path& dir) {
  fs::create_directories(dir);
  for (std::uint32_t z = 0; z < kZ; ++z) {
    char name[32];
    std::snprintf(name, sizeof name, "slice_%03u.raw", z);
    std::ofstream out(dir / name, std::ios::binary);
    for (std::uint32_t y = 0; y < kY; ++y)
      for (std::uint32_t x = 0; x < kX; ++x) {
        const std::uint16_t v = sample(x, y, z);
        const char bytes[2] = {static_cast<char>(v & 0xff), static_cast<char>(v >> 8)};
        out.write(bytes, 2);
      }
  }
  const fs::path header = dir / "volume.nhdr";
  std::ofstream out(header);
  out << "NRRD0004\ntype: uint16\ndimension: 3\nsizes: " << kX << " " << kY << " " << kZ
      << "\nspacings: 1 0.8 1.5\nencoding: raw\nendian: little\n"
      << "data file: slice_%03d.raw 0 " << kZ - 1 << " 1\n";
  return header;
}

// One 16-bit grey PNG per slice in `dir`.
void writePngStack(const fs::path& dir) {
  fs::create_directories(dir);
  for (std::uint32_t z = 0; z < kZ; ++z) {
    const fs::path path = dir / ("ct" + std::to_string(z) + ".png");
    std::FILE* f = std::fopen(path.string().c_str(), "wb");
    REQUIRE(f);
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, kX, kY, 16, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    png_write_info(png, info);
    std::vector<png_byte> row;
    for (std::uint32_t y = 0; y < kY; ++y) {
      row.clear();
      for (std::uint32_t x = 0; x < kX; ++x) {
        const std::uint16_t v = sample(x, y, z);
        row.push_back(static_cast<png_byte>(v >> 8));
        row.push_back(static_cast<png_byte>(v & 0xff));
      }
      png_write_row(png, row.data());
    }
    png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
  }
}

std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = gs::test::readBytes(entry.path());
  return files;
}

void checkSameTree(const fs::path& a, const fs::path& b) {
  const auto x = tree(a), y = tree(b);
  CHECK(x.size() > 2);
  CHECK(x.count("index.qnvt") == 1);
  REQUIRE(x.size() == y.size());
  for (const auto& [path, bytes] : x) {
    INFO(path);
    REQUIRE(y.count(path));
    CHECK(y.at(path) == bytes);
  }
}

gs::test::ProcessResult encode(const std::string& input, const fs::path& out,
                               std::vector<std::string> more) {
  std::vector<std::string> args = {"encode", input, "--tileset", out.string(), "--no-progress"};
  args.insert(args.end(), more.begin(), more.end());
  auto r = runGhostspace(args);
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  return r;
}

std::vector<std::string> with(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

TEST_CASE("an out-of-core volume tileset is the in-memory tileset, byte for byte",
          "[heavy][app][encode][tileset][ooc]") {
  gs::test::TempDir dir("ooc");
  const std::string nrrd = writeMultiFileNrrd(dir.path / "nrrd").string();
  const std::vector<std::vector<std::string>> cases = {
      {"--brick-voxels", "4", "--brick-vectors", "32"},
      {"--brick-voxels", "5", "--brick-vectors", "64", "--fraction", "0.3", "--coding", "entropy",
       "--packet-bytes", "128"},
      {"--brick-voxels", "8", "--brick-vectors", "16", "--count", "777", "--magnitude", "linear"},
      {"--brick-voxels", "3", "--brick-vectors", "40", "--window", "500:1300", "--fraction",
       "0.05"},
  };
  int n = 0;
  for (const auto& options : cases) {
    const fs::path memory = dir.path / ("memory" + std::to_string(n));
    const fs::path ooc = dir.path / ("ooc" + std::to_string(n));
    const fs::path tiny = dir.path / ("tiny" + std::to_string(n++));
    encode(nrrd, memory, options);
    const auto r = encode(nrrd, ooc, with(options, {"--memory", "64", "--threads", "3"}));
    CHECK_THAT(r.out, Catch::Contains("out of core"));
    checkSameTree(memory, ooc);
    // 20 KB: one slice per slab, every leaf and interior contribution spilled.
    const auto t = encode(nrrd, tiny, with(options, {"--memory", "0.02", "--threads", "2"}));
    CHECK_THAT(t.out, Catch::Contains("(1 per slab)"));
    CHECK_THAT(t.out, !Catch::Contains("spilled 0 + 0 bytes"));
    checkSameTree(memory, tiny);
  }
}

TEST_CASE("an out-of-core tileset split into 3 shares merges to the single run's bytes",
          "[app][encode][tileset][ooc]") {
  gs::test::TempDir dir("ooc");
  writePngStack(dir.path / "png");
  const std::string stack = (dir.path / "png").string();
  const std::vector<std::string> options = {"--brick-voxels", "4",   "--brick-vectors", "24",
                                            "--fraction",     "0.4", "--memory",        "0.05"};
  const fs::path single = dir.path / "single", split = dir.path / "split";
  encode(stack, single, options);
  for (std::uint32_t i : {2u, 0u, 1u}) {
    const auto r = encode(stack, split, with(options, {"--bricks", std::to_string(i) + "/3"}));
    CHECK_THAT(r.out, Catch::Contains("share " + std::to_string(i) + " of 3"));
  }
  const auto merge = runGhostspace({"tileset", "index", split.string()});
  INFO(merge.err);
  REQUIRE(merge.exitCode == 0);
  checkSameTree(single, split);
  // The PNG stack holds the NRRD's samples: the same tileset but for the spacing.
  const fs::path memory = dir.path / "memory";
  encode(stack, memory, {"--brick-voxels", "4", "--brick-vectors", "24", "--fraction", "0.4"});
  checkSameTree(single, memory);
}

TEST_CASE("encode refuses --memory without a tileset and for worlds",
          "[app][encode][tileset][ooc]") {
  gs::test::TempDir dir("ooc");
  const std::string sphere = (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string();
  auto r = runGhostspace({"encode", sphere, "-o", (dir.path / "a.qnv").string(), "--memory", "64"});
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.err, Catch::Contains("--memory MB needs --tileset"));
  const std::string world = (gs::test::sourceDir() / "assets/worlds/welcome.wrl").string();
  r = runGhostspace(
      {"encode", world, "--tileset", (dir.path / "t").string(), "--memory", "64", "--no-progress"});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("volumes, PLY meshes and Gaussian splatting scenes"));
}

namespace {

// A binary little-endian INRIA .ply of `count` Gaussians (SH degree 0) at pseudo-random
// places in a unit cube, each of peak opacity sigmoid(`opacityLogit`).
fs::path writeGaussianPly(const fs::path& path, std::uint32_t count, float opacityLogit) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << count << "\n";
  for (const char* p : {"x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0",
                        "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"})
    out << "property float " << p << "\n";
  out << "end_header\n";
  std::uint32_t state = 12345;
  const auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return static_cast<float>(state >> 8) / 16777216.0f;
  };
  for (std::uint32_t i = 0; i < count; ++i) {
    const float row[14] = {next(),         next(),        next(),       next() - 0.5f,
                           next() - 0.5f,  next() - 0.5f, opacityLogit, -4.0f - next(),
                           -4.0f - next(), -5.0f,         1.0f,         next() * 0.1f,
                           0.0f,           0.0f};
    out.write(reinterpret_cast<const char*>(row), sizeof row);  // little-endian hosts
  }
  return path;
}

// The bytes "spilled A + B bytes" of an out-of-core Gaussian encode's summary line.
std::pair<long long, long long> spilled(const std::string& out) {
  const std::size_t at = out.find("spilled ");
  REQUIRE(at != std::string::npos);
  long long a = -1, b = -1;
  REQUIRE(std::sscanf(out.c_str() + at, "spilled %lld + %lld", &a, &b) == 2);
  return {a, b};
}

}  // namespace

TEST_CASE("an out-of-core Gaussian tileset is the in-memory tileset, byte for byte",
          "[app][encode][tileset][ooc][splat]") {
  gs::test::TempDir dir("ooc_gaussian");
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  // Depth 2 (K = 64 of 3,000 splats), merged levels at the scene's default and at 8^3;
  // depth 3 (K = 8) with 32^3 cells, whose level 2 lies below qnv::deepestMergedLevel (1):
  // merged bricks at every interior level all the same (kTilesetMergedEveryLevel).
  for (const char* scene : {"bunny_small.ply", "bunny_small.splat"}) {
    for (const std::vector<std::string>& options :
         {std::vector<std::string>{"--brick-vectors", "64"},
          std::vector<std::string>{"--brick-vectors", "64", "--merged-cells", "8", "--sh-bits", "3",
                                   "--sh-full", "0.25"},
          std::vector<std::string>{"--brick-vectors", "8", "--merged-cells", "32"}}) {
      const std::string input = (data / scene).string();
      INFO(scene << " " << options.size());
      const fs::path memory = dir.path / "memory", ooc = dir.path / "ooc", tiny = dir.path / "tiny";
      encode(input, memory, options);
      const auto r = encode(input, ooc, with(options, {"--memory", "64"}));
      // The merged levels are summed from the leaves' buckets: no third pass.
      CHECK_THAT(r.out, Catch::Contains("2 passes over the scene"));
      if (options[1] == "8") {
        CHECK_THAT(r.out, Catch::Contains("depth 3"));
        CHECK(fs::is_directory(ooc / "merged/2"));
        std::string error;
        const auto index =
            gs::qnv::parseTilesetIndex(gs::test::readBytes(ooc / "index.qnvt"), "index", error);
        REQUIRE(index);
        CHECK(index->mergedEveryLevel);
        for (const gs::qnv::TilesetBrick& b : index->bricks)
          if (b.level < 3) CHECK(fs::is_regular_file(ooc / b.mergedPath()));
      }
      CHECK(spilled(r.out) == std::pair<long long, long long>{0, 0});
      checkSameTree(memory, ooc);
      // A bound far below the scene's 300 KB: leaves and interior nodes spilled.
      const auto t = encode(input, tiny, with(options, {"--memory", "0.01"}));
      CHECK(spilled(t.out).first > 0);
      CHECK(spilled(t.out).second > 0);
      checkSameTree(memory, tiny);
      CHECK_FALSE(fs::exists(tiny / "parts"));  // the spill files and their folder gone
    }
  }
  // 20,000 splats and no --brick-vectors: both encodes pick K = 2048, a 2-deep octree
  // (splats::defaultGaussianBrickVectors).
  {
    const std::string scene = writeGaussianPly(dir.path / "cube.ply", 20000, 2.0f).string();
    const fs::path memory = dir.path / "cube_memory", ooc = dir.path / "cube_ooc";
    const auto m = encode(scene, memory, {});
    CHECK_THAT(m.out, Catch::Contains("depth 2"));
    const auto o = encode(scene, ooc, {"--memory", "0.5"});
    CHECK_THAT(o.out, Catch::Contains("kept 20000, K 2048"));
    checkSameTree(memory, ooc);
  }
  // Shares under --memory, given out of order, merge to the unsplit run's files.
  const std::string ply = (data / "bunny_small.ply").string();
  const fs::path memory = dir.path / "memory3", split = dir.path / "split";
  encode(ply, memory, {"--brick-vectors", "64"});
  for (const char* share : {"2/3", "0/3", "1/3"})
    encode(ply, split, {"--brick-vectors", "64", "--memory", "0.01", "--bricks", share});
  const auto m = runGhostspace({"tileset", "index", split.string()});
  INFO(m.err);
  REQUIRE(m.exitCode == 0);
  checkSameTree(memory, split);
}

TEST_CASE("an out-of-core Gaussian tileset of SPZ SOG and compressed PLY is the in-memory one",
          "[app][encode][tileset][ooc][splat]") {
  gs::test::TempDir dir("ooc_gaussian_compressed");
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  for (const char* scene : {"bunny_small.compressed.ply", "bunny_small.spz", "bunny_small_v3.spz",
                            "bunny_small.sog", "bunny_small_sog/meta.json", "bunny_small.glb"}) {
    INFO(scene);
    const std::string input = (data / scene).string();
    const fs::path memory = dir.path / "memory", ooc = dir.path / "ooc";
    encode(input, memory, {"--brick-vectors", "64"});
    // A bound far below the scene: leaves and interior nodes spilled.
    const auto r = encode(input, ooc, {"--brick-vectors", "64", "--memory", "0.01"});
    CHECK(spilled(r.out).first > 0);
    checkSameTree(memory, ooc);
  }
}

TEST_CASE("an out-of-core Gaussian encode refuses other formats and reports a short file",
          "[app][encode][tileset][ooc][splat]") {
  gs::test::TempDir dir("ooc_gaussian_bad");
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  // An ascii PLY is read whole: a usage error that says which formats are read piecewise.
  const fs::path ascii = dir.path / "ascii.ply";
  std::ofstream(ascii) << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float y\nproperty float z\nproperty float f_dc_0\n"
                          "property float f_dc_1\nproperty float f_dc_2\nproperty float "
                          "opacity\nproperty float scale_0\nproperty float scale_1\nproperty "
                          "float scale_2\nproperty float rot_0\nproperty float rot_1\nproperty "
                          "float rot_2\nproperty float rot_3\nend_header\n0 0 0 1 1 1 5 -3 -3 -3 "
                          "1 0 0 0\n";
  auto r = runGhostspace({"encode", ascii.string(), "--tileset", (dir.path / "ascii").string(),
                          "--memory", "64", "--no-progress"});
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.err, Catch::Contains("read piecewise are binary INRIA .ply, .compressed.ply, "
                                    ".splat, .spz, SOG and glTF, not an ascii PLY"));
  CHECK_FALSE(fs::exists(dir.path / "ascii" / "index.qnvt"));
  // A PLY cut short: its header promises 3,000 rows. An error value, nothing published.
  const std::string bytes = gs::test::readBytes(data / "bunny_small.ply");
  const fs::path cut = dir.path / "cut.ply";
  std::ofstream(cut, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  r = runGhostspace({"encode", cut.string(), "--tileset", (dir.path / "cut").string(), "--memory",
                     "64", "--no-progress"});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("cut.ply: expected"));
  CHECK_FALSE(fs::exists(dir.path / "cut" / "index.qnvt"));
  // Nothing kept (every splat nearly transparent): a usage error (2, as in memory), and
  // the tileset already in OUT/ is left as it was.
  const fs::path kept = dir.path / "kept";
  encode((data / "bunny_small.ply").string(), kept, {"--memory", "64"});
  const std::string before = gs::test::readBytes(kept / "index.qnvt");
  const std::string faint = writeGaussianPly(dir.path / "faint.ply", 100, -20.0f).string();
  r = runGhostspace(
      {"encode", faint, "--tileset", kept.string(), "--memory", "64", "--no-progress"});
  CHECK(r.exitCode == 2);
  CHECK_THAT(r.err, Catch::Contains("nothing to encode"));
  CHECK(gs::test::readBytes(kept / "index.qnvt") == before);
  CHECK_FALSE(fs::exists(kept / "parts"));
  // A .splat of a size that is not whole records.
  const fs::path odd = dir.path / "odd.splat";
  std::ofstream(odd, std::ios::binary).write("0123456789", 10);
  r = runGhostspace({"encode", odd.string(), "--tileset", (dir.path / "odd").string(), "--memory",
                     "64", "--no-progress"});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("multiple of 32 bytes"));
}
