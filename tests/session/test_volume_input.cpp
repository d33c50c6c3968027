// Volume files from disk (app/volume_input.hpp): the hand-made assets, the CThead and
// engine corpus volumes, detached data files that try to leave their folder, damaged gzip.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "encodings/parser.hpp"
#include "formats/input_kind.hpp"
#include "qnv/error.hpp"
#include "session/volume_input.hpp"
#include "test_support.hpp"

using namespace gs;
using Catch::Matchers::Contains;

namespace {

using test::TempDir;

bool isVolumeFile(const std::string& path) {
  return formats::isVolume(formats::classifyFile(path));
}

std::string asset(const std::string& name) {
  return (test::sourceDir() / "assets" / "volumes" / name).string();
}

float sphereValue(int x, int y, int z) {
  const double r = std::sqrt((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) + (z - 3.5) * (z - 3.5));
  return static_cast<float>(std::lround(60.0 * std::max(0.0, 4.0 - r)));
}

void checkSphere(const qnv::Volume& v, float scale = 1.0f, float offset = 0.0f) {
  REQUIRE(v.dims == glm::uvec3(8, 8, 8));
  REQUIRE(v.samples.size() == 512);
  int bad = 0;
  for (int z = 0; z < 8; ++z)
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        if (std::fabs(v.at(x, y, z) - (sphereValue(x, y, z) * scale + offset)) > 1e-4f) ++bad;
  CHECK(bad == 0);
}

std::pair<float, float> minMax(const qnv::Volume& v) {
  const auto [lo, hi] = std::minmax_element(v.samples.begin(), v.samples.end());
  return {*lo, *hi};
}

const std::string kSphereHead =
    "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 8 8 8\nencoding: raw\n";

}  // namespace

TEST_CASE("isVolumeFile: by extension, any case", "[volume_input]") {
  CHECK(isVolumeFile("a.nrrd"));
  CHECK(isVolumeFile("dir/CThead.NHDR"));
  CHECK(isVolumeFile("brain.nii"));
  CHECK(isVolumeFile("brain.Nii.Gz"));
  CHECK_FALSE(isVolumeFile("brain.gz"));
  CHECK_FALSE(isVolumeFile("world.wrl"));
  CHECK_FALSE(isVolumeFile("nrrd"));
  CHECK_FALSE(isVolumeFile(""));
}

TEST_CASE("loadVolumeFile reads the hand-made assets", "[volume_input]") {
  SECTION("attached raw NRRD") {
    checkSphere(session::loadVolumeFile(asset("sphere.nrrd")));
  }
  SECTION("attached gzip NRRD") {
    const qnv::Volume v = session::loadVolumeFile(asset("sphere_gzip.nrrd"));
    checkSphere(v);
    CHECK(v.spacing == glm::vec3(0.5f, 0.5f, 1.0f));
  }
  SECTION("detached header with line and byte skip") {
    const qnv::Volume v = session::loadVolumeFile(asset("sphere_detached.nhdr"));
    checkSphere(v);
    CHECK(v.sourceType == qnv::ScalarType::uint16);
  }
  SECTION("big-endian float NRRD") {
    const qnv::Volume v = session::loadVolumeFile(asset("ramp_float_be.nrrd"));
    REQUIRE(v.dims == glm::uvec3(4, 3, 2));
    CHECK(v.at(3, 2, 1) == 123.25f);
    CHECK(v.origin == glm::vec3(-1, 2, 3.5f));
  }
  SECTION(".nii") {
    const qnv::Volume v = session::loadVolumeFile(asset("sphere.nii"));
    checkSphere(v, 0.5f, 10.0f);
    CHECK(v.spacing == glm::vec3(0.8f, 0.8f, 1.5f));
    CHECK(v.origin == glm::vec3(-3, -2.5f, 4));
  }
  SECTION(".nii.gz, big endian float, sform origin") {
    const qnv::Volume v = session::loadVolumeFile(asset("sphere.nii.gz"));
    checkSphere(v, 0.1f);
    CHECK(v.spacing == glm::vec3(1, 1, 2));
    CHECK(v.origin == glm::vec3(5, 6, 7));
    CHECK(v.sourceType == qnv::ScalarType::float32);
  }
}

