// Slab readers (formats/volume_slabs.hpp): every source on fixtures made at test time or
// the hand-made files of assets/volumes, equality with the whole-volume readers, and
// hostile headers and missing files rejected with messages.
#include <catch2/catch.hpp>

#include <png.h>
#include <tiffio.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "formats/volume_slabs.hpp"
#include "test_support.hpp"

using namespace gs::formats;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

namespace {

void writeFile(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  REQUIRE(out);
}

// A small int16 field: a few shells and a ramp, negative values included.
std::int16_t fieldValue(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
  const double r = std::sqrt((x - 6.0) * (x - 6.0) + (y - 4.5) * (y - 4.5) + (z - 3.0) * (z - 3.0));
  return static_cast<std::int16_t>(std::lround(400.0 * std::cos(r) + 3.0 * x - 7.0 * z));
}

constexpr glm::uvec3 kDims{13, 9, 7};

std::vector<float> fieldSamples(glm::uvec3 d = kDims) {
  std::vector<float> v;
  for (std::uint32_t z = 0; z < d.z; ++z)
    for (std::uint32_t y = 0; y < d.y; ++y)
      for (std::uint32_t x = 0; x < d.x; ++x) v.push_back(fieldValue(x, y, z));
  return v;
}

// Samples [z0, z1) of the field as int16 little-endian bytes.
std::string fieldBytes(std::uint32_t z0, std::uint32_t z1, glm::uvec3 d = kDims) {
  std::string out;
  for (std::uint32_t z = z0; z < z1; ++z)
    for (std::uint32_t y = 0; y < d.y; ++y)
      for (std::uint32_t x = 0; x < d.x; ++x) {
        const auto v = static_cast<std::uint16_t>(fieldValue(x, y, z));
        out += static_cast<char>(v & 0xff);
        out += static_cast<char>(v >> 8);
      }
  return out;
}

const std::string kHead =
    "NRRD0004\ntype: short\ndimension: 3\nsizes: 13 9 7\nendian: little\n"
    "spacings: 0.5 0.75 2\n";

// Every way of cutting [0, dz) into slabs of `thickness`, read in order, must give the
// same samples as `expected`.
void checkSlabs(VolumeSlabReader& reader, const std::vector<float>& expected) {
  const glm::uvec3 d = reader.info().dims;
  const std::size_t slice = std::size_t{d.x} * d.y;
  for (std::uint32_t thickness : {1u, 2u, 3u, d.z}) {
    std::vector<float> all, part;
    for (std::uint32_t z = 0; z < d.z; z += thickness) {
      reader.readSlices(z, std::min(z + thickness, d.z), part);
      REQUIRE(part.size() == slice * (std::min(z + thickness, d.z) - z));
      all.insert(all.end(), part.begin(), part.end());
    }
    CHECK(all == expected);
  }
  // Backwards too (a gzip stream restarts).
  std::vector<float> part;
  reader.readSlices(d.z - 1, d.z, part);
  CHECK(std::equal(part.begin(), part.end(), expected.end() - static_cast<std::ptrdiff_t>(slice)));
  reader.readSlices(0, 1, part);
  CHECK(std::equal(part.begin(), part.end(), expected.begin()));
}

std::string assetPath(const std::string& name) {
  return (gs::test::sourceDir() / "assets" / "volumes" / name).string();
}

// The whole-volume reader's result for a NRRD file with attached data.
Volume wholeNrrd(const std::string& path) {
  const std::string bytes = gs::test::readBytes(path);
  const NrrdHeader h = parseNrrdHeader(bytes, path);
  return decodeNrrdData(h, std::string_view(bytes).substr(h.dataOffset), path);
}

void writePng(const fs::path& path, std::uint32_t w, std::uint32_t h, int depth, int color,
              const std::vector<std::uint16_t>& values) {
  std::FILE* f = std::fopen(path.string().c_str(), "wb");
  REQUIRE(f);
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  png_init_io(png, f);
  png_set_IHDR(png, info, w, h, depth, color, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const int channels = color == PNG_COLOR_TYPE_RGB ? 3 : 1;
  std::vector<png_byte> row;
  for (std::uint32_t y = 0; y < h; ++y) {
    row.clear();
    for (std::uint32_t x = 0; x < w; ++x)
      for (int c = 0; c < channels; ++c) {
        const std::uint16_t v = values[x + std::size_t{w} * y];
        if (depth == 16) row.push_back(static_cast<png_byte>(v >> 8));
        row.push_back(static_cast<png_byte>(v & 0xff));
      }
    png_write_row(png, row.data());
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  std::fclose(f);
}

// Writes pages of int16 samples (one per z of `d`) to one TIFF, or one TIFF per page.
void writeTiffPages(TIFF* tif, glm::uvec3 d, std::uint32_t z0, std::uint32_t z1) {
  for (std::uint32_t z = z0; z < z1; ++z) {
    TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, d.x);
    TIFFSetField(tif, TIFFTAG_IMAGELENGTH, d.y);
    TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, 16);
    TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, 1);
    TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, SAMPLEFORMAT_INT);
    TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_MINISBLACK);
    TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tif, TIFFTAG_COMPRESSION, COMPRESSION_LZW);
    TIFFSetField(tif, TIFFTAG_ROWSPERSTRIP, 4);
    std::vector<std::int16_t> row(d.x);
    for (std::uint32_t y = 0; y < d.y; ++y) {
      for (std::uint32_t x = 0; x < d.x; ++x) row[x] = fieldValue(x, y, z);
      REQUIRE(TIFFWriteScanline(tif, row.data(), y, 0) == 1);
    }
    TIFFWriteDirectory(tif);
  }
}

}  // namespace

