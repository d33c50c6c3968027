// gs_encode's tileset encodes called directly (encode/tileset.hpp): the out-of-core
// volume and mesh encodes give the in-memory encode's files byte for byte (also under a
// tiny memory bound, which must spill), split shares merge to the whole tileset, and a
// truncated PLY or a malformed share is an error value, not a crash.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "encode/tileset.hpp"
#include "formats/mesh_readers.hpp"
#include "qnv/encoder.hpp"
#include "qnv/volume_slabs.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace gs;

namespace {

// A 21 x 17 x 23 uint16-valued volume: a ball, a slab and hashed noise (integer samples,
// so that many gradient magnitudes tie and the selection's tie rule is exercised).
qnv::Volume makeVolume() {
  qnv::Volume v;
  v.dims = glm::uvec3(21, 17, 23);
  v.spacing = glm::vec3(1.0f, 0.8f, 1.5f);
  v.sourceType = qnv::ScalarType::uint16;
  for (std::uint32_t z = 0; z < v.dims.z; ++z)
    for (std::uint32_t y = 0; y < v.dims.y; ++y)
      for (std::uint32_t x = 0; x < v.dims.x; ++x) {
        const int dx = static_cast<int>(x) - 9, dy = static_cast<int>(y) - 8,
                  dz = static_cast<int>(z) - 12;
        int s = dx * dx + dy * dy + dz * dz < 40 ? 900 : 100;
        if (z > 17 && x < 10) s += 300;
        const std::uint32_t h = (x * 73856093u) ^ (y * 19349663u) ^ (z * 83492791u);
        v.samples.push_back(static_cast<float>(s + 2 * static_cast<int>(h % 3)));
      }
  return v;
}

// A binary little-endian PLY height field of G x G vertices with vertex colours, quads
// (fan-triangulated by the reader) and degenerate triangles.
std::string makePly() {
  constexpr int G = 21;
  std::vector<std::vector<std::int32_t>> faces;
  for (int y = 0; y + 1 < G; ++y)
    for (int x = 0; x + 1 < G; ++x) {
      const int v = y * G + x;
      if ((x + y * G) % 7 == 3)
        faces.push_back({v, v + 1, v + 1});
      else
        faces.push_back({v, v + 1, v + G + 1, v + G});
    }
  std::string out =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(G * G) +
      "\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar red\nproperty uchar green\nproperty uchar blue\n"
      "element face " +
      std::to_string(faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const auto put = [&out](const auto& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  };
  for (int y = 0; y < G; ++y)
    for (int x = 0; x < G; ++x) {
      put(static_cast<float>(x * 0.5));
      put(static_cast<float>(y * 0.25));
      put(static_cast<float>((x * 7 + y * 3) % 5 == 0 ? 1.0 : 0.0));
      put(static_cast<unsigned char>(x * 12));
      put(static_cast<unsigned char>(y * 12));
      put(static_cast<unsigned char>((x * y) % 256));
    }
  for (const auto& f : faces) {
    put(static_cast<unsigned char>(f.size()));
    for (std::int32_t i : f) put(i);
  }
  return out;
}

std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = test::readBytes(entry.path());
  return files;
}

// The same files with the same bytes: an index and at least two bricks.
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

encode::TilesetTarget target(const fs::path& dir, std::uint32_t brickVoxels = 8,
                             std::uint64_t brickVectors = 64) {
  encode::TilesetTarget t;
  t.dir = dir;
  t.cut.brickVoxels = brickVoxels;
  t.cut.brickVectors = brickVectors;
  t.cut.write.packetBytes = 4096;
  return t;
}

encode::OutOfCoreOptions bound(double megabytes, unsigned threads) {
  encode::OutOfCoreOptions o;
  o.memoryBytes = static_cast<std::uint64_t>(megabytes * 1048576.0);
  o.threads = threads;
  return o;
}

}  // namespace

TEST_CASE("an out-of-core volume tileset is the in-memory tileset, byte for byte", "[encode]") {
  test::TempDir dir("encode-volume");
  const qnv::Volume volume = makeVolume();
  for (const double fraction : {1.0, 0.4}) {
    INFO("fraction " << fraction);
    qnv::VolumeEncodeOptions options;
    options.selection.fraction = fraction;
    const std::string tag = std::to_string(static_cast<int>(fraction * 10));
    const fs::path memory = dir.path / ("memory" + tag), ooc = dir.path / ("ooc" + tag),
                   tiny = dir.path / ("tiny" + tag);

    const encode::TilesetResult m =
        encode::writeTileset(target(memory), qnv::selectVolumeVectors(volume, options));
    INFO(m.error);
    REQUIRE(m.ok());
    CHECK(m.merged.index.bricks.size() > 2);
    CHECK(!fs::exists(memory / "parts"));

    qnv::MemoryVolumeSlabs reader(volume);
    const encode::VolumeOutOfCoreResult o =
        encode::writeVolumeTilesetOutOfCore(target(ooc), reader, options, bound(64, 3));
    INFO(o.tileset.error);
    REQUIRE(o.tileset.ok());
    CHECK(o.summary.elements == volume.voxelCount());
    CHECK(o.leafSpillBytes == 0);  // 64 MiB holds it all
    checkSameTree(memory, ooc);

    // A bound of about 20 KiB: the leaves' vectors must spill, and the bytes stay.
    qnv::MemoryVolumeSlabs again(volume);
    const encode::VolumeOutOfCoreResult t =
        encode::writeVolumeTilesetOutOfCore(target(tiny), again, options, bound(0.02, 2));
    INFO(t.tileset.error);
    REQUIRE(t.tileset.ok());
    CHECK(t.leafSpillBytes > 0);
    CHECK(t.z0 == 0);
    CHECK(t.z1 == volume.dims.z);
    checkSameTree(memory, tiny);
    CHECK(!fs::exists(tiny / "parts"));  // spill files and parts gone after the merge
  }
}

