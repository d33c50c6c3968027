// Stacks of 2-D slices read slab by slab (formats/volume_slabs.hpp): PNG through libpng,
// TIFF through libtiff, one image (or TIFF page) per z slice.
#include <png.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "base/text.hpp"
#include "formats/tiff_reader.hpp"
#include "formats/volume_slabs.hpp"
#include "slab_io.hpp"
#include "tiff_io.hpp"

namespace gs::formats::detail {

void checkGrid(const VolumeGridInfo& info, const std::string& name) {
  const glm::uvec3 d = info.dims;
  if (d.x == 0 || d.y == 0 || d.z == 0)
    throw InputError(name + ": expected volume dimensions >= 1, got " + std::to_string(d.x) +
                     " x " + std::to_string(d.y) + " x " + std::to_string(d.z));
  if (info.sliceVoxels() > qnv::kMaxSliceVoxels)
    throw InputError(name + ": slices of " + std::to_string(d.x) + " x " + std::to_string(d.y) +
                     " voxels exceed the limit of " + std::to_string(qnv::kMaxSliceVoxels) +
                     " voxels per slice (qnv::kMaxSliceVoxels)");
  if (info.voxelCount() > qnv::kMaxSlabVolumeVoxels)
    throw InputError(name + ": volume of " + std::to_string(d.x) + " x " + std::to_string(d.y) +
                     " x " + std::to_string(d.z) + " voxels exceeds the limit of " +
                     std::to_string(qnv::kMaxSlabVolumeVoxels) +
                     " voxels (qnv::kMaxSlabVolumeVoxels)");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(info.spacing[i]) || !(info.spacing[i] > 0.0f))
      throw InputError(name + ": expected spacings > 0, got " + std::to_string(info.spacing[i]));
}

