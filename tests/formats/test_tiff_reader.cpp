// TIFF and OME-TIFF through libtiff (formats/tiff_reader.hpp, and the slice-stack reader of
// formats/volume_slabs.hpp) on real files: OME's sample OME-TIFFs (BSD-2-Clause;
// tests/data/tiff/README.md) and CThead written as TIFF by
// tests/data/tiff/cthead/make_cthead_tiff.py. Expected values are Pillow's reading of the
// same pages, or CThead's samples.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>

#include "formats/input_kind.hpp"
#include "formats/tiff_reader.hpp"
#include "formats/volume_slabs.hpp"
#include "test_support.hpp"

using namespace gs::formats;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path tiffData() {
  return gs::test::sourceDir() / "tests" / "data" / "tiff";
}

std::string tiffBytesOf(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TiffVolume readTiffData(const std::string& rel) {
  const auto path = tiffData() / rel;
  return readTiff(tiffBytesOf(path), path.string());
}

// The sum of slice z's samples.
double tiffSliceSum(const Volume& v, std::uint32_t z) {
  const std::size_t n = std::size_t{v.dims.x} * v.dims.y;
  const auto first = v.samples.begin() + static_cast<std::ptrdiff_t>(n * z);
  return std::accumulate(first, first + static_cast<std::ptrdiff_t>(n), 0.0);
}

}  // namespace

TEST_CASE("an OME-TIFF gives the Z planes of its first channel, in any DimensionOrder", "[tiff]") {
  // Pillow: page sums of channel 0's planes z = 0..4 (the files differ in page order).
  const double sums[] = {94605, 16575, 93330, 17136, 92820};
  // XYCTZ, SizeC 2: channel 0 is every other page.
  const TiffVolume ctz = readTiffData("ome/18x24y5z1t2c8b-text.ome-v2010-06.ome.tiff");
  REQUIRE(ctz.ome.found);
  CHECK(ctz.ome.dimensionOrder == "XYCTZ");
  CHECK(ctz.pages == 10);
  REQUIRE(ctz.volume.dims == glm::uvec3(18, 24, 5));
  CHECK(ctz.volume.sourceType == ScalarType::uint8);
  // XYZCT, SizeC 2, SizeT 5: the first five of 50 pages.
  const TiffVolume zct = readTiffData("ome/18x24y5z5t2c8b-text.ome-v2010-06.ome.tiff");
  CHECK(zct.pages == 50);
  REQUIRE(zct.volume.dims == glm::uvec3(18, 24, 5));
  for (std::uint32_t z = 0; z < 5; ++z) {
    CHECK(tiffSliceSum(ctz.volume, z) == sums[z]);
    CHECK(tiffSliceSum(zct.volume, z) == sums[z]);
  }
  CHECK(ctz.volume.at(9, 12, 0) == 255.0f);
  CHECK(ctz.volume.at(9, 12, 1) == 0.0f);  // page 2 of 10
}

TEST_CASE("OME physical sizes become the spacing, in micrometres", "[tiff]") {
  // PhysicalSizeX/Y 10000 (no unit: um), PhysicalSizeZ 0.0 (not a size: 1).
  const TiffVolume swatch = readTiffData("ome/6x4y1z1t1c8b-swatch.ome-v2010-06.ome.tiff");
  CHECK(swatch.volume.dims == glm::uvec3(6, 4, 1));
  CHECK(swatch.volume.spacing == glm::vec3(10000.0f, 10000.0f, 1.0f));
  CHECK(!swatch.ome.hasSpacing[2]);
  CHECK(swatch.volume.at(2, 0, 0) == 171.0f);
  CHECK(swatch.volume.at(5, 3, 0) == 133.0f);
  // CThead: 2 mm, 2 mm, 8 mm with their units.
  const TiffVolume ct = readTiffData("cthead/cthead.ome.tif");
  REQUIRE(ct.volume.dims == glm::uvec3(128, 128, 29));
  CHECK(ct.volume.sourceType == ScalarType::uint16);
  CHECK(ct.volume.spacing == glm::vec3(2000.0f, 2000.0f, 8000.0f));
  CHECK(ct.volume.at(64, 64, 0) == 49.0f);
  CHECK(ct.volume.at(70, 40, 0) == 48.0f);
  CHECK(ct.volume.at(64, 64, 14) == 2492.0f);
  CHECK(ct.volume.at(70, 40, 28) == 23.0f);

  const OmePixels units = parseOmeXml(
      "<ome:OME><ome:Pixels PhysicalSizeX='0.5' PhysicalSizeXUnit='nm' PhysicalSizeY=\"3\" "
      "PhysicalSizeYUnit=\"\xC2\xB5m\" PhysicalSizeZ=\"1.5\" PhysicalSizeZUnit=\"cm\" "
      "SizeZ=\"4\" SizeC=\"3\" SizeT=\"2\" DimensionOrder=\"XYCZT\"/></ome:OME>");
  REQUIRE(units.found);
  CHECK(units.spacing.x == Approx(0.0005f));
  CHECK(units.spacing.y == 3.0f);
  CHECK(units.spacing.z == Approx(15000.0f));
  CHECK(units.pageOfSlice(2) == 6);  // C fastest (3 channels), then Z
  CHECK(!parseOmeXml("<Image Name='PixelsLike'/>").found);
}

