// PNG files with libpng. libpng reports errors through
// longjmp; everything that has a destructor lives outside the setjmp frames, and the
// error callback only records the message before jumping.
#include "render/image.hpp"

#include <png.h>

#include <algorithm>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

namespace gs::render {

Image::Image(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a)
    : width(w), height(h) {
  if (w < 0 || h < 0) throw std::invalid_argument("negative image size");
  rgba.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  for (std::size_t i = 0; i < rgba.size(); i += 4) {
    rgba[i] = r;
    rgba[i + 1] = g;
    rgba[i + 2] = b;
    rgba[i + 3] = a;
  }
}

namespace {

struct PngError {
  std::string message;
};

void onPngError(png_structp png, png_const_charp message) {
  auto* error = static_cast<PngError*>(png_get_error_ptr(png));
  if (error != nullptr) error->message = message != nullptr ? message : "libpng error";
  png_longjmp(png, 1);
}

void onPngWarning(png_structp, png_const_charp) {}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// The setjmp frames below hold only trivially destructible locals.
bool writePngRows(std::FILE* file, const Image& image, png_bytep* rows, PngError& error) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &error, &onPngError, &onPngWarning);
  if (png == nullptr) {
    error.message = "out of memory";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    error.message = "out of memory";
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Speed over size (frame sequences of --snapshot --time T0:DT:N spent most of their
  // time in zlib at the default level 6 with adaptive filtering): zlib level 1 with the
  // Sub filter writes a 1280x960 frame several times faster, files somewhat larger
  // (docs/rendering.md, "Writing frames"). Still a valid PNG for every reader.
  png_set_compression_level(png, 1);
  png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

struct PngHeader {
  png_uint_32 width = 0, height = 0;
};

// Reads into `pixels`, which the caller sizes after the header callback; two phases keep
// the vector (which has a destructor) out of the setjmp frame's responsibilities.
bool readPngFile(std::FILE* file, std::vector<std::uint8_t>& pixels, PngHeader& header,
                 PngError& error) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &error, &onPngError, &onPngWarning);
  if (png == nullptr) {
    error.message = "out of memory";
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    error.message = "out of memory";
    return false;
  }
  // Assigned after setjmp and read after a longjmp: must be volatile.
  png_bytep* volatile rows = nullptr;
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::free(rows);
    return false;
  }
  png_set_user_limits(png, kMaxImageSide, kMaxImageSide);
  png_init_io(png, file);
  png_read_info(png, info);
  header.width = png_get_image_width(png, info);
  header.height = png_get_image_height(png, info);
  const int colorType = png_get_color_type(png, info);
  const int bitDepth = png_get_bit_depth(png, info);
  if (bitDepth == 16) png_set_strip_16(png);
  if (colorType == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colorType == PNG_COLOR_TYPE_GRAY && bitDepth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA)
    png_set_gray_to_rgb(png);
  if (!(colorType & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS))
    png_set_filler(png, 0xFF, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != static_cast<png_size_t>(header.width) * 4) {
    error.message = "unsupported pixel layout";
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  // resize() may throw std::bad_alloc: that is not a longjmp, so clean up by hand.
  try {
    pixels.resize(static_cast<std::size_t>(header.width) * header.height * 4);
  } catch (...) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw;
  }
  rows = static_cast<png_bytep*>(std::malloc(sizeof(png_bytep) * header.height));
  if (rows == nullptr) {
    png_destroy_read_struct(&png, &info, nullptr);
    error.message = "out of memory";
    return false;
  }
  for (png_uint_32 r = 0; r < header.height; ++r)
    rows[r] = pixels.data() + static_cast<std::size_t>(r) * header.width * 4;
  png_read_image(png, const_cast<png_bytep*>(rows));
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::free(rows);
  return true;
}

}  // namespace

void writePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw std::runtime_error("cannot write " + path + ": the image is empty or inconsistent");
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file)
    throw std::runtime_error("cannot write " + path + ": cannot open the file for writing");
  std::vector<png_bytep> rows(static_cast<std::size_t>(image.height));
  for (int r = 0; r < image.height; ++r)
    rows[static_cast<std::size_t>(r)] =
        const_cast<png_bytep>(image.rgba.data() + static_cast<std::size_t>(r) * image.width * 4);
  PngError error;
  if (!writePngRows(file.get(), image, rows.data(), error))
    throw std::runtime_error("cannot write " + path + ": " + error.message);
  if (std::fclose(file.release()) != 0)
    throw std::runtime_error("cannot write " + path + ": error closing the file (disk full?)");
}

Image readPng(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) throw std::runtime_error("cannot read " + path + ": no such file or not readable");
  unsigned char signature[8] = {};
  if (std::fread(signature, 1, 8, file.get()) != 8 || png_sig_cmp(signature, 0, 8) != 0)
    throw std::runtime_error("cannot read " + path + ": not a PNG file");
  std::rewind(file.get());
  Image image;
  PngHeader header;
  PngError error;
  if (!readPngFile(file.get(), image.rgba, header, error))
    throw std::runtime_error("cannot read " + path + ": " + error.message);
  image.width = static_cast<int>(header.width);
  image.height = static_cast<int>(header.height);
  return image;
}

}  // namespace gs::render
