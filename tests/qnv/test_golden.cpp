// The frozen golden stream: three triangles whose every field was worked out by hand
// (docs/qnv-format.md, "Worked example"). If this test fails, the format changed: bump
// kFormatVersion instead of regenerating the file.
#include <catch2/catch.hpp>

#include <cstring>
#include <fstream>
#include <sstream>

#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "test_support.hpp"

using namespace gs::qnv;

namespace {

TriangleMesh goldenMesh() {
  TriangleMesh m;
  m.positions = {{-2, -2, 0}, {4, -2, 0}, {-2, 4, 0},  // T0: centroid (0,0,0), +Z, area 18
                 {3, 2, 2},   {3, 4, 2},  {3, 3, 5},   // T1: centroid (3,3,3), +X, area 3
                 {2, 0, -1},  {5, 0, -1}, {2, 0, 2}};  // T2: centroid (3,0,0), -Y, area 4.5
  m.indices = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  m.faceColors = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}};
  return m;
}

std::string goldenPath() {
  return (gs::test::sourceDir() / "tests/qnv/golden/three_triangles.qnv").string();
}

std::uint64_t word(const std::string& bytes, std::size_t at) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[at + i]);
  return v;
}

}  // namespace

TEST_CASE("the encoder reproduces the golden stream byte for byte", "[qnv][golden]") {
  const std::string stream =
      writeStream(encodeSurface(goldenMesh(), {}), {16, PacketEncoding::plain});
  if (std::getenv("GS_WRITE_GOLDEN")) std::ofstream(goldenPath(), std::ios::binary) << stream;
  const std::string golden = gs::test::readBytes(goldenPath());
  REQUIRE(golden.size() == 1132 + 2 * 16 + 3 * 8);
  CHECK(stream == golden);
}

TEST_CASE("the golden stream holds the hand-computed fields", "[qnv][golden]") {
  const std::string g = gs::test::readBytes(goldenPath());
  REQUIRE(g.size() == 1188);
  CHECK(g.compare(0, 8, "\x89QNV\r\n\x1a\n") == 0);
  CHECK(g[8] == 1);    // version 1, little-endian u16
  CHECK(g[10] == 1);   // surface
  CHECK(g[12] == 16);  // 16 record bytes per packet: 2 records
  CHECK(g[16] == 3);   // 3 vectors
  // Palette: distinct colours sorted by their RGBA word: red, green, blue.
  CHECK(std::memcmp(g.data() + 104, "\xff\x00\x00\xff\x00\xff\x00\xff\x00\x00\xff\xff", 12) == 0);
  // Packet 0 at 1132: "QP", count 2, sequence 0, 16 payload bytes, plain.
  CHECK(std::memcmp(g.data() + 1132, "QP\x02\x00\x00\x00\x00\x00\x10\x00\x00\x00", 12) == 0);
  // T0 first (area 18 = the maximum: A 32767), at the box corner, +Z (theta 0, phi 0),
  // red (C 0).
  CHECK(word(g, 1148) == 0x00000000007FFF00ull);
  // T2 (area 4.5): x 1023, y 0, z 0, theta 16, phi 48, C 2 (blue); A = floor(32768 *
  // ln(4.5/3) / ln(18/3)) = floor(7415.3) = 7415 = 0x1CF7.
  CHECK(word(g, 1156) == ((1023ull << 54) | (16ull << 29) | (48ull << 23) | (0x1CF7ull << 8) | 2));
  // Packet 1: one record, sequence 1.
  CHECK(std::memcmp(g.data() + 1164, "QP\x01\x00\x01\x00\x00\x00\x08\x00\x00\x00", 12) == 0);
  // T1 (area 3 = the minimum: A 0): the far corner, +X (theta 16, phi 0), green (C 1).
  CHECK(word(g, 1180) == ((1023ull << 54) | (1023ull << 44) | (1023ull << 34) | (16ull << 29) | 1));
}

TEST_CASE("the golden stream decodes to the triangles' centroids, normals and areas",
          "[qnv][golden]") {
  StreamDecoder decoder("three_triangles.qnv");
  std::vector<DecodedVector> v;
  REQUIRE(decoder.feed(gs::test::readBytes(goldenPath()),
                       [&](std::uint64_t, std::span<const DecodedVector> s) {
                         v.insert(v.end(), s.begin(), s.end());
                       }));
  REQUIRE(decoder.finish());
  REQUIRE(v.size() == 3);
  const float half = 3.0f / 1024 / 2;
  CHECK(v[0].position.x == Approx(half));
  CHECK(v[0].normal.z > 0.99f);
  CHECK(v[0].magnitude == Approx(18.0f).epsilon(1e-4));
  CHECK(v[0].rgba == 0xff0000ffu);
  CHECK(v[1].normal.y < -0.99f);
  CHECK(v[1].magnitude == Approx(4.5f).epsilon(1e-4));
  CHECK(v[1].rgba == 0xffff0000u);
  CHECK(v[2].position.y == Approx(3.0f - half));
  CHECK(v[2].normal.x > 0.99f);
  CHECK(v[2].magnitude == Approx(3.0f).epsilon(1e-4));
}
