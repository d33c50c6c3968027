// Volume readers (formats/volume_readers.hpp): NRRD headers and data, NIfTI-1, raw grids, on
// the hand-made files of assets/volumes and on hostile bytes.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "formats/volume_readers.hpp"
#include "test_support.hpp"

using namespace gs::formats;
using Catch::Matchers::Contains;

namespace {

std::string readAsset(const std::string& name) {
  const auto path = gs::test::sourceDir() / "assets" / "volumes" / name;
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The value assets/volumes/README.md gives the sphere at (x, y, z).
float sphereValue(int x, int y, int z) {
  const double r = std::sqrt((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) + (z - 3.5) * (z - 3.5));
  return static_cast<float>(std::lround(60.0 * std::max(0.0, 4.0 - r)));
}

// Checks every voxel of an 8x8x8 sphere volume against value * scale + offset.
void checkSphere(const Volume& v, float scale = 1.0f, float offset = 0.0f) {
  REQUIRE(v.dims == glm::uvec3(8, 8, 8));
  REQUIRE(v.samples.size() == 512);
  int bad = 0;
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        if (std::fabs(v.at(x, y, z) - (sphereValue(x, y, z) * scale + offset)) > 1e-4f) ++bad;
  CHECK(bad == 0);
  CHECK(v.at(3, 3, 3) == Approx(188 * scale + offset));
  CHECK(v.at(0, 0, 0) == Approx(offset));
}

Volume readNrrd(std::string_view bytes, const std::string& name = "test.nrrd") {
  const NrrdHeader h = parseNrrdHeader(bytes, name);
  return decodeNrrdData(h, bytes.substr(h.dataOffset), name);
}

std::string bigEndian16(std::initializer_list<int> values) {
  std::string out;
  for (int v : values) {
    out += static_cast<char>((v >> 8) & 0xff);
    out += static_cast<char>(v & 0xff);
  }
  return out;
}

}  // namespace

TEST_CASE("scalar types: sizes, names and command-line spellings", "[volume]") {
  CHECK(scalarBytes(ScalarType::int8) == 1);
  CHECK(scalarBytes(ScalarType::uint16) == 2);
  CHECK(scalarBytes(ScalarType::float32) == 4);
  CHECK(scalarBytes(ScalarType::uint32) == 4);
  CHECK(scalarBytes(ScalarType::int64) == 8);
  CHECK(scalarBytes(ScalarType::float64) == 8);
  for (ScalarType t : {ScalarType::int8, ScalarType::uint8, ScalarType::int16, ScalarType::uint16,
                       ScalarType::int32, ScalarType::uint32, ScalarType::int64, ScalarType::uint64,
                       ScalarType::float32, ScalarType::float64})
    CHECK(parseScalarType(scalarTypeName(t)) == t);
  CHECK(std::string(scalarTypeName(ScalarType::uint16)) == "uint16");
  CHECK(parseScalarType("FLOAT") == ScalarType::float32);
  CHECK(parseScalarType("double") == ScalarType::float64);
  CHECK(parseScalarType("short") == ScalarType::int16);
  CHECK(parseScalarType("ushort") == ScalarType::uint16);
  CHECK(parseScalarType("uchar") == ScalarType::uint8);
  CHECK(parseScalarType("char") == ScalarType::int8);
  CHECK_THROWS_WITH(parseScalarType("int12"), Contains("unknown sample type 'int12'"));
  CHECK_THROWS_AS(parseScalarType(""), InputError);
}

TEST_CASE("NRRD attached raw: the sphere", "[volume][nrrd]") {
  const std::string bytes = readAsset("sphere.nrrd");
  const NrrdHeader h = parseNrrdHeader(bytes, "sphere.nrrd");
  CHECK(h.dims == glm::uvec3(8, 8, 8));
  CHECK(h.type == ScalarType::uint8);
  CHECK(h.encoding == NrrdHeader::Encoding::raw);
  CHECK(h.dataFile.empty());
  CHECK(h.dataOffset + 512 == bytes.size());
  const Volume v = decodeNrrdData(h, std::string_view(bytes).substr(h.dataOffset), "sphere.nrrd");
  checkSphere(v);
  CHECK(v.spacing == glm::vec3(1, 1, 1));
  CHECK(v.origin == glm::vec3(0, 0, 0));
  CHECK(v.sourceType == ScalarType::uint8);
}

TEST_CASE("NRRD gzip header, detached header and big-endian float", "[volume][nrrd]") {
  SECTION("gzip") {
    const NrrdHeader h = parseNrrdHeader(readAsset("sphere_gzip.nrrd"), "sphere_gzip.nrrd");
    CHECK(h.encoding == NrrdHeader::Encoding::gzip);
    CHECK(h.spacing == glm::vec3(0.5f, 0.5f, 1.0f));
    CHECK(h.dataBytes() == 512);
  }
  SECTION("detached") {
    const NrrdHeader h = parseNrrdHeader(readAsset("sphere_detached.nhdr"), "d.nhdr");
    CHECK(h.dataFile == "sphere_detached.raw");
    CHECK(h.lineSkip == 1);
    CHECK(h.byteSkip == 2);
    CHECK(h.type == ScalarType::uint16);
    CHECK_FALSE(h.bigEndian);
    const Volume v = decodeNrrdData(h, readAsset("sphere_detached.raw"), "d.raw");
    checkSphere(v);
    CHECK(v.sourceType == ScalarType::uint16);
  }
  SECTION("big-endian float with space directions and origin") {
    const Volume v = readNrrd(readAsset("ramp_float_be.nrrd"));
    REQUIRE(v.dims == glm::uvec3(4, 3, 2));
    CHECK(v.spacing == glm::vec3(0.5f, 0.5f, 2.0f));
    CHECK(v.origin == glm::vec3(-1.0f, 2.0f, 3.5f));
    CHECK(v.sourceType == ScalarType::float32);
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 3; ++y)
        for (int x = 0; x < 4; ++x) CHECK(v.at(x, y, z) == x + 10 * y + 100 * z + 0.25f);
  }
}

