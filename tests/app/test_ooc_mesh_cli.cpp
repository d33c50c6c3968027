// `ghostspace encode MESH.ply --tileset OUT/ --memory MB`: the out-of-core tileset encode
// of a mesh gives the in-memory tileset encode's files byte for byte (keep all,
// --fraction and --count with ties at the threshold, entropy coding, vertex and face
// colours, more than 256 colours), spills under a tiny bound, and split runs (N = 1, 2,
// 3) merge to the single run's bytes; inputs are the PLY assets and meshes made at test
// time as ascii, little- and big-endian PLY (docs/out-of-core.md, "Meshes").
#include <catch2/catch.hpp>

#include <bit>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "base/byte_order.hpp"
#include "process.hpp"
#include "test_support.hpp"

using gs::test::runGhostspace;
namespace fs = std::filesystem;

namespace {

enum class Format { ascii, little, big };
enum class Colors { none, vertex, face };

template <typename T>
void put(std::ofstream& out, T v, Format f) {
  if (f == Format::big) {
    if constexpr (sizeof(T) == 8)
      v = std::bit_cast<T>(gs::base::byteSwap(std::bit_cast<std::uint64_t>(v)));
    else if constexpr (sizeof(T) == 4)
      v = std::bit_cast<T>(gs::base::byteSwap(std::bit_cast<std::uint32_t>(v)));
  }
  out.write(reinterpret_cast<const char*>(&v), sizeof v);
}

// A height field of G x G vertices with integer heights (so that many triangles have
// exactly the same area: ties at the threshold), fan-triangulated quads, every seventh
// quad a degenerate triangle (a repeated index), and one pentagon.
fs::path writeMesh(const fs::path& path, Format f, Colors colors) {
  constexpr int G = 21;
  const auto height = [](int x, int y) { return ((x * 7 + y * 3) % 5 == 0) ? 1.0 : 0.0; };
  std::vector<std::vector<int>> faces;
  for (int y = 0; y + 1 < G; ++y)
    for (int x = 0; x + 1 < G; ++x) {
      const int v = y * G + x;
      if ((x + y * G) % 7 == 3)
        faces.push_back({v, v + 1, v + 1});
      else
        faces.push_back({v, v + 1, v + G + 1, v + G});
    }
  faces.push_back({0, 1, 2, G + 2, G});
  std::ofstream out(path, std::ios::binary);
  const char* format = f == Format::ascii    ? "ascii"
                       : f == Format::little ? "binary_little_endian"
                                             : "binary_big_endian";
  out << "ply\nformat " << format << " 1.0\nelement vertex " << G * G << "\n";
  out << (f == Format::big ? "property double x\nproperty double y\nproperty double z\n"
                           : "property float x\nproperty float y\nproperty float z\n");
  if (colors == Colors::vertex)
    out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "element face " << faces.size() << "\nproperty list uchar int vertex_indices\n";
  if (colors == Colors::face)
    out << "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  out << "end_header\n";
  for (int y = 0; y < G; ++y)
    for (int x = 0; x < G; ++x) {
      const double p[3] = {x * 0.5, y * 0.25, height(x, y)};
      // Vertex colours: 441 distinct ones, so that the kept triangles' means need the
      // median cut (more than 256 colours).
      const unsigned char c[3] = {static_cast<unsigned char>(x * 12),
                                  static_cast<unsigned char>(y * 12),
                                  static_cast<unsigned char>((x * y) % 256)};
      if (f == Format::ascii) {
        out << p[0] << " " << p[1] << " " << p[2];
        if (colors == Colors::vertex)
          out << " " << int{c[0]} << " " << int{c[1]} << " " << int{c[2]};
        out << "\n";
        continue;
      }
      for (double v : p)
        if (f == Format::big)
          put(out, v, f);
        else
          put(out, static_cast<float>(v), f);
      if (colors == Colors::vertex) out.write(reinterpret_cast<const char*>(c), 3);
    }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    // Face colours: three of them.
    const unsigned char c[3] = {static_cast<unsigned char>(i % 3 * 100), 50, 200};
    if (f == Format::ascii) {
      out << faces[i].size();
      for (int v : faces[i]) out << " " << v;
      if (colors == Colors::face) out << " " << int{c[0]} << " " << int{c[1]} << " " << int{c[2]};
      out << "\n";
      continue;
    }
    const auto n = static_cast<unsigned char>(faces[i].size());
    out.write(reinterpret_cast<const char*>(&n), 1);
    for (int v : faces[i]) put(out, static_cast<std::int32_t>(v), f);
    if (colors == Colors::face) out.write(reinterpret_cast<const char*>(c), 3);
  }
  return path;
}

std::map<std::string, std::string> tree(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(dir))
    if (entry.is_regular_file())
      files[fs::relative(entry.path(), dir).string()] = gs::test::readBytes(entry.path());
  return files;
}

