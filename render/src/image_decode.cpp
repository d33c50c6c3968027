// Texture decoding (PNG with libpng, JPEG with libjpeg-turbo, GIF with giflib;
// stb_image only for what none of them claims) and the image
// comparison metric.
// This is the only translation unit that defines STB_IMAGE_IMPLEMENTATION.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_GIF
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wnull-dereference"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <png.h>
#include "image_gif.hpp"

#include "image_jpeg.hpp"
#include "render/image.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace gs::render {

Image decodeImage(std::string_view bytes, const std::string& name, int* components) {
  if (bytes.empty()) throw std::runtime_error("cannot decode " + name + ": no data");
  if (bytes.size() > static_cast<std::size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("cannot decode " + name + ": file too large");
  int w = 0, h = 0, n = 0;
  const std::size_t maxPixels =
      std::max(kImagePixelsAlwaysAllowed, bytes.size() * kMaxImagePixelsPerByte);
  const auto tooManyPixels = [&] {
    return std::runtime_error("cannot decode " + name + ": " + std::to_string(w) + "x" +
                              std::to_string(h) + " pixels is more than " +
                              std::to_string(bytes.size()) + " bytes can hold (limit " +
                              std::to_string(kMaxImagePixelsPerByte) +
                              " pixels per byte, render::kMaxImagePixelsPerByte)");
  };
  if (detail::looksLikeGif(bytes)) {
    // The logical screen size (bytes 6..9, little-endian) bounds what giflib allocates:
    // refuse it before decoding when the file is too small to hold that many pixels.
    if (bytes.size() >= 10) {
      const auto u16 = [&](std::size_t i) {
        return int(static_cast<unsigned char>(bytes[i])) |
               (int(static_cast<unsigned char>(bytes[i + 1])) << 8);
      };
      w = u16(6);
      h = u16(8);
      if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels)
        throw tooManyPixels();
    }
    return detail::decodeGif(bytes, name, components);
  }
  if (detail::looksLikeJpeg(bytes)) {
    // libjpeg-turbo, not stb_image (see image_jpeg.hpp).
    Image image;
    std::string error;
    if (!detail::decodeJpeg(bytes, kMaxImageSide, maxPixels, image.rgba, w, h, n, error)) {
      if (error == "pixels") throw tooManyPixels();
      if (error == "size")
        throw std::runtime_error("cannot decode " + name + ": size " + std::to_string(w) + "x" +
                                 std::to_string(h) + " exceeds the limit of " +
                                 std::to_string(kMaxImageSide) + " pixels per side");
      throw std::runtime_error("cannot decode " + name + ": " + error);
    }
    image.width = w;
    image.height = h;
    if (components != nullptr) *components = n;
    return image;
  }
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) {
    // libpng's simplified API, not stb_image: stb_image 2.27 passes a null pointer to
    // memcpy for an empty first IDAT chunk (fuzz_image, UBSan).
    png_image png{};
    png.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&png, bytes.data(), bytes.size()))
      throw std::runtime_error("cannot decode " + name + ": " + png.message);
    w = static_cast<int>(png.width);
    h = static_cast<int>(png.height);
    n = ((png.format & PNG_FORMAT_FLAG_COLOR) ? 3 : 1) +
        ((png.format & PNG_FORMAT_FLAG_ALPHA) ? 1 : 0);
    if (png.width > static_cast<unsigned>(kMaxImageSide) ||
        png.height > static_cast<unsigned>(kMaxImageSide)) {
      png_image_free(&png);
      throw std::runtime_error("cannot decode " + name + ": size " + std::to_string(w) + "x" +
                               std::to_string(h) + " exceeds the limit of " +
                               std::to_string(kMaxImageSide) + " pixels per side");
    }
    if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels) {
      png_image_free(&png);
      throw tooManyPixels();
    }
    png.format = PNG_FORMAT_RGBA;
    Image image;
    image.rgba.resize(PNG_IMAGE_SIZE(png));
    if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr))
      throw std::runtime_error("cannot decode " + name + ": " + png.message);
    image.width = w;
    image.height = h;
    if (components != nullptr) *components = n;
    return image;
  }
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  if (!stbi_info_from_memory(data, size, &w, &h, &n))
    throw std::runtime_error("cannot decode " + name + ": " + stbi_failure_reason() +
                             " (PNG, JPEG and GIF are supported)");
  if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
    throw std::runtime_error("cannot decode " + name + ": size " + std::to_string(w) + "x" +
                             std::to_string(h) + " exceeds the limit of " +
                             std::to_string(kMaxImageSide) + " pixels per side");
  if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > maxPixels) throw tooManyPixels();
  stbi_uc* pixels = stbi_load_from_memory(data, size, &w, &h, &n, 4);
  if (pixels == nullptr)
    throw std::runtime_error("cannot decode " + name + ": " + stbi_failure_reason());
  Image image;
  image.width = w;
  image.height = h;
  try {
    image.rgba.assign(pixels, pixels + static_cast<std::size_t>(w) * h * 4);
  } catch (...) {
    stbi_image_free(pixels);
    throw;
  }
  stbi_image_free(pixels);
  if (components != nullptr) *components = n;
  return image;
}

Image loadImageFile(const std::string& path, int* components) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": no such file or not readable");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw std::runtime_error("cannot read " + path + ": read error");
  return decodeImage(buffer.str(), path, components);
}

ImageDifference compareImages(const Image& a, const Image& b, int channelTolerance) {
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
    throw std::invalid_argument("cannot compare images of different sizes (" +
                                std::to_string(a.width) + "x" + std::to_string(a.height) + " and " +
                                std::to_string(b.width) + "x" + std::to_string(b.height) + ")");
  ImageDifference d;
  const std::size_t pixels = static_cast<std::size_t>(a.width) * a.height;
  if (pixels == 0) {
    d.psnr = std::numeric_limits<double>::infinity();
    return d;
  }
  double sumAbs = 0.0, sumSq = 0.0;
  std::size_t differing = 0;
  for (std::size_t p = 0; p < pixels; ++p) {
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c) {
      const int delta = std::abs(int(a.rgba[p * 4 + c]) - int(b.rgba[p * 4 + c]));
      sumAbs += delta;
      sumSq += double(delta) * delta;
      if (delta > channelTolerance) differs = true;
    }
    if (differs) ++differing;
  }
  const double samples = double(pixels) * 3.0;
  d.meanAbsolute = sumAbs / samples;
  d.fractionDiffering = double(differing) / double(pixels);
  const double mse = sumSq / samples;
  d.psnr =
      mse == 0.0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
  return d;
}

}  // namespace gs::render