TEST_CASE("NRRD type aliases are teem's", "[volume][nrrd]") {
  const std::pair<const char*, ScalarType> cases[] = {
      {"signed char", ScalarType::int8},
      {"int8", ScalarType::int8},
      {"int8_t", ScalarType::int8},
      {"uchar", ScalarType::uint8},
      {"unsigned char", ScalarType::uint8},
      {"uint8", ScalarType::uint8},
      {"uint8_t", ScalarType::uint8},
      {"short", ScalarType::int16},
      {"short int", ScalarType::int16},
      {"signed short", ScalarType::int16},
      {"signed short int", ScalarType::int16},
      {"int16", ScalarType::int16},
      {"int16_t", ScalarType::int16},
      {"ushort", ScalarType::uint16},
      {"unsigned short", ScalarType::uint16},
      {"unsigned short int", ScalarType::uint16},
      {"uint16", ScalarType::uint16},
      {"uint16_t", ScalarType::uint16},
      {"int", ScalarType::int32},
      {"signed int", ScalarType::int32},
      {"int32", ScalarType::int32},
      {"int32_t", ScalarType::int32},
      {"uint", ScalarType::uint32},
      {"unsigned int", ScalarType::uint32},
      {"uint32", ScalarType::uint32},
      {"uint32_t", ScalarType::uint32},
      {"longlong", ScalarType::int64},
      {"long long", ScalarType::int64},
      {"long long int", ScalarType::int64},
      {"signed long long", ScalarType::int64},
      {"signed long long int", ScalarType::int64},
      {"int64", ScalarType::int64},
      {"int64_t", ScalarType::int64},
      {"ulonglong", ScalarType::uint64},
      {"unsigned long long", ScalarType::uint64},
      {"unsigned long long int", ScalarType::uint64},
      {"uint64", ScalarType::uint64},
      {"uint64_t", ScalarType::uint64},
      {"float", ScalarType::float32},
      {"double", ScalarType::float64},
      {"Unsigned  Short", ScalarType::uint16},
  };
  for (const auto& [name, type] : cases) {
    INFO(name);
    const std::string text =
        std::string("NRRD0004\ntype: ") + name + "\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n\n";
    CHECK(parseNrrdHeader(text, "t.nrrd").type == type);
  }
  CHECK_THROWS_WITH(parseNrrdHeader("NRRD0004\ntype: block\ndimension: 3\nsizes: 1 1 1\n"
                                    "encoding: raw\n",
                                    "b.nrrd"),
                    Contains("b.nrrd:2: unsupported NRRD type 'block'"));
  CHECK_THROWS_WITH(
      parseNrrdHeader("NRRD0004\ndimension: 3\ntype: quaternion\nsizes: 1 1 1\nencoding: raw\n",
                      "q.nrrd"),
      Contains("q.nrrd:3: expected a NRRD type") && Contains("got 'quaternion'"));
  CHECK_THROWS_AS(parseNrrdHeader("NRRD0004\ntype: char\ndimension: 3\nsizes: 1 1 1\n"
                                  "encoding: raw\n",
                                  "c.nrrd"),
                  InputError);
}