// The same files with the same bytes; `a` holds at least `files` files.
void checkSameTree(const fs::path& a, const fs::path& b, std::size_t files = 5) {
  const auto x = tree(a), y = tree(b);
  CHECK(x.size() >= files);
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

TEST_CASE("an out-of-core mesh tileset is the in-memory tileset, byte for byte",
          "[heavy][app][encode][tileset][ooc]") {
  gs::test::TempDir dir("oocmesh");
  const std::vector<std::string> meshes = {
      writeMesh(dir.path / "vertex.ply", Format::ascii, Colors::vertex).string(),
      writeMesh(dir.path / "face.ply", Format::little, Colors::face).string(),
      writeMesh(dir.path / "plain.ply", Format::big, Colors::none).string(),
  };
  const std::vector<std::vector<std::string>> cases = {
      {"--brick-vectors", "16"},
      {"--brick-vectors", "24", "--fraction", "0.3", "--coding", "entropy", "--packet-bytes",
       "128"},
      {"--brick-vectors", "8", "--count", "77", "--magnitude", "linear"},
      {"--brick-vectors", "4", "--fraction", "0.05"},
  };
  int n = 0;
  for (const std::string& mesh : meshes)
    for (const auto& options : cases) {
      INFO(mesh << " case " << n);
      const fs::path memory = dir.path / ("memory" + std::to_string(n));
      const fs::path ooc = dir.path / ("ooc" + std::to_string(n));
      const fs::path tiny = dir.path / ("tiny" + std::to_string(n++));
      encode(mesh, memory, options);
      const auto r = encode(mesh, ooc, with(options, {"--memory", "64", "--threads", "3"}));
      CHECK_THAT(r.out, Catch::Contains("out of core"));
      CHECK_THAT(r.out, Catch::Contains(", 1 vertex block reads"));
      checkSameTree(memory, ooc);
      // 20 KB: a vertex cache of one block; the cases keeping hundreds of vectors spill.
      const auto t = encode(mesh, tiny, with(options, {"--memory", "0.02", "--threads", "2"}));
      if (n % 4 == 1 || n % 4 == 2) CHECK_THAT(t.out, !Catch::Contains("spilled 0 + 0 bytes"));
      checkSameTree(memory, tiny);
    }
}

TEST_CASE("out-of-core encodes of the PLY assets are the in-memory ones",
          "[app][encode][tileset][ooc]") {
  gs::test::TempDir dir("oocmesh");
  for (const char* name : {"cube_ascii.ply", "cube_le.ply", "cube_be.ply"}) {
    INFO(name);
    const std::string mesh = (gs::test::sourceDir() / "assets" / "meshes" / name).string();
    const fs::path memory = dir.path / (std::string(name) + ".memory");
    const fs::path ooc = dir.path / (std::string(name) + ".ooc");
    encode(mesh, memory, {"--brick-vectors", "2", "--fraction", "0.5"});
    encode(mesh, ooc, {"--brick-vectors", "2", "--fraction", "0.5", "--memory", "0.01"});
    checkSameTree(memory, ooc, 2);
  }
}

TEST_CASE("an out-of-core mesh tileset split into 1, 2 or 3 shares merges to the same bytes",
          "[app][encode][tileset][ooc]") {
  gs::test::TempDir dir("oocmesh");
  const std::string mesh = writeMesh(dir.path / "m.ply", Format::little, Colors::vertex).string();
  const std::vector<std::string> options = {"--brick-vectors", "12", "--fraction", "0.4"};
  const fs::path single = dir.path / "single";
  encode(mesh, single, options);  // in memory
  for (std::uint32_t shares : {1u, 2u, 3u}) {
    INFO(shares << " shares");
    const fs::path split = dir.path / ("split" + std::to_string(shares));
    for (std::uint32_t i = shares; i-- > 0;) {
      const auto r = encode(mesh, split,
                            with(options, {"--memory", "0.03", "--bricks",
                                           std::to_string(i) + "/" + std::to_string(shares)}));
      CHECK_THAT(r.out,
                 Catch::Contains("share " + std::to_string(i) + " of " + std::to_string(shares)));
    }
    const auto merge = runGhostspace({"tileset", "index", split.string()});
    INFO(merge.err);
    REQUIRE(merge.exitCode == 0);
    checkSameTree(single, split);
  }
}

TEST_CASE("out-of-core mesh encodes refuse other mesh formats and report bad PLY",
          "[app][encode][tileset][ooc]") {
  gs::test::TempDir dir("oocmesh");
  const std::string obj = (gs::test::sourceDir() / "assets/meshes/quads.obj").string();
  auto r = runGhostspace(
      {"encode", obj, "--tileset", (dir.path / "t").string(), "--memory", "64", "--no-progress"});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("volumes, PLY meshes and Gaussian splatting scenes"));
  const fs::path bad = dir.path / "bad.ply";
  std::ofstream(bad) << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                        "property float y\nproperty float z\nelement face 1\n"
                        "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n"
                        "0 1 0\n3 0 1 7\n";
  r = runGhostspace({"encode", bad.string(), "--tileset", (dir.path / "t").string(), "--memory",
                     "64", "--no-progress"});
  CHECK(r.exitCode == 1);
  CHECK_THAT(r.err, Catch::Contains("a vertex index below 3"));
  CHECK(!fs::exists(dir.path / "t" / "parts" / "0-of-1" / "mesh.vertices"));
}
