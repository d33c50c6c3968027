// compare_reference: renders the castle worlds of the corpus at 1600x900 and compares each
// with castle-model-viewer's reference rendering (X.wrl_screenshot.png beside X.wrl).
//   compare_reference [--out DIR] [CASTLE_DIR] [WORLD.wrl...]
// CASTLE_DIR defaults to ../shared/corpus/vrml/castle (relative to the working directory);
// without WORLDs every .wrl below CASTLE_DIR that has a screenshot is compared. Three
// variants per world:
//   snap   exactly as `ghostspace --snapshot`: the bound Viewpoint, or the VRML97 default
//          viewpoint (0 0 10) when there is none, clip planes fitted to the scene;
//   fit    SceneRenderer::initialCamera: the same when the world has a Viewpoint, else the
//          whole scene framed tightly (what the window does);
//   castle the same when the world has a Viewpoint, else castle's own placement for a world
//          without one (scene::wholeSceneCamera: CameraViewpointForWholeScene in
//          castle-engine's CastleCameras, looking along -Z from the box centre's x, y at
//          z = box max z + 2 * the average of the box's three sizes).
// Each variant is compared with the reference by render::compareImages (tolerance 16), and
// "background-masked": pixels where the reference shows its corner colour (castle's
// background) and ours shows our corner colour (our background) count as equal. Also
// printed: the fraction of foreground (non-background) pixels in the reference and in ours.
// --out DIR writes our images as DIR/NAME_{snap,fit,castle}.png (NAME: the
// world's path below CASTLE_DIR with '/' turned into '__').
#include "encodings/parser.hpp"
#include "image_metrics.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using gs::render::Image;
using gs::render::ImageDifference;