TEST_CASE("NRRD samples of every type, both byte orders, ascii", "[volume][nrrd]") {
  SECTION("int16 big endian, negative values") {
    const std::string bytes =
        "NRRD0001\ntype: short\ndimension: 3\nsizes: 2 2 1\nendian: big\nencoding: raw\n\n" +
        bigEndian16({-1, 300, -32768, 32767});
    const Volume v = readNrrd(bytes);
    CHECK(v.samples == std::vector<float>{-1, 300, -32768, 32767});
    CHECK(v.dims == glm::uvec3(2, 2, 1));
  }
  SECTION("int32, uint32, int64, uint64, double little endian") {
    std::string data;
    auto put = [&](auto value) {
      char b[sizeof value];
      std::memcpy(b, &value, sizeof value);
      data.append(b, sizeof value);  // the test machines are little endian
    };
    put(std::int32_t{-70000});
    put(std::uint32_t{4000000000u});
    put(std::int64_t{-5});
    put(std::uint64_t{1} << 40);
    put(2.5);
    put(-0.125);
    auto one = [&](const char* type, std::size_t bytes, std::size_t offset) {
      const std::string text = std::string("NRRD0004\ntype: ") + type +
                               "\ndimension: 3\nsizes: 1 1 1\nendian: little\nencoding: raw\n\n" +
                               data.substr(offset, bytes);
      return readNrrd(text).samples.at(0);
    };
    CHECK(one("int32", 4, 0) == -70000.0f);
    CHECK(one("uint32", 4, 4) == 4000000000.0f);
    CHECK(one("int64", 8, 8) == -5.0f);
    CHECK(one("uint64", 8, 16) == 1099511627776.0f);
    CHECK(one("double", 8, 24) == 2.5f);
    CHECK(one("double", 8, 32) == -0.125f);
  }
  SECTION("ascii, with commas and CRLF line ends") {
    const Volume v = readNrrd(
        "NRRD0004\r\ntype: float\r\ndimension: 3\r\nsizes: 2 2 2\r\nencoding: text\r\n\r\n"
        "1 2.5,-3\r\n4e2\t5 6\n7 +8 9 10");
    CHECK(v.samples == std::vector<float>{1, 2.5f, -3, 400, 5, 6, 7, 8});
  }
  SECTION("ascii too short or not numbers") {
    const std::string head = "NRRD0004\ntype: int\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n\n";
    CHECK_THROWS_WITH(readNrrd(head + "1 2 3"),
                      Contains("expected 8 values of ascii voxel data, got 3"));
    CHECK_THROWS_WITH(readNrrd(head + "1 2 x3 4 5 6 7 8"),
                      Contains("expected a number in ascii voxel data, got 'x3'"));
  }
  SECTION("line skip and byte skip on raw data, byte skip -1") {
    const std::string head = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 1 1\nencoding: raw\n";
    CHECK(readNrrd(head + "line skip: 2\nbyte skip: 1\n\nab\r\ncd\nxAB").samples ==
          std::vector<float>{'A', 'B'});
    CHECK(readNrrd(head + "byte skip: -1\n\nwhatever comes first, then CD").samples ==
          std::vector<float>{'C', 'D'});
    CHECK_THROWS_WITH(readNrrd(head + "line skip: 3\n\none\ntwo\n"),
                      Contains("expected 3 lines to skip, got 2"));
    CHECK_THROWS_WITH(readNrrd(head + "byte skip: 10\n\nabc"), Contains("byte skip of 10"));
    CHECK_THROWS_WITH(readNrrd(head + "byte skip: -1\n\nx"),
                      Contains("expected 2 bytes of voxel data, got 1"));
  }
}

