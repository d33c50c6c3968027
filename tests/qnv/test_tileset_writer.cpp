// Building tilesets: the octree, the per-leaf quota assignment, per-brick quantization,
// the split into shares and their merge, and the frozen golden tileset
// (docs/qnv-format.md, "Tilesets").
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "qnv/decoder.hpp"
#include "qnv/error.hpp"
#include "qnv/tileset_writer.hpp"
#include "test_support.hpp"

using namespace gs::qnv;

namespace {

// A 6x5x4 volume with a smooth blob: every voxel has a distinct gradient.
Volume blobVolume() {
  Volume v;
  v.dims = {6, 5, 4};
  v.spacing = {1.0f, 1.5f, 2.0f};
  v.origin = {-1, 0, 3};
  for (std::uint32_t z = 0; z < 4; ++z)
    for (std::uint32_t y = 0; y < 5; ++y)
      for (std::uint32_t x = 0; x < 6; ++x)
        v.samples.push_back(100.0f *
                            std::exp(-0.1f * ((x - 2.2f) * (x - 2.2f) + (y - 1.7f) * (y - 1.7f) +
                                              (z - 1.3f) * (z - 1.3f))));
  return v;
}

// A grid of 400 small triangles of distinct areas over a 10 x 10 x 4 box.
TriangleMesh scatterMesh() {
  TriangleMesh m;
  std::mt19937 random(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int t = 0; t < 400; ++t) {
    const glm::vec3 p(10 * u(random), 10 * u(random), 4 * u(random));
    const float s = 0.05f + 0.001f * static_cast<float>(t);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {p, p + glm::vec3(s, 0, 0), p + glm::vec3(0, s, s)});
    m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
  }
  return m;
}

TilesetOptions goldenOptions() {
  TilesetOptions o;
  o.brickVoxels = 2;
  o.brickVectors = 4;
  o.write = {16, PacketEncoding::plain};
  return o;
}

std::vector<DecodedVector> decodeBrick(const BrickFile& brick) {
  StreamDecoder decoder("brick");
  std::vector<DecodedVector> out;
  const auto sink = [&](std::uint64_t, std::span<const DecodedVector> v) {
    out.insert(out.end(), v.begin(), v.end());
  };
  REQUIRE(decoder.feed(brick.bytes, sink));
  CHECK(decoder.finish(sink));
  return out;
}

// Runs shares 0..n-1 over `selected` in the given vector order, serializing each share's
// interior parts, then merges: the files an N-way split run leaves.
TilesetFiles splitRun(const SelectedVectors& selected, const TilesetOptions& options,
                      std::uint32_t n) {
  const TilesetLayout layout(selected.header, options);
  std::vector<BrickFile> bricks;
  std::vector<InteriorParts> parts;
  for (std::uint32_t share = 0; share < n; ++share) {
    TilesetShareWriter writer(layout, share, n);
    for (const SourceVector& v : selected.vectors) writer.add(v);
    for (const glm::uvec3& leaf : writer.openLeaves())
      if (auto brick = writer.finishLeaf(leaf)) bricks.push_back(std::move(*brick));
    std::string error;
    TilesetOptions cut;
    auto parsed = parseInteriorParts(serializeInteriorParts(writer.interior(), options),
                                     "interior.qnvp", cut, error);
    REQUIRE(parsed);
    CHECK(cut.brickVoxels == options.brickVoxels);
    parts.push_back(std::move(*parsed));
  }
  for (BrickFile& b : mergeInteriorParts(parts, layout)) bricks.push_back(std::move(b));
  std::vector<TilesetBrick> records;
  for (const BrickFile& b : bricks) records.push_back(b.brick);
  TilesetFiles files;
  files.index = assembleTilesetIndex(layout, records);
  std::sort(bricks.begin(), bricks.end(), [](const BrickFile& a, const BrickFile& b) {
    return std::make_tuple(a.brick.level, a.brick.z, a.brick.y, a.brick.x) <
           std::make_tuple(b.brick.level, b.brick.z, b.brick.y, b.brick.x);
  });
  files.bricks = std::move(bricks);
  return files;
}

void requireSameFiles(const TilesetFiles& a, const TilesetFiles& b) {
  CHECK(serializeTilesetIndex(a.index) == serializeTilesetIndex(b.index));
  REQUIRE(a.bricks.size() == b.bricks.size());
  for (std::size_t i = 0; i < a.bricks.size(); ++i) CHECK(a.bricks[i].bytes == b.bricks[i].bytes);
}

std::filesystem::path goldenDir() {
  return gs::test::sourceDir() / "tests/qnv/golden/tileset_blob";
}

}  // namespace