TEST_CASE("slab reader: attached raw NRRD equals the whole-volume reader", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  const fs::path path = dir.path / "field.nrrd";
  writeFile(path, kHead + "encoding: raw\n\n" + fieldBytes(0, kDims.z));
  auto reader = openVolumeSlabs(path.string());
  CHECK(reader->info().dims == kDims);
  CHECK(reader->info().spacing == glm::vec3(0.5f, 0.75f, 2.0f));
  CHECK(reader->info().sourceType == ScalarType::int16);
  const Volume whole = wholeNrrd(path.string());
  CHECK(whole.samples == fieldSamples());
  checkSlabs(*reader, whole.samples);
  const Volume again = readWholeVolume(*reader);
  CHECK(again.samples == whole.samples);
  CHECK(again.spacing == whole.spacing);
}

TEST_CASE("slab reader: the assets equal the whole-volume readers", "[formats][slabs]") {
  for (const char* name : {"sphere.nrrd", "sphere_gzip.nrrd", "ramp_float_be.nrrd"}) {
    INFO(name);
    auto reader = openVolumeSlabs(assetPath(name));
    const Volume whole = readWholeVolume(*reader);
    if (std::string(name) == "sphere_gzip.nrrd") continue;  // compared below by value
    const Volume expected = wholeNrrd(assetPath(name));
    CHECK(whole.samples == expected.samples);
    CHECK(whole.origin == expected.origin);
    CHECK(whole.spacing == expected.spacing);
  }
  // The sphere of assets/volumes/README.md, whatever the container.
  for (const char* name :
       {"sphere.nrrd", "sphere_gzip.nrrd", "sphere_detached.nhdr", "sphere.nii", "sphere.nii.gz"}) {
    INFO(name);
    auto reader = openVolumeSlabs(assetPath(name));
    const Volume v = readWholeVolume(*reader);
    REQUIRE(v.dims == glm::uvec3(8, 8, 8));
    const bool nii = std::string(name) == "sphere.nii";
    const bool niigz = std::string(name) == "sphere.nii.gz";
    int bad = 0;
    for (int z = 0; z < 8; ++z)
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const double r =
              std::sqrt((x - 3.5) * (x - 3.5) + (y - 3.5) * (y - 3.5) + (z - 3.5) * (z - 3.5));
          const double s = std::lround(60.0 * std::max(0.0, 4.0 - r));
          const double want = nii ? s * 0.5 + 10 : niigz ? s / 10 : s;
          if (std::fabs(v.at(x, y, z) - want) > 1e-4) ++bad;
        }
    CHECK(bad == 0);
    checkSlabs(*reader, v.samples);
  }
  const Volume nii = readWholeVolume(*openVolumeSlabs(assetPath("sphere.nii")));
  CHECK(nii.origin == glm::vec3(-3.0f, -2.5f, 4.0f));
  CHECK(nii.samples == readNifti(gs::test::readBytes(assetPath("sphere.nii")), "x").samples);
}