TEST_CASE("NRRD header forms: dimensions 2 and 4, comments, unknown fields", "[volume][nrrd]") {
  SECTION("dimension 4 with a first axis of size 1") {
    const NrrdHeader h = parseNrrdHeader(
        "NRRD0005\ntype: float\ndimension: 4\nsizes: 1 5 6 7\nspacings: nan 2 3 4\n"
        "encoding: raw\n\n",
        "4d.nrrd");
    CHECK(h.dims == glm::uvec3(5, 6, 7));
    CHECK(h.spacing == glm::vec3(2, 3, 4));
  }
  SECTION("dimension 4 with a last axis of size 1, space directions with none") {
    const NrrdHeader h = parseNrrdHeader(
        "NRRD0005\ntype: float\ndimension: 4\nsizes: 5 6 7 1\n"
        "space directions: (3,4,0) (0, 0, 2) (0,-1.5,0) none\nencoding: raw\n\n",
        "4d.nrrd");
    CHECK(h.dims == glm::uvec3(5, 6, 7));
    CHECK(h.spacing == glm::vec3(5, 2, 1.5f));
  }
  SECTION("dimension 2 is one slice") {
    const NrrdHeader h = parseNrrdHeader(
        "NRRD0002\ntype: uchar\ndimension: 2\nsizes: 5 6\nspacings: 0.5 -2\nencoding: raw\n\n",
        "2d.nrrd");
    CHECK(h.dims == glm::uvec3(5, 6, 1));
    CHECK(h.spacing == glm::vec3(0.5f, 2.0f, 1.0f));
  }
  SECTION("comments, key/value pairs, unknown fields, odd case, zero spacing") {
    const NrrdHeader h = parseNrrdHeader(
        "NRRD0004\n# a comment: with a colon\nContent: test\nTYPE: uint8\nmodality:=CT\n"
        "dimension: 3\nsizes: 2 3 4\nspacings: 0 1 1\nkinds: domain domain domain\n"
        "thicknesses: 1 1 1\nfuture field: 42\nencoding: GZ\nEndian: Big\n\nDATA",
        "misc.nrrd");
    CHECK(h.dims == glm::uvec3(2, 3, 4));
    CHECK(h.encoding == NrrdHeader::Encoding::gzip);
    CHECK(h.bigEndian);
    CHECK(h.spacing == glm::vec3(1, 1, 1));
    CHECK(h.dataOffset == std::string_view("NRRD0004\n# a comment: with a colon\nContent: test\n"
                                           "TYPE: uint8\nmodality:=CT\ndimension: 3\n"
                                           "sizes: 2 3 4\nspacings: 0 1 1\nkinds: domain "
                                           "domain domain\nthicknesses: 1 1 1\nfuture field: "
                                           "42\nencoding: GZ\nEndian: Big\n\n")
                              .size());
  }
  SECTION("detached header without a blank line, datafile spelling") {
    const NrrdHeader h = parseNrrdHeader(
        "NRRD0003\ntype: float\ndimension: 3\nsizes: 1 1 1\nencoding: txt\ndatafile: a b.txt",
        "d.nhdr");
    CHECK(h.dataFile == "a b.txt");
    CHECK(h.encoding == NrrdHeader::Encoding::ascii);
  }
}

