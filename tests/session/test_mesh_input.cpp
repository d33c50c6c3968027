// Mesh files from disk: extension dispatch, gzip, and glTF external buffers confined to
// the file's folder.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "formats/input_kind.hpp"
#include "qnv/error.hpp"
#include "session/mesh_input.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using gs::qnv::InputError;
using gs::session::loadMeshFile;
using gs::test::gzip;
using gs::test::TempDir;

namespace {

bool isMeshFile(const std::string& path) {
  return gs::formats::isMesh(gs::formats::classifyFile(path));
}

fs::path asset(const std::string& name) {
  return gs::test::sourceDir() / "assets" / "meshes" / name;
}

void writeBytes(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out.good());
}

std::string errorOf(const std::string& path) {
  try {
    loadMeshFile(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The tetrahedron of two_nodes.gltf as a 72-byte buffer: 4 float positions, 12 u16 indices.
std::string tetraBuffer() {
  const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const std::uint16_t i[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  std::string out(72, '\0');
  std::memcpy(out.data(), p, 48);  // the machines we build on are little-endian
  std::memcpy(out.data() + 48, i, 24);
  return out;
}

// two_nodes.gltf with its data: URI replaced by `uri`.
std::string gltfWithUri(const std::string& uri) {
  std::string s = gs::test::readBytes(asset("two_nodes.gltf"));
  const auto start = s.find("data:");
  return s.replace(start, s.find('"', start) - start, uri);
}

}  // namespace

TEST_CASE("isMeshFile goes by extension, any case, optionally .gz", "[app][mesh]") {
  for (const char* yes :
       {"a.ply", "b.OBJ", "dir/c.gltf", "d.GLB", "e.ply.gz", "f.obj.GZ", "g.gltf.gz", "h.glb.gz"})
    CHECK(isMeshFile(yes));
  for (const char* no : {"a.wrl", "b.nrrd", "ply", "c.ply.bz2", "d.gz", "e.objx", ""})
    CHECK_FALSE(isMeshFile(no));
}

TEST_CASE("loadMeshFile reads every mesh asset", "[app][mesh]") {
  struct Expect {
    const char* file;
    std::size_t vertices, triangles;
  };
  for (const Expect& e :
       {Expect{"cube_ascii.ply", 8, 12}, Expect{"cube_le.ply", 8, 12}, Expect{"cube_be.ply", 8, 12},
        Expect{"quads.obj", 6, 5}, Expect{"two_nodes.gltf", 8, 8}, Expect{"tetra.glb", 8, 6}}) {
    INFO(e.file);
    const auto m = loadMeshFile(asset(e.file).string());
    CHECK(m.positions.size() == e.vertices);
    CHECK(m.triangleCount() == e.triangles);
  }
}

TEST_CASE("loadMeshFile decompresses .gz and names the path in errors", "[app][mesh]") {
  TempDir tmp;
  const auto plain = loadMeshFile(asset("cube_le.ply").string());
  for (const char* file : {"cube_le.ply", "tetra.glb", "quads.obj"}) {
    INFO(file);
    const fs::path gz = tmp.path / (std::string(file) + ".gz");
    writeBytes(gz, gzip(gs::test::readBytes(asset(file))));
    const auto m = loadMeshFile(gz.string());
    const auto want = loadMeshFile(asset(file).string());
    CHECK(m.positions == want.positions);
    CHECK(m.indices == want.indices);
    CHECK(m.vertexColors == want.vertexColors);
  }
  const fs::path cut = tmp.path / "cut.ply.gz";
  const std::string whole = gzip(gs::test::readBytes(asset("cube_le.ply")));
  writeBytes(cut, whole.substr(0, whole.size() / 2));
  CHECK(errorOf(cut.string()).starts_with(cut.string() + ": "));

  const fs::path bad = tmp.path / "bad.ply";
  writeBytes(bad, "ply\nformat ascii 1.0\nelement vertex 1\nend_header\n");
  CHECK(errorOf(bad.string()) ==
        bad.string() + ":3: expected vertex properties x, y and z, got fewer");
  const fs::path missing = tmp.path / "missing.obj";
  CHECK(errorOf(missing.string()).find(missing.string()) != std::string::npos);
  const fs::path other = tmp.path / "mesh.stl";
  writeBytes(other, "solid x\n");
  CHECK(errorOf(other.string()).starts_with(other.string() + ": not a mesh file name"));
  CHECK(plain.triangleCount() == 12);
}

TEST_CASE("glTF external buffers are read from the file's folder only", "[app][mesh]") {
  TempDir tmp;
  const fs::path dir = tmp.path / "model";
  writeBytes(dir / "buffers" / "tetra data.bin", tetraBuffer());
  writeBytes(tmp.path / "outside.bin", tetraBuffer());

  const fs::path good = dir / "good.gltf";
  writeBytes(good, gltfWithUri("buffers/tetra%20data.bin"));
  const auto m = loadMeshFile(good.string());
  const auto embedded = loadMeshFile(asset("two_nodes.gltf").string());
  CHECK(m.positions == embedded.positions);
  CHECK(m.indices == embedded.indices);
  CHECK(m.faceColors == embedded.faceColors);

  struct Refused {
    const char* uri;
    const char* why;
  };
  for (const Refused& r : {Refused{"../outside.bin", "leaves the folder ('..')"},
                           Refused{"buffers/../../outside.bin", "leaves the folder ('..')"},
                           Refused{"/etc/passwd", "is an absolute path"},
                           Refused{"file:///etc/passwd", "is not a relative file"},
                           Refused{"http://example.com/a.bin", "is not a relative file"}}) {
    INFO(r.uri);
    const fs::path f = dir / "refused.gltf";
    writeBytes(f, gltfWithUri(r.uri));
    const std::string error = errorOf(f.string());
    CHECK(error.starts_with(f.string() + ": external buffer '"));
    CHECK(error.find(r.why) != std::string::npos);
  }

  std::error_code ec;
  fs::create_symlink(tmp.path / "outside.bin", dir / "link.bin", ec);
  if (!ec) {
    const fs::path f = dir / "link.gltf";
    writeBytes(f, gltfWithUri("link.bin"));
    CHECK(errorOf(f.string()).find("leads out of the folder through a link") != std::string::npos);
  }

  const fs::path absent = dir / "absent.gltf";
  writeBytes(absent, gltfWithUri("nothing.bin"));
  const std::string error = errorOf(absent.string());
  CHECK(error.starts_with(absent.string() + ": external buffer 'nothing.bin': "));
}