namespace {

using gs::bench::foregroundFraction;
using gs::bench::formatPsnr;
using gs::bench::maskedDifference;

constexpr int kWidth = 1600, kHeight = 900, kTolerance = 16;

struct VariantResult {
  ImageDifference raw, masked;
  double foreground = 0.0;  // fraction of our pixels that differ from our corner colour
};

struct WorldResult {
  std::string name;
  bool hasViewpoint = false;
  std::size_t diagnostics = 0;
  double referenceForeground = 0.0;
  VariantResult variants[3];  // snap, fit, castle
};

constexpr const char* kVariantNames[3] = {"snap", "fit", "castle"};

VariantResult renderVariant(gs::render::SceneRenderer& renderer, const gs::scene::Camera& camera,
                            const Image& reference, const std::string& outPath) {
  renderer.draw(camera, 0, 0, kWidth, kHeight);
  const Image ours = gs::render::readPixels(0, 0, kWidth, kHeight);
  if (!outPath.empty()) gs::render::writePng(outPath, ours);
  VariantResult r;
  r.raw = gs::render::compareImages(ours, reference, kTolerance);
  r.masked = maskedDifference(ours, reference, kTolerance);
  r.foreground = foregroundFraction(ours);
  return r;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void printSummary(const char* label, const std::vector<double>& values) {
  if (values.empty()) return;
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  std::printf("| %s | %.3f | %.3f | %.3f |\n", label, median(values), *lo, *hi);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string outDir;
    std::vector<std::string> positional;
    for (int i = 1; i < argc; ++i) {
      if (std::strcmp(argv[i], "--out") == 0 && i + 1 < argc) {
        outDir = argv[++i];
      } else if (std::strcmp(argv[i], "--help") == 0) {
        std::printf("usage: %s [--out DIR] [CASTLE_DIR] [WORLD.wrl...]\n", argv[0]);
        return 0;
      } else {
        positional.emplace_back(argv[i]);
      }
    }
    fs::path castleDir = "../shared/corpus/vrml/castle";
    if (!positional.empty() && fs::is_directory(positional.front())) {
      castleDir = positional.front();
      positional.erase(positional.begin());
    }
    std::vector<fs::path> worlds;
    for (const auto& p : positional) worlds.push_back(fs::exists(p) ? fs::path(p) : castleDir / p);
    if (worlds.empty()) {
      if (!fs::is_directory(castleDir)) {
        std::fprintf(stderr, "compare_reference: no folder %s (the corpus is absent)\n",
                     castleDir.c_str());
        return 1;
      }
      for (const auto& entry : fs::recursive_directory_iterator(castleDir))
        if (entry.is_regular_file() && entry.path().extension() == ".wrl")
          worlds.push_back(entry.path());
      std::sort(worlds.begin(), worlds.end());
    }
    if (!outDir.empty()) fs::create_directories(outDir);

    // One context for all worlds; each SceneRenderer is destroyed while it is current.
    auto context = gs::render::createOffscreenContext(kWidth, kHeight);
    std::vector<WorldResult> results;
    for (const auto& world : worlds) {
      const fs::path shot = world.string() + "_screenshot.png";
      if (!fs::exists(shot)) {
        std::fprintf(stderr, "skipped (no reference): %s\n", world.c_str());
        continue;
      }
      const Image reference = gs::render::readPng(shot.string());
      if (reference.width != kWidth || reference.height != kHeight) {
        std::fprintf(stderr, "skipped (reference is %dx%d): %s\n", reference.width,
                     reference.height, world.c_str());
        continue;
      }
      WorldResult r;
      std::error_code ec;
      const fs::path relative = fs::relative(world, castleDir, ec);
      r.name =
          ec || relative.empty() || *relative.begin() == ".." ? world.string() : relative.string();
      auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile(world.string()));
      context->makeCurrent();
      {
        gs::render::SceneRenderer renderer(scene);
        r.hasViewpoint = !renderer.viewpoints().empty();
        std::string base;
        if (!outDir.empty()) {
          std::string flat = r.name;
          for (std::size_t at; (at = flat.find('/')) != std::string::npos;)
            flat.replace(at, 1, "__");
          base = (fs::path(outDir) / flat).string();
        }
        const float aspect = float(kWidth) / float(kHeight);
        gs::scene::Camera cameras[3] = {renderer.boundViewpointCamera(),
                                        renderer.initialCamera(aspect),
                                        renderer.boundViewpointCamera()};
        gs::scene::fitClipPlanes(cameras[0], renderer.bounds(), renderer.navigation().nearClip());
        if (!r.hasViewpoint)
          cameras[2] = gs::scene::wholeSceneCamera(renderer.bounds(), gs::scene::Camera{});
        for (int v = 0; v < 3; ++v)
          r.variants[v] = renderVariant(renderer, cameras[v], reference,
                                        base.empty() ? "" : base + "_" + kVariantNames[v] + ".png");
        r.diagnostics = scene->diagnostics.items.size() + renderer.diagnostics().items.size();
      }
      r.referenceForeground = foregroundFraction(reference);
      std::fprintf(stderr, "%s done\n", r.name.c_str());
      results.push_back(r);
    }

    std::printf("| world | VP | diag | fg ref");
    for (const char* name : kVariantNames)
      std::printf(" | %s: fg | differ | meanAbs | PSNR | masked", name);
    std::printf(" |\n|---|---|--:|--:");
    for (int v = 0; v < 3; ++v) std::printf("|--:|--:|--:|--:|--:");
    std::printf("|\n");
    for (const auto& r : results) {
      std::printf("| %s | %s | %zu | %.3f", r.name.c_str(), r.hasViewpoint ? "yes" : "no",
                  r.diagnostics, r.referenceForeground);
      for (const VariantResult& v : r.variants)
        std::printf(" | %.3f | %.3f | %.1f | %s | %.3f", v.foreground, v.raw.fractionDiffering,
                    v.raw.meanAbsolute, formatPsnr(v.raw.psnr).c_str(), v.masked.fractionDiffering);
      std::printf(" |\n");
    }

    // Median and range of each metric over all compared worlds (PSNR: finite values only),
    // over all worlds and over those without a Viewpoint (where the variants differ).
    for (int subset = 0; subset < 2; ++subset) {
      std::vector<double> metrics[3][5];
      std::size_t count = 0;
      for (const auto& r : results) {
        if (subset == 1 && r.hasViewpoint) continue;
        ++count;
        for (int v = 0; v < 3; ++v) {
          const VariantResult& x = r.variants[v];
          metrics[v][0].push_back(x.raw.fractionDiffering);
          metrics[v][1].push_back(x.raw.meanAbsolute);
          if (std::isfinite(x.raw.psnr)) metrics[v][2].push_back(x.raw.psnr);
          metrics[v][3].push_back(x.masked.fractionDiffering);
          if (std::isfinite(x.masked.psnr)) metrics[v][4].push_back(x.masked.psnr);
        }
      }
      std::printf("\n%s: %zu worlds\n\n| metric | median | min | max |\n|---|--:|--:|--:|\n",
                  subset == 0 ? "all" : "without a Viewpoint", count);
      const char* labels[5] = {"differ", "meanAbs", "PSNR", "masked differ", "masked PSNR"};
      for (int v = 0; v < 3; ++v)
        for (int k = 0; k < 5; ++k)
          printSummary((std::string(kVariantNames[v]) + " " + labels[k]).c_str(), metrics[v][k]);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "compare_reference: %s\n", e.what());
    return 1;
  }
}