TEST_CASE("NRRD hex encoding and a first axis of components (ImageTexture3D's RGB)",
          "[volume][nrrd]") {
  // create3000's Texturing3D/hex.nrrd: two hex digits per byte, any white space between.
  const std::string text =
      "NRRD0001\ntype: unsigned char\ndimension: 4\nsizes: 3 2 1 1\nencoding: hex\n\n"
      "ff 00 0a\n01F0 ab\n";
  // Without componentAxis the first axis is x (the last, of size 1, dropped); RGB of 2 x 2 x 2
  // voxels is an error.
  CHECK(parseNrrdHeader(text, "c.nrrd").dims == glm::uvec3(3, 2, 1));
  std::string cube = text;
  cube.replace(cube.find("3 2 1 1"), 7, "3 2 2 2");
  CHECK_THROWS_WITH(parseNrrdHeader(cube, "c.nrrd"), Contains("one axis of size 1"));
  NrrdParseOptions options;
  options.componentAxis = true;
  const NrrdHeader h = parseNrrdHeader(text, "c.nrrd", options);
  CHECK(h.encoding == NrrdHeader::Encoding::hex);
  CHECK(h.components == 3);
  CHECK(h.dims == glm::uvec3(6, 1, 1));  // 3 components x 2 voxels along x
  const Volume v = decodeNrrdData(h, std::string_view(text).substr(h.dataOffset), "c.nrrd");
  CHECK(v.samples == std::vector<float>{255, 0, 10, 1, 240, 171});
  // A scalar hex volume, and a digit that is not one.
  const std::string scalar = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 1 1\nencoding: hex\n\n";
  const NrrdHeader s = parseNrrdHeader(scalar + "7f80", "s.nrrd");
  CHECK(s.components == 1);
  CHECK(decodeNrrdData(s, "7f80", "s.nrrd").samples == std::vector<float>{127, 128});
  CHECK_THROWS_WITH(decodeNrrdData(s, "7g80", "s.nrrd"),
                    Contains("s.nrrd: expected a hexadecimal digit in hex data, got 'g'"));
  CHECK_THROWS_WITH(decodeNrrdData(s, "7f", "s.nrrd"), Contains("s.nrrd"));  // too short
  // A byte skip skips decoded bytes.
  const NrrdHeader skipped = parseNrrdHeader(
      "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 1 1\nencoding: hex\nbyte skip: 2\n\n",
      "k.nrrd");
  CHECK(decodeNrrdData(skipped, "0000 7f80", "k.nrrd").samples == std::vector<float>{127, 128});
}

