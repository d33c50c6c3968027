// 8-bit RGBA images: reading the framebuffer, PNG files (libpng), texture decoding
// (libpng: PNG; libjpeg-turbo: JPEG; giflib: GIF) and the image comparison used by the
// baseline tests.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gs::render {

/// An image of width x height pixels, 4 bytes (R, G, B, A) each, rows from top to bottom.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes

  Image() = default;
  /// An image of the given size filled with one colour.
  Image(int w, int h, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
        std::uint8_t a = 255);
  /// Pointer to the 4 bytes of pixel (x, y), y counted from the top row.
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const std::uint8_t* pixel(int x, int y) const {
    return &rgba[(static_cast<std::size_t>(y) * width + x) * 4];
  }
  bool empty() const { return width <= 0 || height <= 0; }
};

/// Largest accepted side of a decoded image, in pixels.
inline constexpr int kMaxImageSide = 16384;
/// Pixels a decoded image may have per byte of its file (beyond the first 4 Mi pixels,
/// always allowed): a header may claim any size, and the decoders allocate what it claims
/// before reading the data. PNG (deflate, at most 1032:1, 8 pixels a byte at 1 bit),
/// JPEG (a 64-pixel block in a few bits) and GIF (LZW, at most about 11,000 pixels a
/// byte) files stay under it; a 12-byte GIF claiming 16247 x 16247 does not.
inline constexpr std::size_t kMaxImagePixelsPerByte = 16384;
inline constexpr std::size_t kImagePixelsAlwaysAllowed = std::size_t{1} << 22;

/// Reads the rectangle (x, y, w, h) of the current read framebuffer (x, y = its lower-left
/// corner in GL window coordinates, pixels) and returns it with rows top to bottom; a
/// multisampled framebuffer is resolved first (render/context.hpp, readFramebufferPixels).
/// Needs a current context with loaded functions. Throws std::runtime_error for a
/// non-positive size.
Image readPixels(int x, int y, int w, int h);

/// Writes `image` as an 8-bit RGBA PNG. Throws std::runtime_error naming `path` and the
/// reason (cannot open, libpng error, empty or inconsistent image).
void writePng(const std::string& path, const Image& image);

/// Reads a PNG of any bit depth and colour type, converted to 8-bit RGBA. Throws
/// std::runtime_error naming `path` and the reason (missing file, not a PNG, corrupt data,
/// larger than kMaxImageSide).
Image readPng(const std::string& path);

/// Decodes a PNG, JPEG or GIF held in memory to 8-bit RGBA (PNG with libpng, JPEG with
/// libjpeg-turbo: stb_image 2.27's PNG and JPEG decoders fail under UBSan on corrupt files,
/// tests/data/regressions/image; GIF with giflib: first image, transparent index as alpha
/// 0, 3 components or 4 with transparent pixels); grey images have R = G = B; a PNG's tRNS
/// chunk counts as alpha (ISO/IEC 14772-1 5.5, 6.22);
/// `components` receives the number of channels the file had (1 grey, 2 grey+alpha,
/// 3 RGB, 4 RGBA) when not null. `name` names the data in error messages. Throws
/// std::runtime_error for undecodable data, for images larger than kMaxImageSide and for
/// images with more pixels than kMaxImagePixelsPerByte per byte of `bytes` allow.
/// Safe for untrusted input.
Image decodeImage(std::string_view bytes, const std::string& name = "image",
                  int* components = nullptr);

/// Reads the file at `path` and decodes it as decodeImage does. Throws std::runtime_error
/// naming the path when the file cannot be read or decoded.
Image loadImageFile(const std::string& path, int* components = nullptr);

/// How two images of the same size differ (the metric of the baseline image tests):
/// - meanAbsolute: the mean over all pixels and the R, G, B channels of |a - b|, in 0..255
///   (alpha is ignored);
/// - fractionDiffering: the fraction (0..1) of pixels where any of R, G, B differs by more
///   than the channel tolerance;
/// - psnr: peak signal-to-noise ratio over R, G, B in decibels, 10 log10(255^2 / MSE);
///   +infinity for identical images.
/// A baseline test passes when fractionDiffering is at most its threshold (typically 0.01
/// with tolerance 16, which absorbs rasterization differences between Mesa versions).
struct ImageDifference {
  double meanAbsolute = 0.0;
  double fractionDiffering = 0.0;
  double psnr = 0.0;
};

/// Compares two images pixel by pixel (see ImageDifference). Throws std::invalid_argument
/// when their sizes differ.
ImageDifference compareImages(const Image& a, const Image& b, int channelTolerance = 16);

}  // namespace gs::render