TEST_CASE("a volume tileset holds exactly the single stream's vectors", "[qnv][tileset]") {
  const SelectedVectors selected = selectVolumeVectors(blobVolume(), {});
  const TilesetFiles files = buildTileset(selected, goldenOptions());
  CHECK(files.index.depth == 2);  // 2^2 * 2 >= 6
  std::string error;
  const auto parsed = parseTilesetIndex(serializeTilesetIndex(files.index), "index.qnvt", error);
  REQUIRE(parsed);
  CHECK(parsed->header.vectorCount == selected.vectors.size());
  CHECK(parsed->header.volumeDims == glm::uvec3(6, 5, 4));
  std::uint64_t total = 0;
  for (const BrickFile& b : files.bricks) {
    const std::vector<DecodedVector> v = decodeBrick(b);
    REQUIRE(v.size() == b.brick.vectorCount);
    total += v.size();
    for (const DecodedVector& d : v) {
      // Voxel-grid positions are exact: every vector sits on a voxel centre in its box.
      for (int a = 0; a < 3; ++a) {
        CHECK(d.position[a] >= b.brick.boundsMin[a] - 1e-4f);
        CHECK(d.position[a] <= b.brick.boundsMax[a] + 1e-4f);
      }
    }
    // Largest A first inside each brick.
    for (std::size_t i = 1; i < v.size(); ++i) CHECK(v[i - 1].magnitude >= v[i].magnitude);
    CHECK(b.bytes.size() == b.brick.fileBytes);
  }
  CHECK(total == selected.vectors.size());
  // The root brick is the strongest sample: its largest vector is the global maximum.
  REQUIRE(files.bricks.front().brick.level == 0);
  CHECK(decodeBrick(files.bricks.front()).front().magnitude ==
        Approx(selected.header.magnitudeMax).epsilon(1e-3));
}

TEST_CASE("the per-leaf quotas give coarse levels an even magnitude-first sample",
          "[qnv][tileset]") {
  SurfaceEncodeOptions o;
  const SelectedVectors selected = selectSurfaceVectors(scatterMesh(), o);
  TilesetOptions options;
  options.brickVectors = 16;
  const TilesetLayout layout(selected.header, options);
  REQUIRE(layout.depth() == 2);  // 8 * 16 < 400 <= 64 * 16
  CHECK(layout.quota(0) == 1);   // ceil(16 / 64)
  CHECK(layout.quota(1) == 2);   // ceil(16 / 8)
  // Brute force: rank each leaf, count what goes up.
  std::map<std::uint64_t, std::vector<SourceVector>> leaves;
  for (const SourceVector& v : selected.vectors)
    leaves[layout.leafIndex(layout.leafOf(v))].push_back(v);
  std::uint64_t root = 0, level1 = 0, rest = 0;
  std::vector<std::uint64_t> rootSources;
  for (auto& [index, v] : leaves) {
    std::sort(v.begin(), v.end(), [](const SourceVector& a, const SourceVector& b) {
      return a.magnitude > b.magnitude || (a.magnitude == b.magnitude && a.source < b.source);
    });
    root += 1;
    rootSources.push_back(v[0].source);
    level1 += std::min<std::size_t>(2, v.size() - 1);
    rest += v.size() - 1 - std::min<std::size_t>(2, v.size() - 1);
  }
  const TilesetFiles files = buildTileset(selected, options);
  std::uint64_t got[3] = {0, 0, 0};
  for (const BrickFile& b : files.bricks) got[b.brick.level] += b.brick.vectorCount;
  CHECK(got[0] == root);
  CHECK(got[1] == level1);
  CHECK(got[2] == rest);
  TilesetShareWriter writer(layout);
  for (const SourceVector& v : selected.vectors) writer.add(v);
  for (const glm::uvec3& leaf : writer.openLeaves()) (void)writer.finishLeaf(leaf);
  std::vector<std::uint64_t> sources;
  for (const InteriorEntry& e : writer.interior().at(TilesetCell{})) sources.push_back(e.source);
  std::sort(sources.begin(), sources.end());
  std::sort(rootSources.begin(), rootSources.end());
  CHECK(sources == rootSources);
}

TEST_CASE("a tileset does not depend on the order vectors arrive in", "[qnv][tileset]") {
  SelectedVectors selected = selectSurfaceVectors(scatterMesh(), {});
  TilesetOptions options;
  options.brickVectors = 16;
  options.write = {64, PacketEncoding::entropy};
  const TilesetFiles first = buildTileset(selected, options);
  std::mt19937 random(3);
  std::shuffle(selected.vectors.begin(), selected.vectors.end(), random);
  requireSameFiles(first, buildTileset(selected, options));
}

