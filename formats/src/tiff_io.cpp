// TIFF pages through libtiff (tiff_io.hpp), from a file or from bytes in memory.
#include "tiff_io.hpp"

#include "qnv/volume_slabs.hpp"

#include <tiffio.h>

#include <algorithm>
#include <bit>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

namespace gs::formats::detail {

namespace {

constexpr bool kTiffNativeBig = std::endian::native == std::endian::big;

int tiffError(TIFF*, void* user, const char* module, const char* fmt, va_list ap) {
  char buffer[512];
  std::vsnprintf(buffer, sizeof buffer, fmt, ap);
  auto* message = static_cast<std::string*>(user);
  if (message->empty()) {
    // Printable ASCII only: libtiff may quote bytes of the file.
    std::string text = std::string(module ? module : "libtiff") + ": " + buffer;
    for (char& c : text)
      if (c < 0x20 || c > 0x7e) c = '?';
    *message = text;
  }
  return 1;
}

int tiffWarning(TIFF*, void*, const char*, const char*, va_list) {
  return 1;
}

// libtiff client procedures over TiffFile::Memory.
tmsize_t tiffMemRead(thandle_t h, void* buf, tmsize_t size) {
  auto* m = static_cast<TiffFile::Memory*>(h);
  if (size <= 0 || m->at >= m->bytes.size()) return 0;
  const std::uint64_t n =
      std::min<std::uint64_t>(static_cast<std::uint64_t>(size), m->bytes.size() - m->at);
  std::memcpy(buf, m->bytes.data() + m->at, static_cast<std::size_t>(n));
  m->at += n;
  return static_cast<tmsize_t>(n);
}
tmsize_t tiffMemWrite(thandle_t, void*, tmsize_t) {
  return 0;
}
toff_t tiffMemSeek(thandle_t h, toff_t off, int whence) {
  auto* m = static_cast<TiffFile::Memory*>(h);
  std::uint64_t base = 0;
  if (whence == SEEK_CUR) base = m->at;
  if (whence == SEEK_END) base = m->bytes.size();
  if (off > UINT64_MAX - base) return static_cast<toff_t>(-1);
  m->at = base + off;  // beyond the end: reads give 0 bytes
  return m->at;
}
int tiffMemClose(thandle_t) {
  return 0;
}
toff_t tiffMemSize(thandle_t h) {
  return static_cast<TiffFile::Memory*>(h)->bytes.size();
}
int tiffMemMap(thandle_t, void**, toff_t*) {
  return 0;
}
void tiffMemUnmap(thandle_t, void*, toff_t) {}

}  // namespace

std::string shapeText(const SliceShape& s) {
  return std::to_string(s.width) + " x " + std::to_string(s.height) + " " + scalarTypeName(s.type);
}

TiffFile::TiffFile(const std::string& path) : name_(path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  fileBytes_ = ec ? 0 : static_cast<std::uint64_t>(size);
  open(nullptr);
}

TiffFile::TiffFile(std::string_view bytes, const std::string& name)
    : name_(name), memory_{bytes, 0}, fileBytes_(bytes.size()), inMemory_(true) {
  open("rm");  // "m": no memory mapping (there is no file)
}

void TiffFile::open(const char* mode) {
  TIFFOpenOptions* options = TIFFOpenOptionsAlloc();
  TIFFOpenOptionsSetErrorHandlerExtR(options, tiffError, &message_);
  TIFFOpenOptionsSetWarningHandlerExtR(options, tiffWarning, nullptr);
  TIFFOpenOptionsSetMaxSingleMemAlloc(options, tmsize_t{1} << 30);
  if (inMemory_)
    tif_ = TIFFClientOpenExt(name_.c_str(), mode, &memory_, tiffMemRead, tiffMemWrite, tiffMemSeek,
                             tiffMemClose, tiffMemSize, tiffMemMap, tiffMemUnmap, options);
  else
    tif_ = TIFFOpenExt(name_.c_str(), "r", options);
  TIFFOpenOptionsFree(options);
  if (!tif_) fail("cannot open as TIFF");
}

TiffFile::~TiffFile() {
  if (tif_) TIFFClose(tif_);
}

void TiffFile::fail(const std::string& what) const {
  throw InputError(name_ + ": " + what + (message_.empty() ? "" : " (" + message_ + ")"));
}

std::uint32_t TiffFile::pages() {
  return TIFFNumberOfDirectories(tif_);
}

std::string TiffFile::description() {
  if (!TIFFSetDirectory(tif_, 0)) return {};
  const char* text = nullptr;
  if (!TIFFGetField(tif_, TIFFTAG_IMAGEDESCRIPTION, &text) || !text) return {};
  return std::string(text, strnlen(text, std::size_t{16} << 20));
}

SliceShape TiffFile::shape(std::uint32_t page) {
  if (!TIFFSetDirectory(tif_, static_cast<tdir_t>(page)))
    fail("cannot read page " + std::to_string(page));
  std::uint32_t w = 0, h = 0;
  std::uint16_t bits = 0, samples = 1, format = SAMPLEFORMAT_UINT;
  TIFFGetField(tif_, TIFFTAG_IMAGEWIDTH, &w);
  TIFFGetField(tif_, TIFFTAG_IMAGELENGTH, &h);
  TIFFGetFieldDefaulted(tif_, TIFFTAG_BITSPERSAMPLE, &bits);
  TIFFGetFieldDefaulted(tif_, TIFFTAG_SAMPLESPERPIXEL, &samples);
  TIFFGetFieldDefaulted(tif_, TIFFTAG_SAMPLEFORMAT, &format);
  if (samples != 1)
    fail("TIFF slices with " + std::to_string(samples) +
         " samples per pixel are not supported (expected one grey sample)");
  SliceShape s;
  s.width = w;
  s.height = h;
  const bool ok = [&] {
    if (format == SAMPLEFORMAT_UINT && bits == 8) return s.type = ScalarType::uint8, true;
    if (format == SAMPLEFORMAT_UINT && bits == 16) return s.type = ScalarType::uint16, true;
    if (format == SAMPLEFORMAT_UINT && bits == 32) return s.type = ScalarType::uint32, true;
    if (format == SAMPLEFORMAT_INT && bits == 8) return s.type = ScalarType::int8, true;
    if (format == SAMPLEFORMAT_INT && bits == 16) return s.type = ScalarType::int16, true;
    if (format == SAMPLEFORMAT_INT && bits == 32) return s.type = ScalarType::int32, true;
    if (format == SAMPLEFORMAT_IEEEFP && bits == 32) return s.type = ScalarType::float32, true;
    if (format == SAMPLEFORMAT_IEEEFP && bits == 64) return s.type = ScalarType::float64, true;
    return false;
  }();
  if (!ok)
    fail("TIFF samples of " + std::to_string(bits) + " bits in sample format " +
         std::to_string(format) + " are not supported");
  if (w == 0 || h == 0 || std::uint64_t{w} * h > qnv::kMaxSliceVoxels)
    fail("page of " + std::to_string(w) + " x " + std::to_string(h) +
         " pixels is empty or over the slice limit");
  return s;
}

void TiffFile::checkStoredBytes(std::uint32_t page, std::uint64_t sampleBytes) {
  if (!TIFFSetDirectory(tif_, static_cast<tdir_t>(page)))
    fail("cannot read page " + std::to_string(page));
  const bool tiled = TIFFIsTiled(tif_);
  const std::uint32_t n = tiled ? TIFFNumberOfTiles(tif_) : TIFFNumberOfStrips(tif_);
  std::uint64_t* counts = nullptr;
  if (n == 0 ||
      !TIFFGetField(tif_, tiled ? TIFFTAG_TILEBYTECOUNTS : TIFFTAG_STRIPBYTECOUNTS, &counts) ||
      !counts)
    fail("page " + std::to_string(page) + " has no strip or tile byte counts");
  std::uint64_t stored = 0;
  for (std::uint32_t i = 0; i < n; ++i) stored += std::min<std::uint64_t>(counts[i], 1ull << 40);
  // libtiff estimates or splits the counts of some files (one big uncompressed strip, no
  // StripByteCounts): no page stores more than the whole file.
  stored = std::min(stored, fileBytes_);
  std::uint16_t compression = COMPRESSION_NONE;
  TIFFGetFieldDefaulted(tif_, TIFFTAG_COMPRESSION, &compression);
  if (compression == COMPRESSION_NONE ? stored < sampleBytes
                                      : sampleBytes > stored * 1032 + (std::uint64_t{1} << 20))
    fail("page " + std::to_string(page) + " stores " + std::to_string(stored) +
         " bytes, which cannot hold its " + std::to_string(sampleBytes) + " bytes of samples");
}

void TiffFile::read(std::uint32_t page, const SliceShape& expect, float* out) {
  const SliceShape s = shape(page);
  if (!(s == expect))
    fail("page " + std::to_string(page) + " is " + shapeText(s) + ", expected " +
         shapeText(expect) + " as the first slice");
  const std::size_t bytes = scalarBytes(s.type);
  if (TIFFIsTiled(tif_)) {
    std::uint32_t tw = 0, th = 0;
    TIFFGetField(tif_, TIFFTAG_TILEWIDTH, &tw);
    TIFFGetField(tif_, TIFFTAG_TILELENGTH, &th);
    if (tw == 0 || th == 0 || std::uint64_t{tw} * th > qnv::kMaxSliceVoxels)
      fail("bad tile size " + std::to_string(tw) + " x " + std::to_string(th));
    const tmsize_t tileBytes = TIFFTileSize(tif_);
    if (tileBytes <= 0 || static_cast<std::uint64_t>(tileBytes) < std::uint64_t{tw} * th * bytes)
      fail("bad tile size");
    std::vector<char> tile(static_cast<std::size_t>(tileBytes));
    for (std::uint32_t y0 = 0; y0 < s.height; y0 += th)
      for (std::uint32_t x0 = 0; x0 < s.width; x0 += tw) {
        if (TIFFReadTile(tif_, tile.data(), x0, y0, 0, 0) < 0)
          fail("cannot read the tile at (" + std::to_string(x0) + ", " + std::to_string(y0) + ")");
        const std::uint32_t cw = std::min(tw, s.width - x0);
        for (std::uint32_t y = y0; y < std::min(y0 + th, s.height); ++y)
          convertSamples(tile.data() + std::size_t{tw} * (y - y0) * bytes, cw, s.type,
                         kTiffNativeBig, out + std::size_t{s.width} * y + x0);
      }
    return;
  }
  const tmsize_t rowBytes = TIFFScanlineSize(tif_);
  if (rowBytes <= 0 || static_cast<std::uint64_t>(rowBytes) < std::uint64_t{s.width} * bytes)
    fail("bad scanline size");
  std::vector<char> row(static_cast<std::size_t>(rowBytes));
  for (std::uint32_t y = 0; y < s.height; ++y) {
    if (TIFFReadScanline(tif_, row.data(), y, 0) < 0)
      fail("cannot read row " + std::to_string(y) + " of page " + std::to_string(page));
    convertSamples(row.data(), s.width, s.type, kTiffNativeBig, out + std::size_t{s.width} * y);
  }
}

}  // namespace gs::formats::detail