TEST_CASE("slab reader: gzip NRRD streams forward and restarts backwards", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  // Attached, gzip, with a byte skip inside the decompressed data.
  const fs::path attached = dir.path / "field_gz.nrrd";
  writeFile(attached,
            kHead + "encoding: gzip\nbyte skip: 3\n\n" + gs::test::gzip("abc" + fieldBytes(0, 7)));
  checkSlabs(*openVolumeSlabs(attached.string()), fieldSamples());
  // Detached, two concatenated gzip members, byte skip -1 (the data are the last bytes).
  const fs::path header = dir.path / "field_gz.nhdr";
  writeFile(header, kHead + "encoding: gz\nbyte skip: -1\ndata file: field.raw.gz\n");
  writeFile(dir.path / "field.raw.gz",
            gs::test::gzip("padding" + fieldBytes(0, 3)) + gs::test::gzip(fieldBytes(3, 7)));
  checkSlabs(*openVolumeSlabs(header.string()), fieldSamples());
  // Truncated gzip data: the error names the file.
  const std::string gz = gs::test::gzip(fieldBytes(0, 7));
  writeFile(dir.path / "cut.raw.gz", gz.substr(0, gz.size() / 2));
  writeFile(header, kHead + "encoding: gzip\ndata file: cut.raw.gz\n");
  auto cut = openVolumeSlabs(header.string());
  std::vector<float> out;
  CHECK_THROWS_WITH(cut->readSlices(0, 7, out), Contains("cut.raw.gz") && Contains("byte offset"));
}