namespace {

// ------------------------------------------------------------------------------- PNG

struct PngError {
  std::string message;
};

void pngError(png_structp png, png_const_charp message) {
  static_cast<PngError*>(png_get_error_ptr(png))->message = message ? message : "libpng error";
  png_longjmp(png, 1);
}

void pngWarning(png_structp, png_const_charp) {}

// Decodes the grey PNG at `path`: its shape into `shape`, and, when `out` is given,
// its samples (after checking the shape equals `expect`).
void readPng(const std::string& path, SliceShape& shape, const SliceShape* expect, float* out) {
  const RandomFile file(path);  // opens (or names the error) and gives the size
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError("cannot open " + path);
  PngError error;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, pngError, pngWarning);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  std::vector<png_byte> pixels;
  std::vector<png_bytep> rows;
  if (!png || !info) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    throw InputError(path + ": cannot start libpng");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(f);
    throw InputError(path + ": bad PNG: " + error.message);
  }
  png_set_user_limits(png, 1u << 20, 1u << 20);
  png_init_io(png, f);
  png_read_info(png, info);
  const png_uint_32 w = png_get_image_width(png, info), h = png_get_image_height(png, info);
  const int color = png_get_color_type(png, info), depth = png_get_bit_depth(png, info);
  if (color != PNG_COLOR_TYPE_GRAY && color != PNG_COLOR_TYPE_GRAY_ALPHA) {
    error.message = "colour PNG slices are not supported (expected grey, 1 to 16 bits)";
    png_longjmp(png, 1);
  }
  shape.width = w;
  shape.height = h;
  shape.type = depth == 16 ? ScalarType::uint16 : ScalarType::uint8;
  const std::uint64_t bytes = std::uint64_t{w} * h * (depth == 16 ? 2 : 1);
  if (std::uint64_t{w} * h > qnv::kMaxSliceVoxels || bytes > file.size() * 1032 + 64 * 1024) {
    error.message = "image of " + std::to_string(w) + " x " + std::to_string(h) +
                    " pixels is more than the file's " + std::to_string(file.size()) +
                    " bytes can hold, or more than the slice limit";
    png_longjmp(png, 1);
  }
  if (out) {
    if (expect && !(shape == *expect)) {
      error.message = "slice is " + shapeText(shape) + ", expected " + shapeText(*expect) +
                      " as the first slice";
      png_longjmp(png, 1);
    }
    if (depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    if (color == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_strip_alpha(png);
    png_set_interlace_handling(png);
    png_read_update_info(png, info);
    const std::size_t rowBytes = png_get_rowbytes(png, info);
    pixels.resize(rowBytes * h);
    rows.resize(h);
    for (png_uint_32 y = 0; y < h; ++y) rows[y] = pixels.data() + rowBytes * y;
    png_read_image(png, rows.data());
    png_read_end(png, nullptr);
    for (png_uint_32 y = 0; y < h; ++y)
      convertSamples(reinterpret_cast<const char*>(rows[y]), w, shape.type, true,
                     out + std::size_t{w} * y);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
}

OmePixels omeOfDescription(const std::string& description) {
  if (description.find("<OME") == std::string::npos &&
      description.find(":OME") == std::string::npos)
    return {};
  return parseOmeXml(description);
}

bool isTiff(const std::string& name) {
  return base::endsWithNoCase(name, ".tif") || base::endsWithNoCase(name, ".tiff");
}
bool isPng(const std::string& name) {
  return base::endsWithNoCase(name, ".png");
}

// ------------------------------------------------------------------------ the stack

class SliceStackReader final : public VolumeSlabReader {
 public:
  // `files`: one image per slice; or one multi-page TIFF (`pages` > 0).
  SliceStackReader(std::vector<std::string> files, std::uint32_t pages)
      : files_(std::move(files)), pages_(pages) {
    SliceShape first;
    std::uint64_t slices = pages_ > 0 ? pages_ : files_.size();
    if (pages_ > 0) {
      tiff_ = std::make_unique<TiffFile>(files_.front());
      first = tiff_->shape(0);
      // OME-TIFF (formats/tiff_reader.hpp): channel 0 at time 0, physical sizes.
      ome_ = omeOfDescription(tiff_->description());
      if (ome_.found) {
        const std::uint64_t planes = ome_.sizeZ * ome_.sizeC * ome_.sizeT;
        if (planes > pages_)
          throw InputError(files_.front() + ": the OME-XML describes " + std::to_string(planes) +
                           " planes, the file has " + std::to_string(pages_) +
                           " pages (multi-file OME-TIFF is not supported)");
        slices = ome_.sizeZ;
        info_.spacing = ome_.spacing;
      }
    } else if (isTiff(files_.front())) {
      TiffFile tiff(files_.front());
      first = tiff.shape(0);
      // Single-page OME-TIFFs in a folder: the first one's physical sizes.
      if (const OmePixels ome = omeOfDescription(tiff.description()); ome.found)
        info_.spacing = ome.spacing;
    } else {
      readPng(files_.front(), first, nullptr, nullptr);
    }
    shape_ = first;
    info_.dims = {first.width, first.height, static_cast<std::uint32_t>(slices)};
    info_.sourceType = first.type;
    checkGrid(info_, files_.front());
  }

  const VolumeGridInfo& info() const override { return info_; }

  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    if (!(z0 < z1 && z1 <= info_.dims.z))
      throw InputError(files_.front() +
                       ": expected slices 0 <= z0 < z1 <= " + std::to_string(info_.dims.z) +
                       ", got [" + std::to_string(z0) + ", " + std::to_string(z1) + ")");
    const std::size_t slice = static_cast<std::size_t>(info_.sliceVoxels());
    out.resize(slice * (z1 - z0));
    for (std::uint32_t z = z0; z < z1; ++z) {
      float* dst = out.data() + slice * (z - z0);
      if (pages_ > 0) {
        tiff_->read(static_cast<std::uint32_t>(ome_.found ? ome_.pageOfSlice(z) : z), shape_, dst);
      } else if (isTiff(files_[z])) {
        TiffFile(files_[z]).read(0, shape_, dst);
      } else {
        SliceShape s;
        readPng(files_[z], s, &shape_, dst);
      }
    }
  }

 private:
  std::vector<std::string> files_;
  std::uint32_t pages_;
  std::unique_ptr<TiffFile> tiff_;
  OmePixels ome_;  // found = false unless a multi-page OME-TIFF
  SliceShape shape_;
  VolumeGridInfo info_;
};

// "s2" < "s10": digit runs compare as numbers.
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool db = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (da && db) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      std::string_view na(a.data() + i, ie - i), nb(b.data() + j, je - j);
      while (na.size() > 1 && na.front() == '0') na.remove_prefix(1);
      while (nb.size() > 1 && nb.front() == '0') nb.remove_prefix(1);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j || (a.size() - i == b.size() - j && a < b);
}

