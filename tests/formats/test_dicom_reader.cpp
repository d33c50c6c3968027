// DICOM through GDCM (formats/dicom_reader.hpp) on real files: pydicom's test files (MIT;
// tests/data/dicom/README.md) and CThead written as DICOM by
// tests/data/dicom/cthead/make_cthead_dicom.py. Expected values are pydicom's reading of
// the same files (pixel_array * RescaleSlope + RescaleIntercept) or CThead's samples.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "formats/dicom_reader.hpp"
#include "formats/input_kind.hpp"
#include "test_support.hpp"

using namespace gs::formats;
using Catch::Matchers::Contains;

namespace {

std::filesystem::path dicomData() {
  return gs::test::sourceDir() / "tests" / "data" / "dicom";
}

std::string dicomBytesOf(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

DicomVolume readDicomData(const std::string& rel) {
  const auto path = dicomData() / rel;
  return readDicom(dicomBytesOf(path), path.string());
}

}  // namespace

TEST_CASE("a CT slice reads in Hounsfield units with its spacing and windows", "[dicom]") {
  const DicomVolume d = readDicomData("pydicom/CT_small.dcm");
  const Volume& v = d.volume;
  REQUIRE(v.dims == glm::uvec3(128, 128, 1));
  CHECK(v.sourceType == ScalarType::int16);
  CHECK(v.spacing.x == Approx(0.661468f));
  CHECK(v.spacing.y == Approx(0.661468f));
  CHECK(d.modality == "CT");
  CHECK(d.rescaleType == "HU");
  CHECK(d.intercept == -1024.0f);
  // pydicom: pixel_array[row, column] + intercept.
  CHECK(v.at(32, 64, 0) == 354.0f);
  CHECK(v.at(0, 0, 0) == -849.0f);
  CHECK(v.at(70, 100, 0) == 36.0f);
  CHECK(v.origin.x == Approx(-158.136f));
  CHECK(d.transferSyntax == "1.2.840.10008.1.2.1");
}

TEST_CASE("compressed transfer syntaxes decode to the uncompressed samples", "[dicom]") {
  const DicomVolume plain = readDicomData("pydicom/MR_small.dcm");
  REQUIRE(plain.volume.dims == glm::uvec3(64, 64, 1));
  CHECK(plain.volume.at(32, 32, 0) == 182.0f);
  CHECK(plain.volume.at(50, 10, 0) == 1104.0f);
  for (const char* name : {"pydicom/MR_small_RLE.dcm", "pydicom/MR_small_jpeg_ls_lossless.dcm",
                           "pydicom/MR_small_jp2klossless.dcm"}) {
    INFO(name);
    const DicomVolume c = readDicomData(name);
    CHECK(c.transferSyntax != plain.transferSyntax);
    REQUIRE(c.volume.dims == plain.volume.dims);
    CHECK(c.volume.samples == plain.volume.samples);
  }
  // JPEG extended (process 2 and 4, lossy 12-bit): 256 columns, 1024 rows.
  const DicomVolume jpeg = readDicomData("pydicom/JPGExtended.dcm");
  CHECK(jpeg.transferSyntax == "1.2.840.10008.1.2.4.51");
  CHECK(jpeg.volume.dims == glm::uvec3(256, 1024, 1));
}

TEST_CASE("a series folder is sorted by position along the normal, spaced by its step", "[dicom]") {
  // pydicom's CT5N: five 16x16 CT slices; file names ascend as z descends (8.7625 .. -1.2375).
  const DicomVolume d = loadDicom((dicomData() / "pydicom/dicomdirtests/98892001/CT5N").string());
  const Volume& v = d.volume;
  REQUIRE(v.dims == glm::uvec3(16, 16, 5));
  CHECK(d.files == 5);
  CHECK(v.spacing.x == Approx(0.488281f));
  CHECK(v.spacing.z == Approx(2.5f));
  // Highest position first (the front-view layout): 2062 (z 8.7625) .. 3353 (z -1.2375).
  CHECK(v.origin.z == Approx(8.7625f));
  const float first[] = {-307, -23, 44, 8, -59};
  const float other[] = {-785, -333, -76, -68, -103};
  for (std::uint32_t z = 0; z < 5; ++z) {
    CHECK(v.at(8, 8, z) == first[z]);
    CHECK(v.at(12, 3, z) == other[z]);
  }
  CHECK(d.sliceDirection == glm::vec3(0, 0, -1));
  REQUIRE(d.windows.size() == 1);
  CHECK(d.windows[0].center == 40.0f);
  CHECK(d.windows[0].width == 400.0f);
}

TEST_CASE("a compressed series takes the position step, not the slice thickness", "[dicom]") {
  // CThead as 29 JPEG-LS slices in shuffled file names, Slice Thickness 1 mm, 8 mm apart.
  const DicomVolume d = loadDicom((dicomData() / "cthead/series").string());
  const Volume& v = d.volume;
  REQUIRE(v.dims == glm::uvec3(128, 128, 29));
  CHECK(v.spacing == glm::vec3(2.0f, 2.0f, 8.0f));
  CHECK(d.transferSyntax == "1.2.840.10008.1.2.4.80");
  // CThead slice 4k averaged 2 x 2, minus 1024 (make_cthead_dicom.py).
  CHECK(v.at(64, 64, 0) == -975.0f);
  CHECK(v.at(70, 40, 0) == -976.0f);
  CHECK(v.at(64, 64, 14) == 1468.0f);
  CHECK(v.at(70, 40, 14) == 33.0f);
  CHECK(v.at(64, 64, 28) == 100.0f);
  CHECK(v.at(70, 40, 28) == -1001.0f);
  REQUIRE(d.windows.size() == 2);
  CHECK(d.windows[1].center == 1000.0f);
  CHECK(d.windows[1].width == 2500.0f);
  CHECK(d.windows[0].explanation == "SOFT TISSUE");
  CHECK(d.windows[1].explanation == "BONE");
  CHECK(d.notes.empty());
}

TEST_CASE("a multi-frame file gives one slice per frame", "[dicom]") {
  const DicomVolume d = loadDicom((dicomData() / "cthead/multiframe.dcm").string());
  const Volume& v = d.volume;
  REQUIRE(v.dims == glm::uvec3(64, 64, 8));
  CHECK(d.transferSyntax == "1.2.840.10008.1.2.5");  // RLE
  CHECK(v.spacing.x == 4.0f);
  CHECK(v.spacing.z == Approx(8.0f));
  CHECK(v.at(32, 32, 0) == -968.0f);
  CHECK(v.at(30, 20, 7) == 48.0f);
}

TEST_CASE("a DICOMDIR opens the largest series it lists that stacks", "[dicom]") {
  for (const auto& path :
       {dicomData() / "pydicom/dicomdirtests/DICOMDIR", dicomData() / "pydicom/dicomdirtests"}) {
    INFO(path.string());
    CHECK(classifyFile(path.string()) == InputKind::dicom);
    const DicomVolume d = loadDicom(path.string());
    // The largest series, 98892003/MR700 (7 images), is radial: its slices turn about an
    // axis, so it is skipped; next is 98892001/CT5N (5 images; see the series test).
    CHECK(d.volume.dims == glm::uvec3(16, 16, 5));
    CHECK(d.modality == "CT");
    CHECK(d.volume.at(8, 8, 0) == -307.0f);
    REQUIRE(d.notes.size() == 2);
    CHECK_THAT(d.notes[0], Contains("series in") && Contains("the largest that stacks"));
    CHECK_THAT(d.notes[1], Contains("skipped:") && Contains("series mixes orientations"));
  }
}

TEST_CASE("DICOM errors name the file and say what was expected", "[dicom]") {
  CHECK_THROWS_WITH(loadDicom((dicomData() / "cthead/mixed").string()),
                    Contains("series has slices of different sizes: a.dcm 32x32, c.dcm 16x16"));
  CHECK_THROWS_WITH(readDicomData("pydicom/SC_rgb_rle_2frame.dcm"),
                    Contains("SC_rgb_rle_2frame.dcm: colour images (3 samples per pixel)"));
  CHECK_THROWS_WITH(readDicom(std::string(300, 'x'), "junk.dcm"),
                    Contains("junk.dcm: not a DICOM file (no 'DICM' at byte 128)"));
  CHECK_THROWS_WITH(loadDicom((gs::test::sourceDir() / "assets").string()),
                    Contains("no DICOM images in the folder"));
  // Every truncation of a real file is an error, never a crash or an over-read.
  const std::string ct = dicomBytesOf(dicomData() / "pydicom/CT_small.dcm");
  for (std::size_t n = 0; n < ct.size(); n += n < 2000 ? 7 : 997)
    CHECK_THROWS_AS(readDicom(std::string_view(ct).substr(0, n), "cut.dcm"), InputError);
  // A length beyond the file is refused before GDCM allocates it.
  std::string huge = ct;
  const std::size_t pixel = huge.find(std::string("\xE0\x7F\x10\x00OW", 6));
  REQUIRE(pixel != std::string::npos);
  huge[pixel + 8] = huge[pixel + 9] = huge[pixel + 10] = huge[pixel + 11] = '\xF0';
  CHECK_THROWS_WITH(readDicom(huge, "huge.dcm"), Contains("huge.dcm: element (7FE0,0010)") &&
                                                     Contains("claims 4042322160 bytes"));
  // An element whose value representation is no VR of PS3.5 table 6.2-1 is refused: GDCM
  // reads an unknown one with a 4-byte length, which the walk would not have checked (CI's
  // fuzz_dicom found a 3.9 KB file, CT_small mutated, that made GDCM allocate 3.26 GB).
  std::string unknown = ct;
  const std::size_t rows = unknown.find(std::string("\x28\x00\x10\x00US", 6));
  REQUIRE(rows != std::string::npos);
  unknown[rows + 4] = 'D';
  unknown[rows + 5] = 'L';
  CHECK_THROWS_WITH(
      readDicom(unknown, "vr.dcm"),
      Contains("vr.dcm: element (0028,0010) with the unknown value representation 'DL'"));
}

TEST_CASE("DICOM is recognised by its magic, its extension and its folder", "[dicom]") {
  std::string head(132, '\0');
  head.replace(128, 4, "DICM");
  CHECK(kindFromContent(head) == InputKind::dicom);
  CHECK(kindFromName("ct/IM0001.dcm") == InputKind::dicom);
  CHECK(kindFromName("ct/IM0001.DICOM") == InputKind::dicom);
  CHECK(kindFromName("/media/cd/DICOMDIR") == InputKind::dicom);
  CHECK(kindFromName("NOTADICOMDIR") == InputKind::unknown);
  CHECK(isOpenableName("scan.dcm"));
  CHECK(isVolume(InputKind::dicom));
  CHECK(classifyFile((dicomData() / "cthead/series").string()) == InputKind::dicom);
  // A file without an extension is DICOM by its magic (pydicom's DICOMDIR tree).
  CHECK(classifyFile((dicomData() / "pydicom/dicomdirtests/98892001/CT5N/2062").string()) ==
        InputKind::dicom);
  CHECK(classifyFile((gs::test::sourceDir() / "assets").string()) != InputKind::dicom);
}

TEST_CASE("GDCM's assertions on a malformed file are errors, never an abort", "[dicom]") {
  // Debian builds GDCM with assertions on; these mutated files fail one each inside
  // gdcm::ImageReader::Read or PixelFormat::GetScalarType (tests/data/dicom/regressions/README.md).
  // Without the guard of formats/src/dicom_assert_guard.cpp the test process aborts here.
  for (const char* file : {"gdcm_assert_bits_allocated.dcm", "gdcm_assert_spacing.dcm",
                           "gdcm_assert_scalar_type.dcm"}) {
    INFO(file);
    CHECK_THROWS_WITH(readDicomData(std::string("regressions/") + file),
                      Contains(std::string(file) + ": GDCM cannot read this DICOM file"));
  }
  // The guard is left as it was found: a later good file still reads.
  CHECK(readDicomData("pydicom/CT_small.dcm").volume.dims.x == 128);
}

TEST_CASE("GDCM's allocations on a malformed file stay in the reader process", "[dicom]") {
  // GDCM allocates the 4.28 GB an encapsulated fragment of this 7.8 KB file claims before it
  // reads it; the child process that runs GDCM (formats/src/dicom_isolated.cpp) may not
  // grow that far, so the read fails there and only an error comes back.
  CHECK_THROWS_WITH(readDicomData("regressions/fragment_oom.dcm"), Contains("fragment_oom.dcm: "));
  CHECK(readDicomData("pydicom/CT_small.dcm").volume.dims.x == 128);
}
