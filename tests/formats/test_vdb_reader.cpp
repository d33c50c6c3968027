// OpenVDB grids through libopenvdb in a child process (formats/vdb_reader.hpp), on corpus
// data written as VDB by OpenVDB's own Python binding (tests/data/vdb/make_vdb.py): CThead
// as a sparse fog volume and its skin as a level set. Expected values are pyopenvdb's
// reading of the same grids.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>

#include "formats/input_kind.hpp"
#include "formats/vdb_reader.hpp"
#include "formats/volume_slabs.hpp"
#include "qnv/error.hpp"
#include "test_support.hpp"

using namespace gs::formats;
using Catch::Matchers::Contains;

namespace {

std::string vdbData(const std::string& name) {
  return (gs::test::sourceDir() / "tests" / "data" / "vdb" / name).string();
}

std::string vdbBytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("OpenVDB files are recognised by their magic number and name", "[vdb]") {
  CHECK(hasVdbMagic(std::string("\x20\x42\x44\x56\0\0\0\0\xde\0", 10)));
  CHECK_FALSE(hasVdbMagic(std::string("\x20\x42\x44\x56\0\0\0\1", 8)));
  CHECK(kindFromContent(std::string("\x20\x42\x44\x56\0\0\0\0", 8)) == InputKind::vdb);
  CHECK(kindFromName("smoke.VDB") == InputKind::vdb);
  CHECK(isVolume(InputKind::vdb));
  CHECK(classifyFile(vdbData("cthead_fog.vdb")) == InputKind::vdb);
}

TEST_CASE("a fog volume reads as its active box with the transform's voxel size", "[vdb]") {
  const auto reader = openVdb(vdbData("cthead_fog.vdb"));
  const VdbGridSummary& s = reader->summary();
  CHECK(s.name == "density");
  CHECK(s.valueType == "float");
  CHECK_FALSE(s.levelSet);
  CHECK(s.grids == 1);
  CHECK(s.activeVoxels == 35002);
  const gs::qnv::VolumeGridInfo& g = reader->info();
  // Active box (4, 2, 0) .. (62, 63, 28) at 4 x 4 x 8 mm.
  CHECK(g.dims == glm::uvec3(59, 62, 29));
  CHECK(g.spacing == glm::vec3(4, 4, 8));
  CHECK(g.origin == glm::vec3(16, 8, 0));
  REQUIRE(g.valueRange);
  CHECK(g.valueRange->first == 0.0f);  // the background
  CHECK(g.valueRange->second == 1.0f);

  const gs::qnv::Volume v = readWholeVolume(*reader);
  REQUIRE(v.samples.size() == std::size_t{59} * 62 * 29);
  const double sum = std::accumulate(v.samples.begin(), v.samples.end(), 0.0);
  CHECK(sum == Approx(13116.614249).epsilon(1e-6));
  CHECK(v.at(32 - 4, 32 - 2, 14) == Approx(0.6698958278f));
  CHECK(v.at(30 - 4, 20 - 2, 10) == Approx(0.4109374881f));
}

TEST_CASE("reading slices backwards starts the reader again and gives the same samples", "[vdb]") {
  const auto reader = openVdb(vdbData("cthead_fog.vdb"));
  std::vector<float> late, early, again;
  reader->readSlices(20, 29, late);
  reader->readSlices(0, 5, early);
  reader->readSlices(20, 29, again);
  CHECK(late == again);
  const gs::qnv::Volume v = readWholeVolume(*openVdb(vdbData("cthead_fog.vdb")));
  const std::size_t slice = std::size_t{59} * 62;
  CHECK(std::equal(early.begin(), early.end(), v.samples.begin()));
  CHECK(std::equal(late.begin(), late.end(), v.samples.begin() + 20 * slice));
}

TEST_CASE("a level set reads as the fog volume of its interior; other grids are skipped", "[vdb]") {
  const auto reader = openVdbBytes(vdbBytesOf(vdbData("cthead_skin_ls.vdb")), "cthead_skin_ls.vdb");
  const VdbGridSummary& s = reader->summary();
  CHECK(s.name == "ls_skin");  // after the vec3s grid "v"
  CHECK(s.levelSet);
  CHECK(s.grids == 2);
  CHECK(s.activeVoxels == 57250);  // the narrow band as stored
  const gs::qnv::VolumeGridInfo& g = reader->info();
  CHECK(g.spacing == glm::vec3(4, 4, 4));
  // Within the level set's active box (2, 0, -2) .. (49, 61, 59): the inner half band and
  // the interior.
  CHECK(g.dims.x <= 48);
  CHECK(g.dims.y <= 62);
  CHECK(g.dims.z <= 62);
  CHECK(g.dims.x > 36);
  const gs::qnv::Volume v = readWholeVolume(*reader);
  const auto [lo, hi] = std::minmax_element(v.samples.begin(), v.samples.end());
  CHECK(*lo == 0.0f);
  CHECK(*hi == 1.0f);
  const auto inside = std::count(v.samples.begin(), v.samples.end(), 1.0f);
  const auto ramp = std::count_if(v.samples.begin(), v.samples.end(),
                                  [](float x) { return x > 0.0f && x < 1.0f; });
  CHECK(inside > 20000);  // the head
  CHECK(ramp > 5000);     // its skin
}

TEST_CASE("a VDB reader error names the file and what failed", "[vdb]") {
  const std::string skin = vdbData("cthead_skin_ls.vdb");
  CHECK_THROWS_WITH(openVdb(skin, "v"),
                    Contains("cthead_skin_ls.vdb: no float or double grid named 'v' (the file has "
                             "vec3s 'v', float 'ls_skin')"));
  CHECK_THROWS_WITH(openVdbBytes(std::string(64, 'x'), "junk.vdb"),
                    Contains("junk.vdb: cannot open as OpenVDB ("));
  CHECK_THROWS_WITH(openVdb(vdbData("missing.vdb")), Contains("missing.vdb"));
  // A child that may not grow: its allocations fail, and the caller hears of it.
  CHECK_THROWS_AS(openVdb(skin, "", 1 << 20), gs::qnv::InputError);
}

TEST_CASE("every truncation of a VDB file is an error, never a crash", "[vdb]") {
  const std::string bytes = vdbBytesOf(vdbData("cthead_fog.vdb"));
  for (std::size_t n = 0; n < bytes.size(); n += bytes.size() / 23 + 1) {
    INFO(n);
    CHECK_THROWS_AS(readWholeVolume(*openVdbBytes(bytes.substr(0, n), "cut.vdb", "",
                                                  {std::uint64_t{256} << 20, 120})),
                    gs::qnv::InputError);
  }
}