TEST_CASE("slab reader: NRRD data file FORMAT MIN MAX STEP [SUBDIM]", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  // One slice per file (SUBDIM defaults to 2), numbered from 1.
  for (std::uint32_t z = 0; z < kDims.z; ++z) {
    char name[32];
    std::snprintf(name, sizeof name, "slice%03u.raw", z + 1);
    writeFile(dir.path / name, fieldBytes(z, z + 1));
  }
  const fs::path header = dir.path / "slices.nhdr";
  writeFile(header, kHead + "encoding: raw\ndata file: slice%03d.raw 1 7 1\n");
  auto reader = openVolumeSlabs(header.string());
  checkSlabs(*reader, fieldSamples());
  // Backwards: STEP -1 from 7 to 1 reverses the slices.
  writeFile(header, kHead + "encoding: raw\ndata file: slice%03d.raw 7 1 -1\n");
  std::vector<float> reversed;
  const std::vector<float> all = fieldSamples();
  const std::size_t slice = std::size_t{kDims.x} * kDims.y;
  for (std::uint32_t z = kDims.z; z-- > 0;)
    reversed.insert(reversed.end(), all.begin() + static_cast<std::ptrdiff_t>(slice * z),
                    all.begin() + static_cast<std::ptrdiff_t>(slice * (z + 1)));
  checkSlabs(*openVolumeSlabs(header.string()), reversed);
  // SUBDIM 1: one row per file, so a slab spans many files.
  std::uint32_t k = 0;
  std::string bytes = fieldBytes(0, kDims.z);
  for (std::size_t at = 0; at < bytes.size(); at += 2 * kDims.x, ++k)
    writeFile(dir.path / ("row" + std::to_string(k) + ".raw"), bytes.substr(at, 2 * kDims.x));
  writeFile(header, kHead + "encoding: raw\ndata file: row%d.raw 0 62 1 1\n");
  checkSlabs(*openVolumeSlabs(header.string()), fieldSamples());
  // Missing slice file: named in the error.
  fs::remove(dir.path / "slice004.raw");
  writeFile(header, kHead + "encoding: raw\ndata file: slice%03d.raw 1 7 1\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("slice004.raw"));
  // A range naming the wrong number of files.
  writeFile(header, kHead + "encoding: raw\ndata file: slice%03d.raw 1 6 1\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("names 6 files, expected 7"));
  // A format without a conversion, or with two.
  writeFile(header, kHead + "encoding: raw\ndata file: slice%03d%d.raw 1 7 1\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("one integer conversion"));
  writeFile(header, kHead + "encoding: raw\ndata file: slice%s.raw 1 7 1\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("one integer conversion"));
}

TEST_CASE("slab reader: NRRD data file LIST [SUBDIM], raw and gzip", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  // One gzip file per slice (SUBDIM 2, the default).
  std::string list;
  for (std::uint32_t z = 0; z < kDims.z; ++z) {
    const std::string name = "part" + std::to_string(z) + ".gz";
    writeFile(dir.path / name, gs::test::gzip(fieldBytes(z, z + 1)));
    list += name + "\n";
  }
  const fs::path header = dir.path / "list.nhdr";
  writeFile(header, kHead + "encoding: gzip\ndata file: LIST\n" + list);
  checkSlabs(*openVolumeSlabs(header.string()), fieldSamples());
  // SUBDIM 3: the whole volume in one file.
  writeFile(dir.path / "all.raw", fieldBytes(0, 7));
  writeFile(header, kHead + "encoding: raw\ndata file: LIST 3\nall.raw\n");
  checkSlabs(*openVolumeSlabs(header.string()), fieldSamples());
  // Too few names, a name leaving the folder.
  writeFile(header, kHead + "encoding: raw\ndata file: LIST\npart0.gz\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("names 1 files, expected 7"));
  writeFile(header, kHead + "encoding: raw\ndata file: LIST 3\n../all.raw\n");
  CHECK_THROWS_WITH(openVolumeSlabs(header.string()), Contains("leaves the header's folder"));
  // The whole-volume parser still refuses the list forms.
  CHECK_THROWS_WITH(parseNrrdHeader(kHead + "encoding: raw\ndata file: LIST 3\nall.raw\n", "h"),
                    Contains("not supported"));
}

TEST_CASE("slab reader: hostile NRRD headers are refused before any large allocation",
          "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  const fs::path path = dir.path / "lie.nrrd";
  // Sizes that lie about the file size.
  writeFile(path, "NRRD0004\ntype: short\ndimension: 3\nsizes: 2048 2048 2048\nencoding: raw\n\n" +
                      std::string(100, '\0'));
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()),
                    Contains("lie.nrrd") && Contains("the header's sizes do not match the file"));
  // gzip data cannot hold what the header describes.
  writeFile(path, "NRRD0004\ntype: short\ndimension: 3\nsizes: 2048 2048 2048\nencoding: gzip\n\n" +
                      gs::test::gzip(std::string(100, '\0')));
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("cannot hold"));
  // One slice over the slice limit; a grid over the volume limit.
  writeFile(path, "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 100000 100000 1\nencoding: raw\n\n");
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("kMaxSliceVoxels"));
  writeFile(path,
            "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 16384 16384 8192\nencoding: raw\n\n");
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("exceeds the limit"));
  // A missing or absolute data file.
  writeFile(path, kHead + "encoding: raw\ndata file: nothere.raw\n");
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("nothere.raw"));
  writeFile(path, kHead + "encoding: raw\ndata file: /etc/passwd\n");
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("absolute path"));
  // A file range of 2^63 files.
  writeFile(path, kHead +
                      "encoding: raw\ndata file: s%d.raw -9223372036854775807 "
                      "9223372036854775807 1\n");
  CHECK_THROWS_WITH(openVolumeSlabs(path.string()), Contains("expected 7"));
  // A slice range outside the grid.
  writeFile(path, kHead + "encoding: raw\n\n" + fieldBytes(0, 7));
  auto reader = openVolumeSlabs(path.string());
  std::vector<float> out;
  CHECK_THROWS_WITH(reader->readSlices(3, 8, out), Contains("z0 < z1 <= 7"));
  CHECK_THROWS_WITH(reader->readSlices(3, 3, out), Contains("z0 < z1 <= 7"));
  // A file that shrinks after opening: the short read names the offset.
  writeFile(path, kHead + "encoding: raw\n\n" + fieldBytes(0, 2));
  CHECK_THROWS_WITH(reader->readSlices(0, 7, out), Contains("short read at byte offset"));
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "none.nrrd").string()), Contains("none.nrrd"));
}

TEST_CASE("slab reader: raw grids with a layout, plain and gzip", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  RawLayout layout;
  layout.dims = kDims;
  layout.type = ScalarType::int16;
  layout.headerBytes = 5;
  writeFile(dir.path / "f.raw", "HEADR" + fieldBytes(0, 7));
  writeFile(dir.path / "f.raw.gz", gs::test::gzip("HEADR" + fieldBytes(0, 7)));
  for (const char* name : {"f.raw", "f.raw.gz"}) {
    auto reader = openVolumeSlabs((dir.path / name).string(), &layout);
    checkSlabs(*reader, fieldSamples());
    CHECK(readWholeVolume(*reader).samples ==
          decodeRaw("HEADR" + fieldBytes(0, 7), layout, "x").samples);
  }
  layout.dims.z = 70;
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "f.raw").string(), &layout),
                    Contains("do not match the file"));
}