TEST_CASE("a tileset split into shares merges to the unsplit one", "[qnv][tileset]") {
  const SelectedVectors volume = selectVolumeVectors(blobVolume(), {});
  for (std::uint32_t n : {1u, 2u, 3u, 7u, 40u})
    requireSameFiles(buildTileset(volume, goldenOptions()), splitRun(volume, goldenOptions(), n));
  const SelectedVectors mesh = selectSurfaceVectors(scatterMesh(), {});
  TilesetOptions options;
  options.brickVectors = 16;
  options.write = {48, PacketEncoding::compact};
  for (std::uint32_t n : {2u, 3u, 5u})
    requireSameFiles(buildTileset(mesh, options), splitRun(mesh, options, n));
}

TEST_CASE("a finished leaf takes no more vectors", "[qnv][tileset]") {
  const SelectedVectors selected = selectVolumeVectors(blobVolume(), {});
  const TilesetLayout layout(selected.header, goldenOptions());
  TilesetShareWriter writer(layout);
  const glm::uvec3 leaf = layout.leafOf(selected.vectors.front());
  (void)writer.finishLeaf(leaf);
  CHECK_THROWS_AS(writer.add(selected.vectors.front()), InputError);
  CHECK_THROWS_AS(TilesetShareWriter(layout, 3, 3), InputError);
}

TEST_CASE("the encoder reproduces the golden tileset byte for byte", "[qnv][tileset][golden]") {
  const TilesetFiles files = buildTileset(selectVolumeVectors(blobVolume(), {}), goldenOptions());
  const std::string index = serializeTilesetIndex(files.index);
  if (std::getenv("GS_WRITE_GOLDEN")) {
    std::filesystem::remove_all(goldenDir());
    for (const BrickFile& b : files.bricks) {
      std::filesystem::create_directories((goldenDir() / b.brick.path()).parent_path());
      std::ofstream(goldenDir() / b.brick.path(), std::ios::binary) << b.bytes;
    }
    std::ofstream(goldenDir() / "index.qnvt", std::ios::binary) << index;
  }
  CHECK(gs::test::readBytes(goldenDir() / "index.qnvt") == index);
  CHECK(gs::test::filesWithSuffix(goldenDir(), ".qnv").size() == files.bricks.size());
  for (const BrickFile& b : files.bricks)
    CHECK(gs::test::readBytes(goldenDir() / b.brick.path()) == b.bytes);
  // Pinned facts of the golden tileset: depth 2, 96 vectors (every voxel of the blob).
  std::string error;
  const auto parsed = parseTilesetIndex(index, "index.qnvt", error);
  REQUIRE(parsed);
  CHECK(parsed->depth == 2);
  CHECK(parsed->header.vectorCount == 120);
}

TEST_CASE("truncated and bit-flipped golden tileset indexes never crash",
          "[qnv][tileset][golden][hostile]") {
  const std::string golden = gs::test::readBytes(goldenDir() / "index.qnvt");
  REQUIRE(golden.size() > kTilesetPreambleBytes);
  std::string error;
  for (std::size_t n = 0; n < golden.size(); ++n)
    CHECK_FALSE(parseTilesetIndex(golden.substr(0, n), "index.qnvt", error));
  for (std::size_t bit = 0; bit < golden.size() * 8; bit += 3) {
    std::string flipped = golden;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    CHECK_FALSE(parseTilesetIndex(flipped, "index.qnvt", error));
  }
}

TEST_CASE("damaged interior parts are rejected with a sentence", "[qnv][tileset][hostile]") {
  const SelectedVectors selected = selectVolumeVectors(blobVolume(), {});
  const TilesetLayout layout(selected.header, goldenOptions());
  TilesetShareWriter writer(layout);
  for (const SourceVector& v : selected.vectors) writer.add(v);
  for (const glm::uvec3& leaf : writer.openLeaves()) (void)writer.finishLeaf(leaf);
  const std::string bytes = serializeInteriorParts(writer.interior(), goldenOptions());
  TilesetOptions cut;
  std::string error;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    CHECK_FALSE(parseInteriorParts(bytes.substr(0, n), "p/interior.qnvp", cut, error));
    CHECK(error.rfind("p/interior.qnvp: ", 0) == 0);
  }
  std::string flipped = bytes;
  flipped[30] ^= 4;
  CHECK_FALSE(parseInteriorParts(flipped, "p", cut, error));
  CHECK(error.find("CRC mismatch") != std::string::npos);
}
