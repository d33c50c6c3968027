// Splat pass throughput on the headless path (OSMesa), the three SplatPaths (geometry: GL with
// the CPU's sort; gpu: GL with the compute-shader sort; cpu) in one run:
// M splats/s of a whole frame (depth sort, upload of the order, draw, glFinish; the
// framebuffer's clear is finished before the clock starts: it is the world's, not the
// splat pass's, and llvmpipe would otherwise do it inside the timed glFinish) for
// synthetic sphere shells of a few sizes and for .qnv files given on the command line
// (e.g. the bunny and CThead's top 9.1%, docs/rendering.md), each seen whole by a fitted
// camera. Each figure is the best of FRAMES frames (the camera moves a little every
// frame, so each frame sorts again); "cpu" is the process's CPU time per frame (all
// llvmpipe threads and the cpu path's workers), less sensitive to other work on a shared
// machine than the wall time.
//
// With --distances, each Gaussian scene is also seen through its level-of-detail tree
// (splats/lod_tree.hpp) from D box diagonals away (the fitted camera moved back along its
// view): the cut's size (splats drawn, and their share of the scene) and the M splats/s of
// the cut, best of FRAMES frames, each frame a new view (a new cut, assembled and sorted).
// Every figure is of splats depth-tested against the framebuffer's depth (a capture in a
// world of shapes: the cpu path reads that depth back); the cpu path's cuts also
// "alone", as the app draws a world of splats alone (no depth to read: SplatBlend::
// frontToBack, render/src/scene_splats.hpp).
//
// Each path's last frame is kept: the geometry and gpu paths' PSNR against the cpu path's
// picture is printed (the same model drawn three ways: about 40 dB or more, docs/splats.md),
// and with --pictures DIR each is written as DIR/NAME_PATH.png.
//
//   bench_splats [WxH] [--millions 1,4] [--frames N] [--path P] [--distances 1.5,3,12]
//                [--cuts-only] [--pictures DIR] [FILE.qnv|SCENE ...]
//   (SCENE: a Gaussian splatting scene, docs/splats.md: .ply, .spz, .splat, .sog, .glb ...)
//   (default 512x512; --path geometry|gpu|cpu measures only that path)
#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <glm/geometric.hpp>

#include "base/file.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_renderer.hpp"
#include "render/splat_source.hpp"
#include "splats/lod_tree.hpp"
#include "splats/readers.hpp"

using namespace gs;
using Clock = std::chrono::steady_clock;

namespace {

double processSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

std::shared_ptr<render::SplatSet> shell(std::size_t n) {
  auto set = std::make_shared<render::SplatSet>();
  set->vectors.resize(n);
  std::mt19937 rng(3);
  std::normal_distribution<float> g(0.0f, 1.0f);
  // A sphere shell, each splat about as large as its share of the surface.
  const float area = 4.0f * 3.14159265f / static_cast<float>(n);
  for (auto& v : set->vectors) {
    const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
    v = {d, area, d, 0xffc0c0c0u};
  }
  set->computeBounds();
  return set;
}

struct Figure {
  double wall = 1e9, cpu = 1e9, sort = 0.0;
  render::SplatPath drew = render::SplatPath::geometry;
  std::size_t drawn = 0;  // splats drawn in the best frame
  render::Image picture;  // the last frame
};

// The best of `frames` frames of `set` seen from `camera`, moved by `step` along x each
// frame, back to the start every fourth (so each frame sorts, and cuts a tree, again).
Figure measureFrom(const render::SplatSet& set, render::SplatPath path, int width, int height,
                   int frames, scene::Camera camera, float step,
                   render::SplatBlend blend = render::SplatBlend::backToFront) {
  const float aspect = float(width) / float(height);
  const glm::vec3 start = camera.position;
  const render::SplatLight lights[] = {{camera.forward(), glm::vec3(1.0f)}};
  render::SplatRenderer renderer;
  renderer.setPath(path);
  Figure f;
  for (int frame = 0; frame <= frames; ++frame) {
    // Four positions in turn: each frame differs from the last, and many frames stay near.
    camera.position = start + glm::vec3(step * static_cast<float>(frame % 4), 0.0f, 0.0f);
    glViewport(0, 0, width, height);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glFinish();  // the clear is the world's, not the splat pass's
    const auto t0 = Clock::now();
    const double c0 = processSeconds();
    renderer.draw(set, set.size(), glm::mat4(1.0f), camera, aspect, lights, blend);
    glFinish();
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const double cpu = processSeconds() - c0;
    if (frame == 0) continue;  // upload and shader compilation
    if (seconds < f.wall) {
      f.sort = renderer.statistics().sortSeconds;
      f.drawn = renderer.statistics().splats;
    }
    f.wall = std::min(f.wall, seconds);
    f.cpu = std::min(f.cpu, cpu);
    f.drew = renderer.statistics().path;
  }
  f.picture = render::readPixels(0, 0, width, height);
  return f;
}

// The whole set seen by the fitted camera.
Figure measure(const render::SplatSet& set, render::SplatPath path, int width, int height,
               int frames) {
  scene::Camera direction;
  const scene::Camera camera =
      scene::fitCamera(set.bounds, float(width) / float(height), direction);
  return measureFrom(set, path, width, height, frames, camera,
                     0.003f * glm::length(set.bounds.size()));
}

std::string only;      // --path: measure only that path
std::string pictures;  // --pictures: where each path's last frame is written

// PSNR (dB) of a's RGB against b's, over every pixel; 99 when they are equal.
double psnr(const render::Image& a, const render::Image& b) {
  if (a.rgba.size() != b.rgba.size() || a.rgba.empty()) return 0.0;
  double squared = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(a.rgba[i]) - double(b.rgba[i]);
    squared += d * d;
  }
  const double mse = squared / (double(a.rgba.size()) * 0.75);
  return mse <= 0.0 ? 99.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}