TEST_CASE("slab reader: PNG stacks (folder, pattern) and TIFF stacks", "[formats][slabs]") {
  gs::test::TempDir dir("slabs");
  const glm::uvec3 d{11, 6, 12};  // 12 slices: natural order puts s10 after s9
  std::vector<float> expected8, expected16;
  fs::create_directories(dir.path / "png8");
  fs::create_directories(dir.path / "png16");
  for (std::uint32_t z = 0; z < d.z; ++z) {
    std::vector<std::uint16_t> v8, v16;
    for (std::uint32_t y = 0; y < d.y; ++y)
      for (std::uint32_t x = 0; x < d.x; ++x) {
        v8.push_back(static_cast<std::uint16_t>((x * 7 + y * 13 + z * 29) % 256));
        v16.push_back(static_cast<std::uint16_t>(fieldValue(x, y, z) + 1000));
      }
    expected8.insert(expected8.end(), v8.begin(), v8.end());
    expected16.insert(expected16.end(), v16.begin(), v16.end());
    writePng(dir.path / "png8" / ("s" + std::to_string(z) + ".png"), d.x, d.y, 8,
             PNG_COLOR_TYPE_GRAY, v8);
    char name[32];
    std::snprintf(name, sizeof name, "ct_%04u.png", z + 5);
    writePng(dir.path / "png16" / name, d.x, d.y, 16, PNG_COLOR_TYPE_GRAY, v16);
  }
  auto folder = openVolumeSlabs((dir.path / "png8").string());
  CHECK(folder->info().dims == d);
  CHECK(folder->info().sourceType == ScalarType::uint8);
  checkSlabs(*folder, expected8);
  auto pattern = openVolumeSlabs((dir.path / "png16" / "ct_%04d.png").string());
  CHECK(pattern->info().sourceType == ScalarType::uint16);
  checkSlabs(*pattern, expected16);
  // A gap in the pattern's numbers names the missing file.
  fs::remove(dir.path / "png16" / "ct_0009.png");
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "png16" / "ct_%04d.png").string()),
                    Contains("missing slice file") && Contains("ct_0009.png"));
  // A slice of another size, a colour slice.
  writePng(dir.path / "png8" / "s5.png", d.x + 1, d.y, 8, PNG_COLOR_TYPE_GRAY,
           std::vector<std::uint16_t>((d.x + 1) * d.y, 1));
  std::vector<float> out;
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "png8").string())->readSlices(0, d.z, out),
                    Contains("s5.png") && Contains("expected 11 x 6 uint8"));
  writePng(dir.path / "png8" / "s5.png", d.x, d.y, 8, PNG_COLOR_TYPE_RGB,
           std::vector<std::uint16_t>(d.x * d.y, 1));
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "png8").string())->readSlices(0, d.z, out),
                    Contains("colour PNG slices are not supported"));

  // TIFF: a folder of single-page files and one multi-page file, int16 LZW strips.
  fs::create_directories(dir.path / "tif");
  for (std::uint32_t z = 0; z < d.z; ++z) {
    TIFF* tif = TIFFOpen((dir.path / "tif" / ("p" + std::to_string(z) + ".tif")).c_str(), "w");
    REQUIRE(tif);
    writeTiffPages(tif, d, z, z + 1);
    TIFFClose(tif);
  }
  TIFF* multi = TIFFOpen((dir.path / "multi.tiff").c_str(), "w");
  REQUIRE(multi);
  writeTiffPages(multi, d, 0, d.z);
  TIFFClose(multi);
  const std::vector<float> field = fieldSamples(d);
  for (const fs::path& p : {dir.path / "tif", dir.path / "multi.tiff"}) {
    INFO(p.string());
    auto reader = openVolumeSlabs(p.string());
    CHECK(reader->info().dims == d);
    CHECK(reader->info().sourceType == ScalarType::int16);
    checkSlabs(*reader, field);
  }
  writeFile(dir.path / "tif" / "p3.tif", "II*\0garbage");
  CHECK_THROWS_WITH(openVolumeSlabs((dir.path / "tif").string())->readSlices(0, d.z, out),
                    Contains("p3.tif"));
}
