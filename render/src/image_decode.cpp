// Texture decoding (PNG and JPEG with stb_image, GIF with giflib) and the image
// comparison metric. This is the only translation unit that defines
// STB_IMAGE_IMPLEMENTATION.
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS 16384
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
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

#include "image_gif.hpp"
#include "render/image.hpp"

#include <cmath>
#include <cstdlib>
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
  if (detail::looksLikeGif(bytes)) return detail::decodeGif(bytes, name, components);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int size = static_cast<int>(bytes.size());
  int w = 0, h = 0, n = 0;
  if (!stbi_info_from_memory(data, size, &w, &h, &n))
    throw std::runtime_error("cannot decode " + name + ": " + stbi_failure_reason() +
                             " (PNG, JPEG and GIF are supported)");
  if (w <= 0 || h <= 0 || w > kMaxImageSide || h > kMaxImageSide)
    throw std::runtime_error("cannot decode " + name + ": size " + std::to_string(w) + "x" +
                             std::to_string(h) + " exceeds the limit of " +
                             std::to_string(kMaxImageSide) + " pixels per side");
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