std::vector<double> distances;  // --distances: box diagonals for the cut figures
bool cutsOnly = false;          // --cuts-only: with --distances, only the cut figures

// The cut figures of a Gaussian scene with its tree (see the top of this file).
void reportCuts(const char* name, const render::SplatSet& set, int width, int height, int frames) {
  const float aspect = float(width) / float(height);
  const float diagonal = glm::length(set.bounds.size());
  const glm::vec3 centre = (set.bounds.min + set.bounds.max) * 0.5f;
  scene::Camera direction;
  const scene::Camera fitted = scene::fitCamera(set.bounds, aspect, direction);
  const glm::vec3 back = -fitted.forward();
  const render::SplatPath paths[3] = {render::SplatPath::geometry, render::SplatPath::gpu,
                                      render::SplatPath::cpu};
  for (const render::SplatPath path : paths) {
    if (!only.empty() && only != render::splatPathName(path)) continue;
    for (const double d : distances) {
      scene::Camera camera = fitted;
      camera.farClip = std::max(fitted.farClip, static_cast<float>(d + 2.0) * diagonal);
      camera.position = centre + back * (static_cast<float>(d) * diagonal);
      const Figure f = measureFrom(set, path, width, height, frames, camera,
                                   0.003f * diagonal * static_cast<float>(d));
      const std::size_t drawn = f.drawn;
      const double best = f.wall;
      std::printf(
          "%-14s %-8s %5.1f diagonals: cut %9zu splats (%6.2f%%)  frame %7.4f s  %6.2f M "
          "splats/s%s%s",
          name, render::splatPathName(path), d, drawn,
          100.0 * static_cast<double>(drawn) / static_cast<double>(set.size()), best,
          static_cast<double>(drawn) / best / 1e6, f.drew == path ? "" : ", drawn by ",
          f.drew == path ? "" : render::splatPathName(f.drew));
      if (path == render::SplatPath::cpu) {
        // The capture alone, as the app draws a world of splats without shapes: nothing
        // can hide them, so the cpu path reads no depth back (SplatBlend::frontToBack).
        const Figure alone =
            measureFrom(set, path, width, height, frames, camera,
                        0.003f * diagonal * static_cast<float>(d), render::SplatBlend::frontToBack);
        std::printf("; alone %7.4f s  %6.2f M splats/s", alone.wall,
                    static_cast<double>(alone.drawn) / alone.wall / 1e6);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
  }
}

void report(const char* name, const render::SplatSet& set, int width, int height, int frames) {
  const double n = static_cast<double>(set.size());
  constexpr int kPaths = 3;
  Figure figures[kPaths];
  const render::SplatPath paths[kPaths] = {render::SplatPath::geometry, render::SplatPath::gpu,
                                           render::SplatPath::cpu};
  for (int i = 0; i < kPaths; ++i) {
    if (!only.empty() && only != render::splatPathName(paths[i])) continue;  // --path
    figures[i] = measure(set, paths[i], width, height, frames);
  }
  for (int i = 0; i < kPaths; ++i) {
    if (!only.empty() && only != render::splatPathName(paths[i])) continue;
    const Figure& f = figures[i];
    std::printf(
        "%-14s %9.0f splats  %-8s frame %7.3f s  %5.2f M splats/s  (cpu %.3f s, "
        "sort %.3f s)%s%s\n",
        name, n, render::splatPathName(paths[i]), f.wall, n / f.wall / 1e6, f.cpu, f.sort,
        f.drew == paths[i] ? "" : ", drawn by ",
        f.drew == paths[i] ? "" : render::splatPathName(f.drew));
  }
  for (int i = 0; i < kPaths && !pictures.empty(); ++i) {
    if (figures[i].picture.empty()) continue;
    std::string file = pictures + "/" + name + "_" + render::splatPathName(paths[i]) + ".png";
    std::replace(file.begin() + static_cast<std::ptrdiff_t>(pictures.size()) + 1, file.end(), ' ',
                 '_');
    render::writePng(file, figures[i].picture);
  }
  if (!only.empty()) return;
  std::printf("%-14s PSNR against the cpu path's picture: geometry %.1f dB, gpu %.1f dB\n", name,
              psnr(figures[0].picture, figures[2].picture),
              psnr(figures[1].picture, figures[2].picture));
  std::printf(
      "%-14s cpu / geometry: %.2fx (wall), %.2fx (cpu); gpu sort / geometry: %.2fx (wall)\n", name,
      figures[0].wall / figures[2].wall, figures[0].cpu / figures[2].cpu,
      figures[0].wall / figures[1].wall);
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  int width = 512, height = 512, frames = 3;
  std::vector<double> millions = {1, 4};
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--path" && i + 1 < argc) {
      only = argv[++i];
    } else if (a == "--pictures" && i + 1 < argc) {
      pictures = argv[++i];
    } else if (a == "--distances" && i + 1 < argc) {
      for (char* p = argv[++i]; *p != '\0';) {
        char* end = nullptr;
        distances.push_back(std::strtod(p, &end));
        if (end == p) break;
        p = *end == ',' ? end + 1 : end;
      }
    } else if (a == "--cuts-only") {
      cutsOnly = true;
    } else if (a == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--millions" && i + 1 < argc) {
      millions.clear();
      for (char* p = argv[++i]; *p != '\0';) {
        char* end = nullptr;
        millions.push_back(std::strtod(p, &end));
        if (end == p) break;
        p = *end == ',' ? end + 1 : end;
      }
    } else if (a.find(".qnv") == std::string::npos &&
               std::sscanf(a.c_str(), "%dx%d", &width, &height) == 2) {
      // the size
    } else if ((a.size() > 4 && a.substr(a.size() - 4) == ".qnv") ||
               std::filesystem::is_regular_file(a)) {  // a scene: readGaussians decides
      files.push_back(a);
    } else {
      std::fprintf(stderr,
                   "usage: bench_splats [WxH] [--millions 1,4] [--frames N] [--path P] "
                   "[--distances D,...] [--cuts-only] [--pictures DIR] [FILE.qnv|SCENE ...]\n");
      return 2;
    }
  }
  auto context = render::createOffscreenContext(width, height);
  double load[3] = {0, 0, 0};
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf %lf %lf", &load[0], &load[1], &load[2]) != 3) load[0] = -1;
    std::fclose(f);
  }
  std::printf(
      "%s, OpenGL %s; %dx%d; best of %d frames; %u hardware threads; load average %.2f %.2f "
      "%.2f\n",
      glGetString(GL_RENDERER), glGetString(GL_VERSION), width, height, frames,
      std::thread::hardware_concurrency(), load[0], load[1], load[2]);
  for (const std::string& file : files) {
    std::string error;
    std::shared_ptr<const render::SplatSet> set;
    if (file.size() > 4 && file.substr(file.size() - 4) == ".qnv") {
      set = render::loadQnvFile(file, error);
    } else {
      // A Gaussian splatting scene, in importance order.
      std::string bytes;
      if (gs::base::readFile(file, bytes, error, std::size_t{16} << 30)) {
        try {
          auto gaussians = std::make_shared<render::SplatSet>();
          gaussians->gaussians = std::make_shared<const gs::splats::GaussianCloud>(
              gs::splats::sortByImportance(gs::splats::readGaussians(bytes, file, nullptr)));
          gaussians->computeBounds();
          set = gaussians;
        } catch (const gs::splats::FormatError& e) {
          error = e.what();
        }
      }
    }
    if (!set) {
      std::fprintf(stderr, "%s\n", error.c_str());
      return 1;
    }
    const std::size_t slash = file.find_last_of('/');
    const std::string name = file.substr(slash == std::string::npos ? 0 : slash + 1);
    if (!cutsOnly || distances.empty()) report(name.c_str(), *set, width, height, frames);
    if (!distances.empty() && set->gaussians) {
      auto withTree = std::make_shared<render::SplatSet>();
      withTree->gaussians = set->gaussians;
      withTree->computeBounds();
      withTree->lodTree = std::make_shared<const gs::splats::LodTree>(
          gs::splats::buildLodTree(*withTree->gaussians));
      reportCuts(name.c_str(), *withTree, width, height, frames);
    }
  }
  for (const double m : millions) {
    if (!(m > 0.0)) continue;  // --millions 0: the scenes only
    const auto set = shell(static_cast<std::size_t>(m * 1e6));
    char name[32];
    std::snprintf(name, sizeof name, "shell %.2g M", m);
    report(name, *set, width, height, frames);
  }
  return 0;
}