TEST_CASE("split volume shares merge to the whole tileset", "[encode]") {
  test::TempDir dir("encode-shares");
  const qnv::Volume volume = makeVolume();
  qnv::VolumeEncodeOptions options;
  options.selection.fraction = 0.5;
  const fs::path whole = dir.path / "whole", split = dir.path / "split";
  REQUIRE(encode::writeTileset(target(whole), qnv::selectVolumeVectors(volume, options)).ok());
  for (std::uint32_t i = 0; i < 3; ++i) {
    encode::TilesetTarget t = target(split);
    t.whole = false;
    t.share = i;
    t.shares = 3;
    qnv::MemoryVolumeSlabs reader(volume);
    const encode::VolumeOutOfCoreResult r =
        encode::writeVolumeTilesetOutOfCore(t, reader, options, bound(0.05, 2));
    INFO(r.tileset.error);
    REQUIRE(r.tileset.ok());
    CHECK(fs::exists(split / "parts" / encode::shareName(i, 3) / "leaves.qnvt"));
    CHECK(!fs::exists(split / "index.qnvt"));
  }
  encode::Merged merged;
  REQUIRE(encode::mergeShares(split, merged) == "");
  CHECK(merged.totalBytes > merged.indexBytes);
  checkSameTree(whole, split);
  // Merged once: the parts are gone, a second merge is an error.
  CHECK(encode::mergeShares(split, merged) != "");
}

TEST_CASE("an out-of-core mesh tileset is the in-memory tileset, byte for byte", "[encode]") {
  test::TempDir dir("encode-mesh");
  const fs::path ply = dir.path / "field.ply";
  const std::string bytes = makePly();
  std::ofstream(ply, std::ios::binary) << bytes;
  const qnv::TriangleMesh mesh = formats::readPly(bytes, ply.string());
  for (const double fraction : {1.0, 0.5}) {
    INFO("fraction " << fraction);
    qnv::SurfaceEncodeOptions options;
    options.selection.fraction = fraction;
    const std::string tag = std::to_string(static_cast<int>(fraction * 10));
    const fs::path memory = dir.path / ("memory" + tag), ooc = dir.path / ("ooc" + tag),
                   tiny = dir.path / ("tiny" + tag);
    const encode::TilesetResult m =
        encode::writeTileset(target(memory, 64, 32), qnv::selectSurfaceVectors(mesh, options));
    INFO(m.error);
    REQUIRE(m.ok());

    const encode::MeshOutOfCoreResult o =
        encode::writeMeshTilesetOutOfCore(target(ooc, 64, 32), ply, options, bound(64, 3));
    INFO(o.tileset.error);
    REQUIRE(o.tileset.ok());
    CHECK(o.vertices == 21 * 21);
    CHECK(o.summary.elements == mesh.triangleCount());
    checkSameTree(memory, ooc);

    const encode::MeshOutOfCoreResult t =
        encode::writeMeshTilesetOutOfCore(target(tiny, 64, 32), ply, options, bound(0.01, 2));
    INFO(t.tileset.error);
    REQUIRE(t.tileset.ok());
    CHECK(t.leafSpillBytes > 0);
    checkSameTree(memory, tiny);
  }
}

TEST_CASE("a truncated or malformed PLY is an error value, its copy removed", "[encode]") {
  test::TempDir dir("encode-bad-ply");
  const std::string bytes = makePly();
  const fs::path truncated = dir.path / "truncated.ply";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() * 2 / 3);
  const fs::path out = dir.path / "t";
  encode::MeshOutOfCoreResult r =
      encode::writeMeshTilesetOutOfCore(target(out), truncated, {}, bound(64, 2));
  CHECK(!r.tileset.ok());
  CHECK(r.tileset.failure == encode::Failure::input);
  CHECK(!r.tileset.error.empty());
  CHECK(!fs::exists(out / "parts" / "0-of-1" / "mesh.vertices"));
  CHECK(!fs::exists(out / "index.qnvt"));

  const fs::path bad = dir.path / "bad.ply";
  std::ofstream(bad) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                        "0 1 0\n3 0 1 7\n";
  r = encode::writeMeshTilesetOutOfCore(target(out), bad, {}, bound(64, 2));
  CHECK(r.tileset.failure == encode::Failure::input);
  CHECK_THAT(r.tileset.error, Catch::Contains("a vertex index below 3"));

  r = encode::writeMeshTilesetOutOfCore(target(out), dir.path / "missing.ply", {}, bound(64, 2));
  CHECK(!r.tileset.ok());
}

TEST_CASE("shares: I/N parsed, names, and a merge without shares is an error", "[encode]") {
  std::uint32_t i = 9, n = 9;
  CHECK(encode::parseShare("1/3", i, n));
  CHECK((i == 1 && n == 3));
  CHECK(encode::parseShare("0/1", i, n));
  for (const char* bad : {"3/3", "1/0", "1", "/3", "1/3x", "-1/3", "1/2000000", ""}) {
    INFO(bad);
    CHECK(!encode::parseShare(bad, i, n));
  }
  CHECK(encode::shareName(2, 5) == "2-of-5");
  test::TempDir dir("encode-merge");
  encode::Merged merged;
  CHECK_THAT(encode::mergeShares(dir.path, merged), Catch::Contains("holds no shares"));
}