// The file names of a printf-style pattern "prefix%[0][width]d suffix".
struct Pattern {
  std::string prefix, suffix;
  bool zero = false;
  std::size_t width = 0;

  std::string format(std::uint64_t i) const {
    std::string digits = std::to_string(i);
    if (digits.size() < width) digits.insert(0, width - digits.size(), zero ? '0' : ' ');
    return prefix + digits + suffix;
  }
};

Pattern parsePattern(const std::string& name, const std::string& whole) {
  Pattern p;
  const std::size_t at = name.find('%');
  std::size_t k = at + 1;
  if (k < name.size() && name[k] == '0') p.zero = true, ++k;
  while (k < name.size() && std::isdigit(static_cast<unsigned char>(name[k])) && p.width < 100)
    p.width = p.width * 10 + static_cast<std::size_t>(name[k++] - '0');
  if (k >= name.size() || (name[k] != 'd' && name[k] != 'i' && name[k] != 'u') || p.width > 32 ||
      name.find('%', k) != std::string::npos)
    throw InputError(whole +
                     ": expected a file name pattern with one integer conversion (%d, %03d)");
  p.prefix = name.substr(0, at);
  p.suffix = name.substr(k + 1);
  return p;
}

std::vector<std::string> patternFiles(const std::string& pattern) {
  const std::filesystem::path whole(pattern);
  std::filesystem::path dir = whole.parent_path();
  if (dir.empty()) dir = ".";
  const Pattern p = parsePattern(whole.filename().string(), pattern);
  std::map<std::uint64_t, std::string> found;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= p.prefix.size() + p.suffix.size() || !name.starts_with(p.prefix) ||
        !name.ends_with(p.suffix))
      continue;
    const std::string middle =
        name.substr(p.prefix.size(), name.size() - p.prefix.size() - p.suffix.size());
    std::string digits = middle;  // "%3d" pads with spaces
    digits.erase(0, std::min(digits.find_first_not_of(' '), digits.size()));
    if (digits.empty() || digits.size() > 18 ||
        !std::all_of(digits.begin(), digits.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      continue;
    const std::uint64_t i = std::stoull(digits);
    if (p.format(i) == name) found[i] = (dir / name).string();
  }
  if (ec) throw InputError("cannot list the folder of " + pattern + ": " + ec.message());
  if (found.empty()) throw InputError(pattern + ": no file matches the pattern");
  const std::uint64_t lo = found.begin()->first, hi = found.rbegin()->first;
  std::vector<std::string> files;
  for (const auto& [i, path] : found) {
    const std::uint64_t expected = lo + files.size();
    if (i != expected)
      throw InputError(pattern + ": missing slice file '" + (dir / p.format(expected)).string() +
                       "' (the pattern's files run from " + std::to_string(lo) + " to " +
                       std::to_string(hi) + ")");
    files.push_back(path);
  }
  return files;
}

std::vector<std::string> folderFiles(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if ((isPng(name) || isTiff(name)) && !name.starts_with(".")) names.push_back(name);
  }
  if (ec) throw InputError("cannot list " + folder + ": " + ec.message());
  if (names.empty()) throw InputError(folder + ": no .png, .tif or .tiff slices in the folder");
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> files;
  for (const std::string& n : names) files.push_back((std::filesystem::path(folder) / n).string());
  return files;
}

}  // namespace

std::unique_ptr<VolumeSlabReader> openSliceStack(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    return std::make_unique<SliceStackReader>(folderFiles(path), 0);
  if (std::filesystem::path(path).filename().string().find('%') != std::string::npos)
    return std::make_unique<SliceStackReader>(patternFiles(path), 0);
  if (isTiff(path)) {
    const std::uint32_t pages = TiffFile(path).pages();
    if (pages == 0) throw InputError(path + ": a TIFF without pages");
    return std::make_unique<SliceStackReader>(std::vector<std::string>{path}, pages);
  }
  return std::make_unique<SliceStackReader>(std::vector<std::string>{path}, 0);
}

}  // namespace gs::formats::detail