TEST_CASE("NRRD hostile headers give InputError", "[volume][nrrd][hostile]") {
  const std::string head = "NRRD0004\ntype: uint8\ndimension: 3\nencoding: raw\n";
  auto parse = [](const std::string& text) { return parseNrrdHeader(text, "h.nrrd"); };
  CHECK_THROWS_WITH(parse(""), Contains("h.nrrd:1: expected the NRRD magic"));
  CHECK_THROWS_WITH(parse("NRRD0006\n"), Contains("got 'NRRD0006'"));
  CHECK_THROWS_WITH(parse("P5 8 8 255\n"), Contains("expected the NRRD magic"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\n\n"), Contains("missing required NRRD field"));
  CHECK_THROWS_WITH(parse(head + "sizes: 10000 10000 10000\n"),
                    Contains("h.nrrd:5: volume of 10000 x 10000 x 10000 voxels exceeds"));
  CHECK_THROWS_WITH(parse(head + "sizes: 4294967295 4294967295 4294967295\n"),
                    Contains("exceeds the limit"));
  CHECK_THROWS_WITH(parse(head + "sizes: 4294967296 1 1\n"), Contains("below 2^32"));
  CHECK_THROWS_WITH(parse(head + "sizes: 99999999999999999999999 1 1\n"),
                    Contains("expected a size >= 1"));
  CHECK_THROWS_WITH(parse(head + "sizes: 0 8 8\n"),
                    Contains("h.nrrd:5: expected a size >= 1, got '0'"));
  CHECK_THROWS_WITH(parse(head + "sizes: -8 8 8\n"), Contains("got '-8'"));
  CHECK_THROWS_WITH(parse(head + "sizes: 8 8\n"), Contains("expected 3 sizes, got 2"));
  CHECK_THROWS_WITH(parse(head + "sizes: 8 8 x\n"), Contains("got 'x'"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\ndimension: 5\nsizes: 1 1 1 1 1\nencoding: raw\n"),
                    Contains("expected dimension 2, 3 or 4, got '5'"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\ndimension: 4\nsizes: 2 3 4 5\nencoding: raw\n"),
                    Contains("one axis of size 1"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspacings: 1 1\n"), Contains("expected 3 spacings"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspacings: 1 one 1\n"),
                    Contains("expected a spacing, got 'one'"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspace directions: (1,0,0) (0,1,0)\n"),
                    Contains("expected 3 space directions"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspace directions: (1,0,0) (0,1,0) (0,0,1\n"),
                    Contains("expected a vector"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspace origin: (1,,2)\n"),
                    Contains("expected a vector component"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nspace origin: none\n"),
                    Contains("expected one vector"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nendian: middle\n"),
                    Contains("expected endian 'little' or 'big', got 'middle'"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: bzip2\n"),
                    Contains("h.nrrd:5: unsupported NRRD encoding 'bzip2'"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: zip\n"),
                    Contains("expected a NRRD encoding"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\ndata file: LIST\nslice0.raw\n"),
                    Contains("not supported"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\ndata file: slice%03d.raw 1 2 1\n"),
                    Contains("not supported"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\ndata file:   \n"),
                    Contains("expected a data file"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nline skip: -1\n"),
                    Contains("expected a line skip"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nbyte skip: -2\n"),
                    Contains("expected a byte skip >= -1, got '-2'"));
  CHECK_THROWS_WITH(parse(head + "sizes: 2 2 2\nno colon here\n"),
                    Contains("h.nrrd:6: expected 'field: value', got 'no colon here'"));
  CHECK_THROWS_WITH(parse("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n"
                          "byte skip: -1\n"),
                    Contains("only with raw or gzip"));
}

TEST_CASE("NRRD: every truncation of sphere.nrrd gives InputError", "[volume][nrrd][hostile]") {
  const std::string bytes = readAsset("sphere.nrrd");
  for (std::size_t n = 0; n < bytes.size(); ++n) {
    INFO("length " << n);
    CHECK_THROWS_AS(readNrrd(std::string_view(bytes).substr(0, n)), InputError);
  }
  CHECK_NOTHROW(readNrrd(bytes));
}

TEST_CASE("NRRD decode checks a header it did not parse", "[volume][nrrd][hostile]") {
  NrrdHeader h;
  h.dims = {1u << 20, 1u << 20, 1};
  CHECK_THROWS_WITH(decodeNrrdData(h, "abc", "x"), Contains("exceeds the limit"));
  h.dims = {0, 4, 4};
  CHECK_THROWS_AS(decodeNrrdData(h, "abc", "x"), InputError);
  h.dims = {2, 2, 2};
  h.byteSkip = -3;
  CHECK_THROWS_AS(decodeNrrdData(h, "abcdefgh", "x"), InputError);
  h.byteSkip = 0;
  CHECK_THROWS_WITH(decodeNrrdData(h, "abc", "x"),
                    Contains("x: expected 8 bytes of voxel data, got 3"));
  h.spacing = {0, 1, 1};
  CHECK_THROWS_WITH(decodeNrrdData(h, "abcdefgh", "x"), Contains("spacings > 0"));
}

TEST_CASE("NIfTI-1 single file: the sphere, scaled, with qform origin", "[volume][nifti]") {
  const Volume v = readNifti(readAsset("sphere.nii"), "sphere.nii");
  checkSphere(v, 0.5f, 10.0f);
  CHECK(v.spacing == glm::vec3(0.8f, 0.8f, 1.5f));
  CHECK(v.origin == glm::vec3(-3.0f, -2.5f, 4.0f));
  CHECK(v.sourceType == ScalarType::int16);
}

TEST_CASE("NIfTI-1 hostile headers give InputError", "[volume][nifti][hostile]") {
  const std::string good = readAsset("sphere.nii");
  auto with16 = [&](std::size_t offset, std::int16_t value) {
    std::string b = good;
    std::memcpy(b.data() + offset, &value, 2);
    return b;
  };
  auto withF = [&](std::size_t offset, float value) {
    std::string b = good;
    std::memcpy(b.data() + offset, &value, 4);
    return b;
  };
  auto read = [](const std::string& b) { return readNifti(b, "h.nii"); };
  CHECK_THROWS_WITH(read(with16(70, 128)), Contains("unsupported NIfTI datatype 128 (RGB24)"));
  CHECK_THROWS_WITH(read(with16(70, 77)), Contains("unsupported NIfTI datatype 77"));
  CHECK_THROWS_WITH(read(with16(40, 0)), Contains("expected dim[0] between 1 and 7, got 0"));
  CHECK_THROWS_WITH(read(with16(40, 9)), Contains("dim[0]"));
  CHECK_THROWS_WITH(read(with16(42, -8)), Contains("expected dim[1] >= 1, got -8"));
  CHECK_THROWS_WITH(read(with16(44, 0)), Contains("expected dim[2] >= 1, got 0"));
  {
    std::string b = with16(40, 4);
    const std::int16_t two = 2;
    std::memcpy(b.data() + 48, &two, 2);
    CHECK_THROWS_WITH(read(b), Contains("expected a 3-dimensional volume"));
  }
  {
    std::string b = good;
    const std::int16_t big = 32767;
    for (std::size_t o : {42, 44, 46}) std::memcpy(b.data() + o, &big, 2);
    CHECK_THROWS_WITH(read(b), Contains("exceeds the limit"));
  }
  CHECK_THROWS_WITH(read(withF(108, 1e30f)), Contains("expected vox_offset"));
  CHECK_THROWS_WITH(read(withF(108, std::nanf(""))), Contains("expected vox_offset"));
  CHECK_THROWS_WITH(read(withF(108, -4.0f)), Contains("expected vox_offset"));
  CHECK_THROWS_WITH(read(withF(108, 1000.0f)),
                    Contains("expected 1024 bytes of voxel data, got 376"));
  CHECK_NOTHROW(read(withF(108, 0.0f)));  // taken as 352
  {
    std::string b = good;
    std::memcpy(b.data() + 344, "ni1", 4);
    CHECK_THROWS_WITH(read(b), Contains("header/image pairs (.hdr/.img) are not supported"));
    std::memcpy(b.data() + 344, "abc", 4);
    CHECK_THROWS_WITH(read(b), Contains("not a NIfTI-1 file"));
  }
  {
    std::string b = good;
    const std::int32_t nifti2 = 540;
    std::memcpy(b.data(), &nifti2, 4);
    CHECK_THROWS_WITH(read(b), Contains("NIfTI-2"));
    const std::int32_t other = 1234;
    std::memcpy(b.data(), &other, 4);
    CHECK_THROWS_WITH(read(b), Contains("not a NIfTI-1 file"));
  }
  // Every truncation: short header, then short data.
  for (std::size_t n = 0; n < good.size(); ++n) {
    INFO("length " << n);
    CHECK_THROWS_AS(read(good.substr(0, n)), InputError);
  }
  CHECK_THROWS_WITH(read(good.substr(0, 100)), Contains("not a NIfTI-1 file"));
  CHECK_THROWS_WITH(read(good.substr(0, 1000)),
                    Contains("expected 1024 bytes of voxel data, got 648"));
}

TEST_CASE("raw volumes: layout, byte order, errors", "[volume][raw]") {
  RawLayout layout;
  layout.dims = {2, 1, 2};
  layout.type = ScalarType::int16;
  layout.bigEndian = true;
  layout.spacing = {1, 2, 3};
  layout.headerBytes = 3;
  const std::string bytes = "HDR" + bigEndian16({1, -2, 258, 1000}) + "tail";
  const Volume v = decodeRaw(bytes, layout, "r.raw");
  CHECK(v.samples == std::vector<float>{1, -2, 258, 1000});
  CHECK(v.at(1, 0, 1) == 1000.0f);
  CHECK(v.spacing == glm::vec3(1, 2, 3));
  CHECK(v.sourceType == ScalarType::int16);

  CHECK_THROWS_WITH(decodeRaw(bytes.substr(0, 9), layout, "r.raw"),
                    Contains("r.raw: expected 8 bytes of voxel data, got 6"));
  layout.headerBytes = 1000;
  CHECK_THROWS_WITH(decodeRaw(bytes, layout, "r.raw"), Contains("got 0"));
  layout.headerBytes = 0;
  layout.dims = {2, 0, 2};
  CHECK_THROWS_WITH(decodeRaw(bytes, layout, "r.raw"), Contains("dimensions >= 1"));
  layout.dims = {0xffffffffu, 0xffffffffu, 0xffffffffu};
  CHECK_THROWS_WITH(decodeRaw(bytes, layout, "r.raw"), Contains("exceeds the limit"));
  layout.dims = {1u << 16, 1u << 14, 1};  // exactly kMaxVoxels: allowed, but the data is short
  CHECK_THROWS_WITH(decodeRaw(bytes, layout, "r.raw"), Contains("bytes of voxel data"));
  layout.dims = {2, 1, 2};
  layout.spacing = {1, -1, 1};
  CHECK_THROWS_WITH(decodeRaw(bytes, layout, "r.raw"), Contains("spacings > 0"));
}

TEST_CASE("volume readers survive random and mutated bytes", "[volume][hostile]") {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> byte(0, 255);
  const std::string nrrd = readAsset("sphere.nrrd");
  const std::string ramp = readAsset("ramp_float_be.nrrd");
  const std::string nii = readAsset("sphere.nii");
  auto tryAll = [&](const std::string& b) {
    try {
      (void)readNrrd(b);
    } catch (const InputError&) {
    }
    try {
      (void)readNifti(b, "m.nii");
    } catch (const InputError&) {
    }
  };
  for (int i = 0; i < 300; ++i) {  // garbage, some of it with a NRRD magic
    std::string b(static_cast<std::size_t>(byte(rng)) * 3, '\0');
    for (char& c : b) c = static_cast<char>(byte(rng));
    CHECK_THROWS_AS(readNifti(b, "g.nii"), InputError);
    CHECK_THROWS_AS(readNrrd(b), InputError);
    CHECK_THROWS_AS(readNrrd("NRRD0004\n" + b), InputError);
  }
  for (const std::string* base : {&nrrd, &ramp, &nii}) {
    const std::size_t headerEnd = base == &nii ? 352 : base->find("\n\n") + 2;
    for (int i = 0; i < 2000; ++i) {
      std::string b = *base;
      const int edits = 1 + byte(rng) % 4;
      for (int e = 0; e < edits; ++e) {
        const std::size_t at = static_cast<std::size_t>(byte(rng) * 256 + byte(rng)) % headerEnd;
        b[at] =
            static_cast<char>(byte(rng) % 3 == 0 ? "0123456789 -:\n"[byte(rng) % 14] : byte(rng));
      }
      REQUIRE_NOTHROW(tryAll(b));
    }
  }
}
