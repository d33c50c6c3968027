// bench_render: renders a VRML97 world off-screen from its bound Viewpoint and prints how
// long the first frame (loading, tessellation, upload) and the following frames take.
//   bench_render WORLD.wrl [OUT.png] [WIDTHxHEIGHT] [FRAMES] [--fit] [--generic]
// The camera is SceneRenderer::initialCamera; --fit frames the whole scene instead.
// After the first frame, 10 untimed warm-up frames, then FRAMES timed ones (default 10).
// --generic draws every frame with the one generic surface program (no shader variants:
// SceneRendererOptions::shaderVariants false), the "before" of issue 22's variants.
#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

constexpr int kWarmUpFrames = 10;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: %s WORLD.wrl [OUT.png] [WIDTHxHEIGHT] [FRAMES] [--fit] [--generic]\n",
                 argv[0]);
    return 2;
  }
  try {
    using Clock = std::chrono::steady_clock;
    const std::string world = argv[1];
    std::string out;
    int width = 300, height = 300, frames = 10;
    bool fit = false, generic = false;
    int positional = 0;
    for (int i = 2; i < argc; ++i) {
      if (std::strcmp(argv[i], "--fit") == 0) {
        fit = true;
        continue;
      }
      if (std::strcmp(argv[i], "--generic") == 0) {
        generic = true;
        continue;
      }
      ++positional;
      if (positional == 1) out = argv[i];
      if (positional == 2) std::sscanf(argv[i], "%dx%d", &width, &height);
      if (positional == 3) frames = std::atoi(argv[i]);
    }
    const auto t0 = Clock::now();
    auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile(world));
    for (const auto& d : scene->diagnostics.items) std::fprintf(stderr, "%s\n", d.format().c_str());
    const auto t1 = Clock::now();
    auto context = gs::render::createOffscreenContext(width, height);
    gs::render::SceneRendererOptions options;
    options.shaderVariants = !generic;
    gs::render::SceneRenderer renderer(scene, std::move(options));
    gs::scene::Camera camera = renderer.initialCamera(float(width) / float(height));
    if (fit) camera = renderer.fitToScene(float(width) / float(height), camera);
    const auto t2 = Clock::now();
    renderer.draw(camera, 0, 0, width, height);
    glFinish();
    const auto t3 = Clock::now();
    // Untimed warm-up: the shader variants are compiled in frames 2-9 (a few per frame), and
    // llvmpipe compiles each program's code for the pipeline state at its first draw.
    for (int f = 0; f < kWarmUpFrames; ++f) renderer.draw(camera, 0, 0, width, height);
    glFinish();
    const auto t35 = Clock::now();
    for (int f = 0; f < frames; ++f) renderer.draw(camera, 0, 0, width, height);
    glFinish();
    const auto t4 = Clock::now();
    for (const auto& d : renderer.diagnostics().items)
      std::fprintf(stderr, "%s\n", d.format().c_str());
    auto ms = [](auto a, auto b) {
      return std::chrono::duration<double, std::milli>(b - a).count();
    };
    const auto& b = renderer.bounds();
    std::printf(
        "%s: parse %.1f ms, setup %.1f ms, first frame %.1f ms, warm-up %.0f ms, %.2f ms/frame "
        "over %d, "
        "%zu shapes, %zu triangles, %zu shader variants, bounds (%g %g %g)-(%g %g %g)\n",
        world.c_str(), ms(t0, t1), ms(t1, t2), ms(t2, t3), ms(t3, t35),
        frames > 0 ? ms(t35, t4) / frames : 0.0, frames, renderer.statistics().shapes,
        renderer.trianglesDrawn(), renderer.statistics().shaderVariants, b.min.x, b.min.y, b.min.z,
        b.max.x, b.max.y, b.max.z);
    if (!out.empty()) gs::render::writePng(out, gs::render::readPixels(0, 0, width, height));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_render: %s\n", e.what());
    return 1;
  }
}
