// Image figures shared by the comparison benchmarks (compare_reference, compare_png;
// docs/castle-comparison.md): the background-masked metric and the foreground share.
#pragma once

#include "render/image.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace gs::bench {

/// Whether the RGB channels of two pixels differ by at most `tolerance` (of 255).
inline bool sameColour(const std::uint8_t* a, const std::uint8_t* b, int tolerance) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(a[c]) - int(b[c])) > tolerance) return false;
  return true;
}

/// Fraction of the pixels of `image` that differ from its top-left pixel (taken as the
/// background) by more than 2 per channel.
inline double foregroundFraction(const render::Image& image) {
  const std::uint8_t* corner = image.pixel(0, 0);
  std::size_t count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!sameColour(image.pixel(x, y), corner, 2)) ++count;
  return double(count) / (double(image.width) * image.height);
}

/// render::compareImages(ours, reference, tolerance) after making equal every pixel that is
/// background in both images (each image's own corner colour, 2 per channel of tolerance).
/// The images must have the same size.
inline render::ImageDifference maskedDifference(const render::Image& ours,
                                                const render::Image& reference, int tolerance) {
  render::Image masked = ours;
  const std::uint8_t* ourBackground = ours.pixel(0, 0);
  const std::uint8_t* referenceBackground = reference.pixel(0, 0);
  for (int y = 0; y < ours.height; ++y)
    for (int x = 0; x < ours.width; ++x)
      if (sameColour(ours.pixel(x, y), ourBackground, 2) &&
          sameColour(reference.pixel(x, y), referenceBackground, 2))
        std::memcpy(masked.pixel(x, y), reference.pixel(x, y), 4);
  return render::compareImages(masked, reference, tolerance);
}

/// PSNR in dB with one decimal, "inf" for identical images.
inline std::string formatPsnr(double psnr) {
  if (!std::isfinite(psnr)) return "inf";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", psnr);
  return buffer;
}

}  // namespace gs::bench
