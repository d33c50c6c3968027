// PLY, OBJ and glTF readers: the assets in assets/meshes, the Stanford bunny from the
// corpus, and hostile input (truncations, huge counts, bad indices, garbage), which must
// give InputError and never crash or over-allocate.
#include <catch2/catch.hpp>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "formats/mesh_readers.hpp"
#include "test_support.hpp"

using namespace gs::formats;

namespace {

std::string readAsset(const std::string& name) {
  const auto path = gs::test::sourceDir() / "assets" / "meshes" / name;
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The invariants TriangleMesh promises.
void checkInvariants(const TriangleMesh& m) {
  REQUIRE(m.indices.size() % 3 == 0);
  for (std::uint32_t i : m.indices) REQUIRE(i < m.positions.size());
  REQUIRE((m.vertexColors.empty() || m.vertexColors.size() == m.positions.size()));
  REQUIRE((m.faceColors.empty() || m.faceColors.size() == m.triangleCount()));
}

// What `read` throws (the message), or "" when it succeeds.
template <typename Read>
std::string errorOf(Read read) {
  try {
    checkInvariants(read());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string ply(const std::string& text) {
  return errorOf([&] { return readPly(text, "t.ply"); });
}
std::string obj(const std::string& text) {
  return errorOf([&] { return readObj(text, "t.obj"); });
}
std::string gltf(const std::string& text) {
  return errorOf([&] { return readGltf(text, "t.gltf"); });
}

// Reads every proper prefix of `bytes`: each must throw InputError or give a valid mesh
// no larger than the whole one. Returns how many prefixes threw.
template <typename Read>
std::size_t truncations(const std::string& bytes, Read read) {
  const TriangleMesh whole = read(std::string_view(bytes));
  std::size_t errors = 0;
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    const std::string cut = bytes.substr(0, n);  // a copy, so ASan sees reads past n
    try {
      const TriangleMesh m = read(std::string_view(cut));
      checkInvariants(m);
      CHECK(m.triangleCount() <= whole.triangleCount());
    } catch (const InputError&) {
      ++errors;
    }
  }
  return errors;
}

}  // namespace

TEST_CASE("PLY ascii cube: quads fan-triangulated, vertex colours, extras skipped", "[qnv][mesh]") {
  const TriangleMesh m = readPly(readAsset("cube_ascii.ply"), "cube_ascii.ply");
  checkInvariants(m);
  REQUIRE(m.positions.size() == 8);
  REQUIRE(m.triangleCount() == 12);
  CHECK(m.faceColors.empty());
  REQUIRE(m.vertexColors.size() == 8);
  CHECK(m.positions[6] == glm::vec3(0, 1, 1));
  CHECK(m.vertexColors[1] == Rgba8(255, 0, 0, 255));
  CHECK(m.vertexColors[6] == Rgba8(0, 255, 255, 255));
  CHECK(m.vertexColors[7] == Rgba8(255, 255, 255, 255));
  const std::vector<std::uint32_t> first{0, 2, 3, 0, 3, 1, 4, 5, 7};
  CHECK(std::vector<std::uint32_t>(m.indices.begin(), m.indices.begin() + 9) == first);
  // Every face points outwards: its normal agrees with centre-of-face minus cube centre.
  for (std::size_t t = 0; t < m.triangleCount(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    CHECK(glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0f - glm::vec3(0.5f)) > 0.0f);
  }
}

TEST_CASE("PLY binary little- and big-endian cubes equal the ascii one", "[qnv][mesh]") {
  const TriangleMesh a = readPly(readAsset("cube_ascii.ply"), "cube_ascii.ply");
  for (const char* file : {"cube_le.ply", "cube_be.ply"}) {
    INFO(file);
    const TriangleMesh b = readPly(readAsset(file), file);
    checkInvariants(b);
    CHECK(b.positions == a.positions);
    CHECK(b.indices == a.indices);
    CHECK(b.vertexColors == a.vertexColors);
    CHECK(b.faceColors.empty());
  }
}

TEST_CASE("PLY face colours, CRLF header, skipped face lists, degenerate triangles kept",
          "[qnv][mesh]") {
  const std::string text =
      "ply\r\nformat ascii 1.0\r\ncomment c\r\nelement vertex 4\r\nproperty double x\r\n"
      "property double y\r\nproperty double z\r\nelement face 2\r\n"
      "property list uchar float texcoord\r\nproperty list ushort uint vertex_index\r\n"
      "property float red\r\nproperty float green\r\nproperty float blue\r\n"
      "property uchar alpha\r\nend_header\r\n"
      "0 0 0\r\n1 0 0\r\n1 1 0\r\n+1e-1 .5 -0\r\n"
      "2 0.5 0.5 3 0 1 2 1 0 0.5 128\r\n0 4 3 3 3 3 0 0 1 255\r\n";
  const TriangleMesh m = readPly(text, "t.ply");
  checkInvariants(m);
  REQUIRE(m.triangleCount() == 3);
  CHECK(m.vertexColors.empty());
  REQUIRE(m.faceColors.size() == 3);
  CHECK(m.faceColors[0] == Rgba8(255, 0, 128, 128));
  CHECK(m.faceColors[1] == Rgba8(0, 0, 255, 255));
  CHECK(m.faceColors[2] == Rgba8(0, 0, 255, 255));
  CHECK(m.positions[3] == glm::vec3(0.1f, 0.5f, 0.0f));
  CHECK(m.indices[3] == 3);  // the degenerate 3 3 3 3 fan is kept
}

TEST_CASE("PLY errors name the file and line", "[qnv][mesh]") {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::string verts = "0 0 0\n1 0 0\n0 1 0\n";
  CHECK(ply(head + verts + "3 0 1 2\n").empty());
  CHECK(ply(head + verts + "3 0 1 3\n") == "t.ply:13: expected a vertex index below 3, got '3'");
  CHECK(ply(head + verts + "3 0 -1 2\n") == "t.ply:13: expected a vertex index below 3, got '-1'");
  CHECK(ply(head + verts + "2 0 1\n") == "t.ply:13: expected at least 3 vertex indices, got 2");
  CHECK(ply(head + verts + "3 0 1\n") == "t.ply:13: expected a list item, got end of file");
  CHECK(ply(head + "0 0 0\n1 zero 0\n") == "t.ply:11: expected a number, got 'zero'");
  CHECK(ply(head + "0 0 nan\n") == "t.ply:10: expected finite coordinates, got NaN or inf");
  CHECK(ply("plx\n") == "t.ply:1: expected 'ply', got 'plx'");
  CHECK(ply("") == "t.ply:1: expected 'ply', got end of file");
  CHECK(ply("ply\nformat ascii 2.0\n") == "t.ply:2: expected version 1.0, got '2.0'");
  CHECK(ply("ply\nformat text 1.0\n") ==
        "t.ply:2: expected ascii, binary_little_endian or binary_big_endian, got 'text'");
  CHECK(ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n") ==
        "t.ply:5: expected 'end_header', got end of file");
  CHECK(ply("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n") ==
        "t.ply:3: expected vertex properties x, y and z, got fewer");
  CHECK(ply("ply\nformat ascii 1.0\nelement vertex 0\nproperty half x\n") ==
        "t.ply:4: expected a property type, got 'half'");
  CHECK(ply("ply\nformat ascii 1.0\nelement face 0\nproperty list float int vertex_indices\n") ==
        "t.ply:4: expected an integer list count type, got 'float'");
  CHECK(ply("ply\nformat ascii 1.0\nproperty float x\n") ==
        "t.ply:3: expected 'element' before 'property', got 'property float x'");
  CHECK(ply("ply\nformat ascii 1.0\nelement vertex -1\n") ==
        "t.ply:3: expected an element count, got '-1'");
  CHECK(ply("ply\nformat ascii 1.0\nfoo\n") == "t.ply:3: expected a header keyword, got 'foo'");
}

TEST_CASE("PLY huge claimed counts fail fast without allocating", "[qnv][mesh]") {
  const auto start = std::chrono::steady_clock::now();
  for (const char* format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    INFO(format);
    const std::string head = std::string("ply\nformat ") + format +
                             " 1.0\nelement vertex 1000000000000\nproperty float x\n"
                             "property float y\nproperty float z\nend_header\n";
    CHECK(ply(head + "0 0 0 1 1 1 2 2 2\n").find("4294967295 vertices") != std::string::npos);
    const std::string head2 = std::string("ply\nformat ") + format +
                              " 1.0\nelement vertex 4000000000\nproperty float x\n"
                              "property float y\nproperty float z\nelement junk 1000000000000\n"
                              "property double a\nend_header\n";
    CHECK_FALSE(ply(head2 + std::string(1000, '1')).empty());
    // A face whose list claims 2^31 indices.
    const std::string head3 = std::string("ply\nformat ") + format +
                              " 1.0\nelement vertex 1\nproperty uchar x\nproperty uchar y\n"
                              "property uchar z\nelement face 1\n"
                              "property list uint uint vertex_indices\nend_header\n";
    const std::string body = format == std::string("ascii") ? "0 0 0\n2147483648 0 0 0 0\n"
                             : format == std::string("binary_little_endian")
                                 ? std::string("\0\0\0\0\0\0\x80", 7) + std::string(16, '\0')
                                 : std::string("\0\0\0\x80\0\0\0", 7) + std::string(16, '\0');
    CHECK_FALSE(ply(head3 + body).empty());
  }
  CHECK(ply("ply\nformat binary_little_endian 1.0\nelement vertex 1000000\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n" +
            std::string(100, '\0')) ==
        "t.ply: element vertex claims 1000000 entries of at least 12 bytes but only 100 bytes "
        "remain");
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
}

TEST_CASE("PLY binary: every truncation is an error, never a crash", "[qnv][mesh]") {
  for (const char* file : {"cube_le.ply", "cube_be.ply", "cube_ascii.ply"}) {
    INFO(file);
    const std::string bytes = readAsset(file);
    const std::size_t errors =
        truncations(bytes, [&](std::string_view b) { return readPly(b, file); });
    // The binary cubes end with an element after the faces: every cut is an error. The
    // ascii cube may lose only its final newline.
    CHECK(errors >= bytes.size() - 1);
  }
}

TEST_CASE("PLY binary: bad indices and garbage give InputError", "[qnv][mesh]") {
  std::string le = readAsset("cube_le.ply");
  const std::size_t body = le.find("end_header\n") + 11;
  // Face 0's first index (after 8 vertices of 15 + 1 + 2 * (i % 3) bytes and a count).
  std::size_t at = body;
  for (int i = 0; i < 8; ++i) at += 16 + 2 * (i % 3);
  at += 1;
  std::string bad = le;
  bad[at] = 8;
  CHECK(errorOf([&] { return readPly(bad, "bad.ply"); }) ==
        "bad.ply: face 0: vertex index 8 is out of range (8 vertices)");
  bad = le;
  bad[at + 3] = '\x80';  // index becomes 2^31 + 0
  CHECK_FALSE(errorOf([&] { return readPly(bad, "bad.ply"); }).empty());
  std::mt19937 rng(7);
  for (int trial = 0; trial < 300; ++trial) {
    std::string g = le;
    for (int k = 0; k < 8; ++k) g[body + rng() % (g.size() - body)] = static_cast<char>(rng());
    (void)errorOf([&] { return readPly(g, "g.ply"); });  // either is fine; no crash
    std::string noise(rng() % 2000, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    CHECK_FALSE(errorOf([&] { return readPly("ply\n" + noise, "n.ply"); }).empty());
    (void)errorOf([&] { return readPly(le.substr(0, body) + noise, "n.ply"); });
  }
}

TEST_CASE("OBJ: negative indices, i/t/n forms, colours, ignored statements", "[qnv][mesh]") {
  const TriangleMesh m = readObj(readAsset("quads.obj"), "quads.obj");
  checkInvariants(m);
  REQUIRE(m.positions.size() == 6);
  REQUIRE(m.triangleCount() == 5);
  const std::vector<std::uint32_t> want{0, 1, 2, 0, 2, 3, 0, 1, 5, 0, 5, 4, 4, 5, 2};
  CHECK(m.indices == want);
  REQUIRE(m.vertexColors.size() == 6);
  CHECK(m.vertexColors[0] == Rgba8(255, 0, 0, 255));
  CHECK(m.vertexColors[3] == Rgba8(255, 255, 255, 255));
  CHECK(m.vertexColors[4] == Rgba8(128, 128, 128, 255));
  CHECK(m.positions[5] == glm::vec3(1, 0, 1));
  CHECK(m.faceColors.empty());
}

TEST_CASE("OBJ: partial colours, forward references and errors", "[qnv][mesh]") {
  const TriangleMesh m = readObj("f 1 2 3\nv 0 0 0\nv 1 0 0 0 0 1\r\nv 0 1 0 1\n", "t.obj");
  REQUIRE(m.triangleCount() == 1);
  REQUIRE(m.vertexColors.size() == 3);
  CHECK(m.vertexColors[0] == m.baseColor);
  CHECK(m.vertexColors[1] == Rgba8(0, 0, 255, 255));
  CHECK(m.vertexColors[2] == m.baseColor);
  CHECK(readObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "t.obj").vertexColors.empty());
  CHECK(readObj("\xEF\xBB\xBFv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "t.obj").positions.size() == 3);
  CHECK(obj("v 0 0 0\nv 1 0 0\nf 1 2 3\n") ==
        "t.obj:3: expected a vertex index of at most 2, got 3");
  CHECK(obj("v 0 0 0\nv 1 0 0\nf 1 2 -3\n") ==
        "t.obj:3: expected a relative index within the 2 vertices so far, got '-3'");
  CHECK(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n") ==
        "t.obj:4: expected a non-zero vertex index, got '0'");
  CHECK(obj("v 0 0 0\nv 1 0 0\nf 1 2\n") == "t.obj:3: expected at least 3 vertex indices, got 2");
  CHECK(obj("v 0 0\n") == "t.obj:1: expected 3 coordinates after 'v', got 2");
  CHECK(obj("\n\nv 0 x 0\n") == "t.obj:3: expected a number, got 'x'");
  CHECK(obj("v 0 0 inf\n") == "t.obj:1: expected finite coordinates, got NaN or inf");
  CHECK(obj("v 0 0 0\nf a/1 1 1\n") == "t.obj:2: expected a vertex index, got 'a/1'");
  CHECK(obj("v 0 0 0\nf 99999999999 1 1\n") ==
        "t.obj:2: expected a vertex index below 4294967296, got '99999999999'");
  CHECK(obj("").empty());
  const std::string bytes = readAsset("quads.obj");
  truncations(bytes, [](std::string_view b) { return readObj(b, "quads.obj"); });
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    std::string noise(rng() % 3000, '\0');
    for (char& c : noise) c = static_cast<char>("vf 0123-/.\n#x"[rng() % 13]);
    (void)obj(noise);
  }
}

TEST_CASE("glTF: two nodes with a transform and two materials", "[qnv][mesh]") {
  const TriangleMesh m = readGltf(readAsset("two_nodes.gltf"), "two_nodes.gltf");
  checkInvariants(m);
  REQUIRE(m.positions.size() == 8);
  REQUIRE(m.triangleCount() == 8);
  CHECK(glm::distance(m.positions[1], glm::vec3(2, 2, 3)) < 1e-6f);  // parent: translated
  CHECK(glm::distance(m.positions[5], glm::vec3(1, 4, 3)) < 1e-5f);  // child: T * R * S
  CHECK(glm::distance(m.positions[7], glm::vec3(1, 2, 5)) < 1e-5f);
  CHECK(m.vertexColors.empty());
  REQUIRE(m.faceColors.size() == 8);
  CHECK(m.faceColors[0] == Rgba8(255, 0, 0, 255));
  CHECK(m.faceColors[7] == Rgba8(0, 0, 255, 255));
  CHECK(std::vector<std::uint32_t>(m.indices.begin(), m.indices.begin() + 3) ==
        std::vector<std::uint32_t>{0, 2, 1});
  CHECK(m.indices[12] == 4);  // the child's vertices follow the parent's
}

TEST_CASE("glTF: fans, skipped modes, mirrored nodes, no scenes", "[qnv][mesh]") {
  const std::string base = readAsset("two_nodes.gltf");
  auto read = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    const TriangleMesh m = readGltf(s.replace(at, from.size(), to), "t.gltf");
    checkInvariants(m);
    return m;
  };
  const TriangleMesh fan = read("\"mode\": 4", "\"mode\": 6");
  REQUIRE(fan.triangleCount() == 4 + 10);
  CHECK(std::vector<std::uint32_t>(fan.indices.begin() + 12, fan.indices.begin() + 15) ==
        std::vector<std::uint32_t>{6, 5, 4});
  const TriangleMesh lines = read("\"mode\": 4", "\"mode\": 1");
  CHECK(lines.positions.size() == 4);
  CHECK(lines.triangleCount() == 4);
  CHECK(lines.faceColors.empty());  // one material left: it becomes baseColor
  CHECK(lines.baseColor == Rgba8(255, 0, 0, 255));
  const TriangleMesh mirrored = read("\"scale\": [\n    2,", "\"scale\": [\n    -2,");
  CHECK(std::vector<std::uint32_t>(mirrored.indices.begin() + 12, mirrored.indices.begin() + 15) ==
        std::vector<std::uint32_t>{4, 5, 6});  // (0, 2, 1) reversed
  const TriangleMesh noScenes = read("\"scene\": 0,\n \"scenes\"", "\"unused\"");
  CHECK(noScenes.triangleCount() == 8);
  CHECK(noScenes.positions == readGltf(base, "t.gltf").positions);
}

TEST_CASE("GLB: interleaved unorm colours, u8 indices, a strip, a matrix", "[qnv][mesh]") {
  const TriangleMesh m = readGltf(readAsset("tetra.glb"), "tetra.glb");
  checkInvariants(m);
  REQUIRE(m.positions.size() == 8);
  REQUIRE(m.triangleCount() == 6);
  CHECK(m.positions[1] == glm::vec3(1, 0, 5));
  CHECK(m.positions[7] == glm::vec3(1, 1, 7));
  REQUIRE(m.vertexColors.size() == 8);
  CHECK(m.vertexColors[0] == Rgba8(255, 0, 0, 255));
  CHECK(m.vertexColors[3] == Rgba8(255, 255, 255, 128));
  CHECK(m.vertexColors[5] == Rgba8(0, 255, 0, 255));  // the strip's material
  CHECK(m.faceColors.empty());
  const std::vector<std::uint32_t> strip{4, 5, 6, 5, 7, 6};
  CHECK(std::vector<std::uint32_t>(m.indices.end() - 6, m.indices.end()) == strip);
}

TEST_CASE("glTF: every truncation of the GLB and of the JSON is an error", "[qnv][mesh]") {
  for (const char* file : {"tetra.glb", "two_nodes.gltf"}) {
    INFO(file);
    const std::string bytes = readAsset(file);
    const std::size_t errors =
        truncations(bytes, [&](std::string_view b) { return readGltf(b, file); });
    CHECK(errors >= bytes.size() - 1);  // the JSON may lose its final newline
  }
}

TEST_CASE("glTF: hostile accessors, indices, nodes and chunks give InputError", "[qnv][mesh]") {
  const std::string base = readAsset("two_nodes.gltf");
  auto edit = [&](const std::string& from, const std::string& to) {
    std::string s = base;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  CHECK(gltf(base).empty());
  CHECK(gltf(edit("\"count\": 4", "\"count\": 2")) ==
        "t.gltf: index 2 in accessor 1 is out of range (2 vertices)");
  CHECK(gltf(edit("\"count\": 4", "\"count\": 5")) ==
        "t.gltf: POSITION accessor 0 runs past the end of its buffer view");
  CHECK(gltf(edit("\"count\": 4", "\"count\": 1000000000000")) ==
        "t.gltf: POSITION accessor 0 runs past the end of its buffer view");
  CHECK(gltf(edit("\"count\": 12", "\"count\": 13")) ==
        "t.gltf: indices accessor 1 runs past the end of its buffer view");
  CHECK(gltf(edit("\"byteOffset\": 48", "\"byteOffset\": 4000")) ==
        "t.gltf: indices accessor 1: its buffer view runs past the end of its buffer");
  CHECK(gltf(edit("\"target\": 34962", "\"byteStride\": 8")) ==
        "t.gltf: POSITION accessor 0: byteStride is smaller than an element");
  CHECK(gltf(edit("\"componentType\": 5126", "\"componentType\": 5125")) ==
        "t.gltf: POSITION accessor 0 is not float VEC3");
  // tinygltf checks this one itself.
  CHECK(gltf(edit("\"indices\": 1", "\"indices\": 7")) ==
        "t.gltf: primitive indices accessor out of bounds");
  CHECK(gltf(edit("\"children\": [\n    1\n   ]", "\"children\": [0]")) ==
        "t.gltf: node 0 is reached twice (not a tree)");
  CHECK(gltf(edit("\"children\": [\n    1\n   ]", "\"children\": [5]")) ==
        "t.gltf: node 5 does not exist");
  CHECK(gltf(edit("\"mesh\": 1", "\"mesh\": 9")) ==
        "t.gltf: node 1 uses mesh 9, which does not exist");
  CHECK(gltf(edit("\"scale\"", "\"matrix\": [1], \"x\"")) ==
        "t.gltf: node 1: a matrix needs 16 numbers");
  CHECK_FALSE(gltf(edit("\"byteLength\": 72", "\"byteLength\": 73")).empty());
  CHECK_FALSE(gltf(edit("\"version\": \"2.0\"", "\"versio\": \"2.0\"")).empty());
  CHECK(gltf("{\"asset\":{\"version\":\"2.0\"},\"extras\":" + std::string(100000, '[')) ==
        "t.gltf: JSON nested deeper than 64 levels");
  CHECK_FALSE(gltf("").empty());
  CHECK_FALSE(gltf("{").empty());
  CHECK_FALSE(gltf("glTF").empty());

  // GLB containers: a BIN chunk one byte longer than the file, a JSON chunk too long.
  const std::string glb = readAsset("tetra.glb");
  const std::uint32_t jsonLen = static_cast<std::uint8_t>(glb[12]) |
                                static_cast<std::uint32_t>(static_cast<std::uint8_t>(glb[13])) << 8;
  std::string g = glb;
  g[20 + jsonLen] = static_cast<char>(g[20 + jsonLen] + 4);
  CHECK(errorOf([&] { return readGltf(g, "t.glb"); }) ==
        "t.glb: GLB BIN chunk runs past the end of the file");
  g = glb;
  g[14] = 1;
  CHECK(errorOf([&] { return readGltf(g, "t.glb"); }) ==
        "t.glb: GLB JSON chunk runs past the end of the file");
  g = glb;
  g[4] = 1;
  CHECK(errorOf([&] { return readGltf(g, "t.glb"); }) == "t.glb: expected GLB version 2, got 1");

  std::mt19937 rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    std::string noise(rng() % 1500, '\0');
    for (char& c : noise) c = static_cast<char>(rng());
    CHECK_FALSE(errorOf([&] { return readGltf("glTF" + noise, "n.glb"); }).empty());
    CHECK_FALSE(gltf(noise).empty());
    std::string flip = glb;  // corrupt the BIN chunk and JSON: errors or valid meshes only
    for (int k = 0; k < 4; ++k) flip[20 + rng() % (flip.size() - 20)] = static_cast<char>(rng());
    (void)errorOf([&] { return readGltf(flip, "f.glb"); });
  }
}

TEST_CASE("glTF: external buffers only through the loader", "[qnv][mesh]") {
  const std::string base = readAsset("two_nodes.gltf");
  const auto uriStart = base.find("data:");
  const auto uriEnd = base.find('"', uriStart);
  std::string ext = base;
  ext.replace(uriStart, uriEnd - uriStart, "tetra%20data.bin");
  // The buffer's bytes, taken from a successful read of the embedded version.
  std::string buffer;
  const auto fromEmbedded = [&](const std::string& uri) -> std::optional<std::string> {
    CHECK(uri == "tetra data.bin");
    return buffer;
  };
  CHECK(gltf(ext) ==
        "t.gltf: cannot load external buffer 'tetra data.bin' (no resource loader: external "
        "files are not allowed)");
  CHECK(errorOf([&] {
          return readGltf(ext, "t.gltf", [](const std::string&) { return std::nullopt; });
        }) == "t.gltf: cannot load external buffer 'tetra data.bin'");
  buffer = std::string(72, '\0');  // right size, all zeros: a valid degenerate mesh
  const TriangleMesh zeros = readGltf(ext, "t.gltf", fromEmbedded);
  CHECK(zeros.triangleCount() == 8);
  buffer = std::string(71, '\0');
  CHECK(errorOf([&] { return readGltf(ext, "t.gltf", fromEmbedded); }).find("tetra data.bin") !=
        std::string::npos);
  CHECK_THROWS_WITH(readGltf(ext, "t.gltf",
                             [](const std::string&) -> std::optional<std::string> {
                               throw std::runtime_error("loader says no");
                             }),
                    "loader says no");
  // A URI naming a real file is still not read without a loader.
  std::string abs = base;
  abs.replace(uriStart, uriEnd - uriStart, (gs::test::sourceDir() / "CMakeLists.txt").string());
  CHECK(gltf(abs).find("cannot load external buffer") != std::string::npos);
  // Image URIs are not requested at all.
  int calls = 0;
  std::string withImage = base;
  withImage.insert(withImage.rfind('}'), ", \"images\": [{\"uri\": \"texture.png\"}]");
  const TriangleMesh m = readGltf(withImage, "t.gltf", [&](const std::string&) {
    ++calls;
    return std::optional<std::string>();
  });
  CHECK(m.triangleCount() == 8);
  CHECK(calls == 0);
}

TEST_CASE("PLY: the Stanford bunny", "[qnv][mesh][corpus]") {
  if (!gs::test::haveCorpus("mesh/bunny")) return;
  struct Expect {
    const char* file;
    std::size_t vertices, triangles;
  };
  for (const Expect& e :
       {Expect{"bun_zipper.ply", 35947, 69451}, Expect{"bun_zipper_res2.ply", 8171, 16301},
        Expect{"bun_zipper_res4.ply", 453, 948}}) {
    INFO(e.file);
    const auto path = gs::test::corpusDir() / "mesh" / "bunny" / e.file;
    std::ifstream in(path, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const TriangleMesh m = readPly(bytes, e.file);
    checkInvariants(m);
    CHECK(m.positions.size() == e.vertices);
    CHECK(m.triangleCount() == e.triangles);
    CHECK(m.vertexColors.empty());
    CHECK(m.faceColors.empty());
    if (e.vertices != 35947) continue;
    glm::vec3 lo(1e9f), hi(-1e9f);
    for (const glm::vec3& p : m.positions) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    CHECK(lo.x == Approx(-0.0946899));
    CHECK(lo.y == Approx(0.0329874));
    CHECK(lo.z == Approx(-0.0618736));
    CHECK(hi.x == Approx(0.0610091));
    CHECK(hi.y == Approx(0.187321));
    CHECK(hi.z == Approx(0.0587997));
    CHECK(m.positions[0] == glm::vec3(-0.0378297f, 0.12794f, 0.00447467f));
  }
}
