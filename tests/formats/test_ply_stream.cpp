// streamPly: the PLY file read piece by piece gives readPly's vertices, triangles and
// colours in readPly's order, and readPly's errors, whatever the piece size (pieces of 1
// to 7 bytes cut every token, list and header line somewhere).
#include <catch2/catch.hpp>

#include <fstream>
#include <iterator>
#include <string>

#include "formats/mesh_readers.hpp"
#include "test_support.hpp"

using namespace gs::formats;
namespace fs = std::filesystem;

namespace {

std::string readAll(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Builds readPly's TriangleMesh from the sink calls.
class Collect final : public PlySink {
 public:
  TriangleMesh mesh;
  PlyLayout layout;
  int begins = 0;
  void begin(const PlyLayout& l) override {
    layout = l;
    ++begins;
  }
  void vertex(const glm::vec3& p, Rgba8 c) override {
    mesh.positions.push_back(p);
    if (layout.vertexColors) mesh.vertexColors.push_back(c);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, Rgba8 color) override {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
    if (layout.faceColors) mesh.faceColors.push_back(color);
  }
};

void checkSame(const TriangleMesh& a, const TriangleMesh& b) {
  CHECK(a.positions == b.positions);
  CHECK(a.indices == b.indices);
  CHECK(a.vertexColors == b.vertexColors);
  CHECK(a.faceColors == b.faceColors);
}

template <typename Read>
std::string errorOf(Read read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// An ascii PLY with long tokens, CRLF line ends, a pentagon, face colours and an extra
// list to skip.
const char* const kAscii =
    "ply\r\nformat ascii 1.0\r\ncomment long tokens\r\nelement vertex 5\r\n"
    "property double x\r\nproperty double y\r\nproperty double z\r\n"
    "element face 2\r\nproperty list uchar int vertex_indices\r\nproperty uchar red\r\n"
    "property uchar green\r\nproperty uchar blue\r\nproperty list uchar float junk\r\n"
    "end_header\r\n"
    "0.000000000000000000000000000000000000000000000000001 0 0\r\n"
    "1 0 0\r\n1 1 0\r\n0 1 0\r\n0.5 1.5 +0.25\r\n"
    "5 0 1 2 4 3 10 20 30 2 1.5 2.5\r\n3 0 1 2 255 0 7 0\r\n";

}  // namespace

TEST_CASE("streamPly gives readPly's mesh for every piece size", "[formats][mesh][ooc]") {
  gs::test::TempDir dir("plystream");
  std::vector<fs::path> files;
  for (const char* name : {"cube_ascii.ply", "cube_le.ply", "cube_be.ply"})
    files.push_back(gs::test::sourceDir() / "assets" / "meshes" / name);
  files.push_back(dir.path / "long.ply");
  std::ofstream(files.back(), std::ios::binary) << kAscii;
  for (const fs::path& file : files) {
    INFO(file.string());
    const TriangleMesh whole = readPly(readAll(file), file.string());
    REQUIRE(whole.triangleCount() > 0);
    for (std::size_t chunk : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{7},
                              std::size_t{64}, std::size_t{1} << 20}) {
      INFO("piece " << chunk);
      Collect sink;
      streamPly(file.string(), sink, chunk);
      CHECK(sink.begins == 1);
      checkSame(sink.mesh, whole);
    }
  }
}

TEST_CASE("streamPly reports readPly's errors, and refuses gzip", "[formats][mesh][ooc]") {
  gs::test::TempDir dir("plystream");
  const fs::path cube = gs::test::sourceDir() / "assets" / "meshes" / "cube_le.ply";
  const std::string bytes = readAll(cube);
  const fs::path cut = dir.path / "cut.ply";
  // Every truncation of the binary cube and of the ascii file: the same message (or none).
  for (const std::string& whole : {bytes, std::string(kAscii)})
    for (std::size_t n = 0; n < whole.size(); n += 3) {
      std::ofstream(cut, std::ios::binary | std::ios::trunc) << whole.substr(0, n);
      const std::string expected = errorOf([&] { readPly(whole.substr(0, n), cut.string()); });
      for (std::size_t chunk : {std::size_t{1}, std::size_t{5}, std::size_t{4096}}) {
        INFO(n << " bytes, piece " << chunk);
        Collect sink;
        CHECK(errorOf([&] { streamPly(cut.string(), sink, chunk); }) == expected);
      }
    }
  // A bad index.
  std::string bad = kAscii;
  bad.replace(bad.find("3 0 1 2 255"), 11, "3 0 9 2 255");
  std::ofstream(cut, std::ios::binary | std::ios::trunc) << bad;
  Collect sink;
  const std::string error = errorOf([&] { streamPly(cut.string(), sink, 2); });
  CHECK_THAT(error, Catch::Contains("a vertex index below 5"));
  CHECK(error == errorOf([&] { readPly(bad, cut.string()); }));
  // gzip (its magic bytes) and a missing file.
  const fs::path gz = dir.path / "cube.ply.gz";
  std::ofstream(gz, std::ios::binary) << std::string("\x1f\x8b\x08\x00\x00\x00\x00\x00", 8);
  CHECK_THAT(errorOf([&] { streamPly(gz.string(), sink); }), Catch::Contains("gunzip it first"));
  CHECK_THAT(errorOf([&] { streamPly((dir.path / "none.ply").string(), sink); }),
             Catch::Contains("cannot open"));
}
