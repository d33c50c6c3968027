// DICOM, TIFF and OpenVDB volumes through the real binary (docs/volumes.md): --snapshot of a
// series folder, an OME-TIFF and VDB fog and level-set grids, info's window presets,
// physical sizes and grids, encode of a folder of TIFF slices and of a VDB file, and errors
// that name the file and exit 1.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"

using Catch::Matchers::Contains;
using gs::test::runGhostspace;

namespace {

std::string volumeFormatData(const std::string& rel) {
  return (gs::test::sourceDir() / "tests" / "data" / rel).string();
}

}  // namespace

TEST_CASE("a DICOM series folder and an OME-TIFF render with --snapshot",
          "[heavy][app][snapshot]") {
  for (const std::string& input :
       {volumeFormatData("dicom/cthead/series/"), volumeFormatData("tiff/cthead/cthead.ome.tif")}) {
    INFO(input);
    const std::string png = gs::test::snapshot(
        "volume_format_" + std::filesystem::path(input).parent_path().filename().string(),
        {"--size", "160x160", input});
    // The front view of CThead: the face fills the centre.
    const auto c = gs::test::centrePixel(png);
    CHECK(c[0] + c[1] + c[2] > 60);
  }
}

TEST_CASE("info prints a DICOM series' windows and an OME-TIFF's physical sizes", "[app][cli]") {
  const auto dicom = runGhostspace({"info", volumeFormatData("dicom/cthead/series")});
  CHECK(dicom.exitCode == 0);
  CHECK_THAT(dicom.out, Contains("128 x 128 x 29 voxels from 29 files, spacing 2 2 8 mm"));
  CHECK_THAT(dicom.out, Contains("window: centre 40, width 400 (-160 .. 240) SOFT TISSUE"));
  CHECK_THAT(dicom.out, Contains("window: centre 1000, width 2500 (-250 .. 2250) BONE"));
  CHECK_THAT(dicom.out, Contains("values: -1024 .. 2248 HU"));
  const auto tiff = runGhostspace({"info", volumeFormatData("tiff/cthead/cthead.ome.tif")});
  CHECK(tiff.exitCode == 0);
  CHECK_THAT(tiff.out,
             Contains("128 x 128 x 29 voxels from 29 pages, uint16, spacing 2000 2000 8000 um"));
}

TEST_CASE("encode reads a folder of TIFF slices; bad DICOM exits 1 naming the file",
          "[app][encode]") {
  const gs::test::TempDir dir("volfmt");
  const std::string out = (dir.path / "slices.qnv").string();
  const auto r = runGhostspace({"encode", volumeFormatData("tiff/cthead/slices"), "-o", out});
  CHECK(r.exitCode == 0);
  CHECK(std::filesystem::file_size(out) > 1000);
  const std::string junk = dir.write("junk.dcm", std::string(300, 'x'));
  const auto bad = runGhostspace({"encode", junk, "-o", (dir.path / "junk.qnv").string()});
  CHECK(bad.exitCode == 1);
  CHECK_THAT(bad.err, Contains("junk.dcm: not a DICOM file (no 'DICM' at byte 128)"));
  CHECK(!std::filesystem::exists(dir.path / "junk.qnv"));
  const auto mixed = runGhostspace(
      {"--snapshot", (dir.path / "m.png").string(), volumeFormatData("dicom/cthead/mixed")});
  CHECK(mixed.exitCode == 1);
  CHECK_THAT(mixed.err, Contains("series has slices of different sizes: a.dcm 32x32, c.dcm 16x16"));
}

TEST_CASE("OpenVDB fog volumes and level sets open, encode and say what they are",
          "[app][snapshot]") {
  for (const std::string& input :
       {volumeFormatData("vdb/cthead_fog.vdb"), volumeFormatData("vdb/cthead_skin_ls.vdb")}) {
    INFO(input);
    const std::string png =
        gs::test::snapshot("volume_format_" + std::filesystem::path(input).stem().string(),
                           {"--size", "160x160", input});
    // The front view of CThead's face.
    const auto c = gs::test::centrePixel(png);
    CHECK(c[0] + c[1] + c[2] > 60);
  }
  const auto info = runGhostspace({"info", volumeFormatData("vdb/cthead_skin_ls.vdb")});
  CHECK(info.exitCode == 0);
  CHECK_THAT(info.out, Contains("OpenVDB grid 'ls_skin' (float, level set read as fog), 1 of 2 "
                                "grids, 57250 active voxels"));
  const gs::test::TempDir dir("vdb");
  const std::string out = (dir.path / "fog.qnv").string();
  const auto r = runGhostspace({"encode", volumeFormatData("vdb/cthead_fog.vdb"), "-o", out});
  CHECK(r.exitCode == 0);
  CHECK(std::filesystem::file_size(out) > 1000);
  const std::string junk =
      dir.write("junk.vdb", std::string("\x20\x42\x44\x56\0\0\0\0", 8) + std::string(300, 'x'));
  const auto bad = runGhostspace({"--snapshot", (dir.path / "junk.png").string(), junk});
  CHECK(bad.exitCode == 1);
  CHECK_THAT(bad.err, Contains("junk.vdb: cannot open as OpenVDB ("));
}