TEST_CASE("float TIFF pages and a folder of single-page TIFFs read as volumes", "[tiff]") {
  const TiffVolume f = readTiffData("cthead/float32.tif");
  REQUIRE(f.volume.dims == glm::uvec3(64, 64, 8));
  CHECK(f.volume.sourceType == ScalarType::float32);
  CHECK(!f.ome.found);
  CHECK(f.volume.spacing == glm::vec3(1.0f));
  CHECK(f.volume.at(32, 32, 0) == 0.056f);
  CHECK(f.volume.at(30, 20, 7) == 1.0718125f);
  // The folder: z1.tif .. z8.tif through the slice-stack reader.
  const auto reader = openVolumeSlabs((tiffData() / "cthead/slices").string());
  const Volume v = readWholeVolume(*reader);
  REQUIRE(v.dims == glm::uvec3(64, 64, 8));
  CHECK(v.sourceType == ScalarType::uint8);
  CHECK(v.at(32, 32, 0) == 4.0f);
  CHECK(v.at(32, 32, 1) == 50.0f);
  CHECK(v.at(30, 20, 7) == 67.0f);
  // A multi-page OME-TIFF through the slab reader: the same planes and spacing as readTiff.
  const auto ome =
      openVolumeSlabs((tiffData() / "ome/18x24y5z1t2c8b-text.ome-v2010-06.ome.tiff").string());
  CHECK(ome->info().dims == glm::uvec3(18, 24, 5));
  const Volume ov = readWholeVolume(*ome);
  CHECK(ov.samples == readTiffData("ome/18x24y5z1t2c8b-text.ome-v2010-06.ome.tiff").volume.samples);
  const auto ct = openVolumeSlabs((tiffData() / "cthead/cthead.ome.tif").string());
  CHECK(ct->info().spacing == glm::vec3(2000.0f, 2000.0f, 8000.0f));
}

TEST_CASE("TIFF is recognised by its magic and its name; errors name the file", "[tiff]") {
  CHECK(kindFromContent(std::string("II*\0\x08\0\0\0", 8)) == InputKind::tiff);
  CHECK(kindFromContent(std::string("MM\0*\0\0\0\x08", 8)) == InputKind::tiff);
  CHECK(kindFromContent(std::string("II+\0\x08\0\0\0", 8)) == InputKind::tiff);
  CHECK(kindFromName("stack.ome.tiff") == InputKind::tiff);
  CHECK(kindFromName("STACK.TIF") == InputKind::tiff);
  CHECK(isOpenableName("cells.ome.tif"));
  CHECK(isVolume(InputKind::tiff));
  CHECK(classifyFile((tiffData() / "cthead/slices").string()) == InputKind::tiff);
  CHECK(classifyFile((tiffData() / "cthead/float32.tif").string()) == InputKind::tiff);

  CHECK_THROWS_WITH(readTiff("GIF89a", "x.tif"), Contains("x.tif: not a TIFF file"));
  const std::string ct = tiffBytesOf(tiffData() / "cthead/float32.tif");
  // Every truncation is an error naming the file, never a crash or a print.
  for (std::size_t n = 8; n < ct.size(); n += n < 4000 ? 61 : 4093)
    CHECK_THROWS_WITH(readTiff(std::string_view(ct).substr(0, n), "cut.tif"),
                      Contains("cut.tif: "));
  // A page whose strips cannot hold its samples is refused before the allocation.
  std::string wide = tiffBytesOf(tiffData() / "cthead/slices/z1.tif");
  REQUIRE(wide.substr(0, 4) == std::string("II*\0", 4));
  // ImageWidth (tag 256) as a LONG 0x4000 in the first IFD.
  const std::uint32_t ifd = static_cast<unsigned char>(wide[4]) |
                            static_cast<unsigned char>(wide[5]) << 8 |
                            static_cast<unsigned char>(wide[6]) << 16;
  const std::size_t entries = static_cast<unsigned char>(wide[ifd]);
  bool patched = false;
  for (std::size_t e = 0; e < entries; ++e) {
    const std::size_t at = ifd + 2 + 12 * e;
    if (static_cast<unsigned char>(wide[at]) == 0 &&
        static_cast<unsigned char>(wide[at + 1]) == 1) {
      wide[at + 2] = 4, wide[at + 3] = 0;  // LONG
      wide.replace(at + 8, 4, std::string("\0\x40\0\0", 4));
      patched = true;
    }
  }
  REQUIRE(patched);
  CHECK_THROWS_WITH(readTiff(wide, "wide.tif"), Contains("wide.tif: ") && Contains("cannot hold"));
}