TEST_CASE("loadRawVolumeFile reads a headerless grid", "[volume_input]") {
  formats::RawLayout layout;
  layout.dims = {8, 8, 8};
  layout.type = qnv::ScalarType::uint16;
  layout.headerBytes = 22;  // "a text line to skip\n" and "XX"
  checkSphere(session::loadRawVolumeFile(asset("sphere_detached.raw"), layout));
  layout.headerBytes = 100;
  CHECK_THROWS_WITH(session::loadRawVolumeFile(asset("sphere_detached.raw"), layout),
                    Contains("sphere_detached.raw: expected 1024 bytes of voxel data, got 946"));
  CHECK_THROWS_WITH(session::loadRawVolumeFile(asset("no_such.raw"), layout),
                    Contains("cannot open"));
}

TEST_CASE("CThead and engine from the corpus", "[volume_input][corpus]") {
  if (!test::haveCorpus("volume/cthead")) return;
  {
    const auto path = (test::corpusDir() / "volume/cthead/CThead.nhdr").string();
    const qnv::Volume v = session::loadVolumeFile(path);
    REQUIRE(v.dims == glm::uvec3(256, 256, 113));
    CHECK(v.spacing == glm::vec3(1, 1, 2));
    CHECK(v.sourceType == qnv::ScalarType::int16);
    CHECK(minMax(v) == std::pair{0.0f, 3272.0f});
    // Values read independently (python3: gzip + struct, big-endian int16).
    CHECK(v.at(128, 128, 56) == 2322.0f);
    CHECK(v.at(100, 150, 60) == 1077.0f);
    CHECK(v.at(133, 125, 56) == 3272.0f);
    CHECK(v.at(255, 255, 112) == 25.0f);

    formats::RawLayout layout;
    layout.dims = {256, 256, 113};
    layout.type = qnv::ScalarType::int16;
    layout.bigEndian = true;
    layout.spacing = {1, 1, 2};
    const qnv::Volume raw = session::loadRawVolumeFile(
        (test::corpusDir() / "volume/cthead/CThead.raw.gz").string(), layout);
    CHECK(raw.samples == v.samples);
  }
  if (!test::haveCorpus("volume/engine")) return;
  {
    const qnv::Volume v =
        session::loadVolumeFile((test::corpusDir() / "volume/engine/engine.nhdr").string());
    REQUIRE(v.dims == glm::uvec3(256, 256, 128));
    CHECK(v.spacing == glm::vec3(1, 1, 1));
    CHECK(v.sourceType == qnv::ScalarType::uint8);
    CHECK(minMax(v) == std::pair{0.0f, 255.0f});
    CHECK(v.at(128, 128, 64) == 133.0f);
    CHECK(v.at(100, 150, 60) == 24.0f);
    CHECK(v.at(181, 133, 1) == 255.0f);
  }
}

TEST_CASE("CThead conversion time", "[.][bench]") {
  if (!test::haveCorpus("volume/cthead")) return;
  const auto dir = test::corpusDir() / "volume/cthead";
  const std::string header = gs::test::readBytes(dir / "CThead.nhdr");
  const std::string data = vrml::gunzipIfCompressed(gs::test::readBytes(dir / "CThead.raw.gz"),
                                                    "CThead.raw.gz", 1u << 26);
  const formats::NrrdHeader h = formats::parseNrrdHeader(header, "CThead.nhdr");
  double best = 1e9;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const qnv::Volume v = formats::decodeNrrdData(h, data, "CThead.raw");
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double, std::milli>(t1 - t0).count());
    REQUIRE(v.samples.size() == 256u * 256u * 113u);
  }
  std::printf("CThead (7.4 M int16 big-endian voxels) to float: %.1f ms\n", best);
}

