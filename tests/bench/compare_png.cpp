// compare_png: prints the project's image metric between two PNG files.
//
//   compare_png [--tolerance N] [--markdown] OURS.png REFERENCE.png
//
// The metric is render::compareImages (docs/rendering-tests.md): `differ` = fraction of
// pixels with an R, G or B channel off by more than the tolerance (16 of 255 by default),
// `meanAbs` = mean |a - b| over the R, G, B channels, `PSNR` in dB. Also printed, as in
// tests/bench/compare_reference.cpp (docs/castle-comparison.md): the background-masked
// `differ` and `PSNR`, where a pixel that shows each image's own background (its top-left
// corner colour, +-2 per channel) in both images counts as equal, and `fg`, the fraction of
// each image's pixels that are not its corner colour.
//
// Default output is one line of key=value pairs; --markdown prints the same figures as
// the cells of a markdown table row (differ %, meanAbs, PSNR, masked differ %, masked
// PSNR, fg ours %, fg reference %), without the leading and trailing bars.
// Exit status: 0 on success, 1 on unreadable files or different sizes, 2 on bad usage.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "image_metrics.hpp"
#include "render/image.hpp"

namespace {

using gs::bench::foregroundFraction;
using gs::bench::formatPsnr;
using gs::bench::maskedDifference;

using gs::render::Image;
using gs::render::ImageDifference;

int usage() {
  std::fprintf(stderr, "usage: compare_png [--tolerance N] [--markdown] OURS.png REFERENCE.png\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int tolerance = 16;
  bool markdown = false;
  const char* paths[2] = {nullptr, nullptr};
  int count = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--tolerance" && i + 1 < argc) {
      tolerance = std::atoi(argv[++i]);
    } else if (arg == "--markdown") {
      markdown = true;
    } else if (!arg.empty() && arg[0] == '-') {
      return usage();
    } else if (count < 2) {
      paths[count++] = argv[i];
    } else {
      return usage();
    }
  }
  if (count != 2) return usage();

  try {
    const Image ours = gs::render::readPng(paths[0]);
    const Image reference = gs::render::readPng(paths[1]);
    if (ours.width != reference.width || ours.height != reference.height) {
      std::fprintf(stderr, "compare_png: sizes differ: %s is %dx%d, %s is %dx%d\n", paths[0],
                   ours.width, ours.height, paths[1], reference.width, reference.height);
      return 1;
    }
    const ImageDifference raw = gs::render::compareImages(ours, reference, tolerance);
    const ImageDifference masked = maskedDifference(ours, reference, tolerance);
    const double fgOurs = foregroundFraction(ours);
    const double fgReference = foregroundFraction(reference);
    if (markdown) {
      std::printf("%.1f | %.1f | %s | %.1f | %s | %.1f | %.1f\n", 100.0 * raw.fractionDiffering,
                  raw.meanAbsolute, formatPsnr(raw.psnr).c_str(), 100.0 * masked.fractionDiffering,
                  formatPsnr(masked.psnr).c_str(), 100.0 * fgOurs, 100.0 * fgReference);
    } else {
      std::printf(
          "differ=%.4f meanAbs=%.2f psnr=%s masked_differ=%.4f masked_meanAbs=%.2f "
          "masked_psnr=%s fg_ours=%.4f fg_reference=%.4f\n",
          raw.fractionDiffering, raw.meanAbsolute, formatPsnr(raw.psnr).c_str(),
          masked.fractionDiffering, masked.meanAbsolute, formatPsnr(masked.psnr).c_str(), fgOurs,
          fgReference);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_png: %s\n", e.what());
    return 1;
  }
  return 0;
}
