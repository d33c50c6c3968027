// Splat pass throughput on the headless path (OSMesa): splats per second at 1, 4 and 16
// million vectors, and the frame time of the depth sort alone.
//
//   bench_splats [WxH]      (default 512x512)
#include <glad/gl.h>

#include <chrono>
#include <cstdio>
#include <random>

#include "render/context.hpp"
#include "render/splat_renderer.hpp"

using namespace gs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  int width = 512, height = 512;
  if (argc > 1 && std::sscanf(argv[1], "%dx%d", &width, &height) != 2) {
    std::fprintf(stderr, "usage: bench_splats [WxH]\n");
    return 2;
  }
  auto context = render::createOffscreenContext(width, height);
  GLint maxTexels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  std::printf("%s; %dx%d; GL_MAX_TEXTURE_BUFFER_SIZE %d texels\n", glGetString(GL_RENDERER), width,
              height, maxTexels);
  render::Camera camera;
  camera.position = {0.0f, 0.0f, 3.0f};
  camera.nearClip = 0.5f;
  camera.farClip = 10.0f;
  const render::SplatLight lights[] = {{glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  for (std::size_t millions : {1, 4, 16}) {
    const std::size_t n = millions * 1000000;
    if (2 * n > static_cast<std::size_t>(maxTexels)) {
      std::printf("%2zu M: skipped (more than the texture buffer holds)\n", millions);
      continue;
    }
    render::SplatSet set;
    set.vectors.resize(n);
    std::mt19937 rng(3);
    std::normal_distribution<float> g(0.0f, 1.0f);
    // A sphere shell, each splat about as large as its share of the surface.
    const float area = 4.0f * 3.14159265f / static_cast<float>(n);
    for (auto& v : set.vectors) {
      const glm::vec3 d = glm::normalize(glm::vec3(g(rng), g(rng), g(rng)));
      v = {d, area, d, 0xffc0c0c0u};
    }
    set.computeBounds();
    render::SplatRenderer renderer;
    double sortSeconds = 0.0, frameSeconds = 1e9;
    for (int frame = 0; frame < 4; ++frame) {
      // Move the camera a little every frame so each frame sorts again.
      camera.position.x = 0.01f * static_cast<float>(frame);
      glViewport(0, 0, width, height);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      const auto t0 = Clock::now();
      renderer.draw(set, n, glm::mat4(1.0f), camera, float(width) / float(height), lights);
      glFinish();
      const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
      if (frame == 0) continue;  // upload
      frameSeconds = std::min(frameSeconds, seconds);
      sortSeconds = renderer.statistics().sortSeconds;
    }
    std::printf("%2zu M splats: frame %.3f s (%.1f M splats/s), of which the depth sort %.3f s\n",
                millions, frameSeconds, static_cast<double>(n) / frameSeconds / 1e6, sortSeconds);
  }
  return 0;
}