TEST_CASE("detached data files stay beside their header", "[volume_input][hostile]") {
  TempDir dir("detached");
  dir.write("secret.raw", std::string(512, 'S'));
  dir.write("hdr/ok.raw", std::string(512, '\x07'));
  auto header = [&](const std::string& name, const std::string& dataFile) {
    return dir.write("hdr/" + name, kSphereHead + "data file: " + dataFile + "\n");
  };
  const qnv::Volume ok = session::loadVolumeFile(header("ok.nhdr", "ok.raw"));
  CHECK(ok.at(7, 7, 7) == 7.0f);
  CHECK_NOTHROW(session::loadVolumeFile(header("dot.nhdr", "./ok.raw")));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("up.nhdr", "../secret.raw")),
                    Contains("up.nhdr: data file '../secret.raw' leaves the header's folder"));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("mid.nhdr", "sub/../../secret.raw")),
                    Contains("leaves the header's folder"));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("abs.nhdr", (dir.path / "secret.raw").string())),
                    Contains("is an absolute path"));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("etc.nhdr", "/etc/passwd")),
                    Contains("is an absolute path"));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("missing.nhdr", "missing.raw")),
                    Contains("cannot open") && Contains("missing.raw"));
  CHECK_THROWS_WITH(session::loadVolumeFile(header("short.nhdr", "short.raw")),
                    Contains("cannot open"));
  dir.write("hdr/short.raw", "abc");
  CHECK_THROWS_WITH(session::loadVolumeFile(header("short.nhdr", "short.raw")),
                    Contains("short.raw: expected 512 bytes of voxel data, got 3"));
}

TEST_CASE("damaged files give InputError naming the file", "[volume_input][hostile]") {
  TempDir dir("damaged");
  CHECK_THROWS_WITH(session::loadVolumeFile((dir.path / "none.nrrd").string()),
                    Contains("cannot open") && Contains("none.nrrd"));
  CHECK_THROWS_WITH(session::loadVolumeFile(dir.write("garbage.nii", std::string(400, 'x'))),
                    Contains("garbage.nii: not a NIfTI-1 file"));
  CHECK_THROWS_WITH(session::loadVolumeFile(dir.write("text.nrrd", "hello\n")),
                    Contains("text.nrrd:1: expected the NRRD magic"));
  CHECK_THROWS_WITH(
      session::loadVolumeFile(
          dir.write("notgz.nrrd",
                    "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\n\n"
                    "12345678")),
      Contains("notgz.nrrd: the NRRD header says 'encoding: gzip' but the data are not gzip"));

  // Every truncation of the gzip assets: corrupt gzip or short data, never a crash.
  const std::string gz = gs::test::readBytes(asset("sphere_gzip.nrrd"));
  for (std::size_t n = 0; n < gz.size(); ++n) {
    INFO("length " << n);
    CHECK_THROWS_AS(session::loadVolumeFile(dir.write("cut.nrrd", gz.substr(0, n))),
                    qnv::InputError);
  }
  const std::string niigz = gs::test::readBytes(asset("sphere.nii.gz"));
  for (std::size_t n = 0; n < niigz.size(); ++n) {
    INFO("length " << n);
    CHECK_THROWS_AS(session::loadVolumeFile(dir.write("cut.nii.gz", niigz.substr(0, n))),
                    qnv::InputError);
  }
  CHECK_THROWS_WITH(session::loadVolumeFile(dir.write("cut.nii.gz", niigz.substr(0, 100))),
                    Contains("cut.nii.gz: corrupt gzip data"));

  // gzip data far larger than the header says (the 14 MB of CThead behind an 8x8x8
  // header): refused once the inflated bytes pass what the volume needs.
  if (!test::haveCorpus("volume/cthead")) return;
  std::string bomb = kSphereHead;
  bomb.replace(bomb.find("raw"), 3, "gzip");
  bomb += "\n" + gs::test::readBytes(test::corpusDir() / "volume/cthead/CThead.raw.gz");
  CHECK_THROWS_WITH(
      session::loadVolumeFile(dir.write("bomb.nrrd", bomb)),
      Contains("bomb.nrrd: decompressed data exceed") && Contains("more than the volume needs"));
}
