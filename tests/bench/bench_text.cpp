// Text figures (docs/text.md, "Measured"): a Text node of N characters (lines of 100)
// laid out and tessellated cold (empty glyph cache) and warm, and the first frame of it
// drawn off-screen at 300x300.
//
//   bench_text [characters]      (default 10000)
#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "scene/text_mesh.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string textWorld(int characters) {
  static const char* kWords[] = {"the ",  "quick ", "brown ", "fox ",   "jumps ",  "over ",
                                 "lazy ", "dog ",   "VRML ",  "glyph ", "shaping "};
  std::string w =
      "#VRML V2.0 utf8\nShape { appearance Appearance { material Material {} }\n"
      "geometry Text { fontStyle FontStyle { family \"SANS\" } string [\n";
  unsigned state = 1;
  for (int done = 0; done < characters;) {
    std::string line;
    while (static_cast<int>(line.size()) < 100) {
      state = state * 1103515245u + 12345u;
      line += kWords[(state >> 16) % 11];
    }
    line.resize(static_cast<std::size_t>(std::min(100, characters - done)));
    done += static_cast<int>(line.size());
    w += "\"" + line + "\"\n";
  }
  return w + "] } }\n";
}

}  // namespace

int main(int argc, char** argv) {
  const int characters = argc > 1 ? std::atoi(argv[1]) : 10000;
  auto scene =
      std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(textWorld(characters), "bench.wrl"));
  const gs::vrml::Node& text = *scene->rootNodes.at(0)->sfnode("geometry");

  auto t0 = Clock::now();
  const gs::vrml::Mesh cold = gs::scene::tessellateText(text);
  const double coldS = since(t0);
  t0 = Clock::now();
  const gs::vrml::Mesh warm = gs::scene::tessellateText(text);
  const double warmS = since(t0);
  std::printf("characters %d, glyph meshes cached %zu, triangles %zu, vertices %zu\n", characters,
              gs::scene::cachedGlyphMeshCount(), warm.triangleCount(), warm.positions.size());
  std::printf("layout + tessellation: cold %.1f ms, warm %.1f ms\n", coldS * 1e3, warmS * 1e3);
  (void)cold;

  auto fresh =
      std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(textWorld(characters), "bench.wrl"));
  auto context = gs::render::createOffscreenContext(300, 300);
  context->makeCurrent();
  t0 = Clock::now();
  gs::render::SceneRenderer renderer(fresh);
  renderer.draw(renderer.initialCamera(1.0f), 0, 0, 300, 300);
  const gs::render::Image image = gs::render::readPixels(0, 0, 300, 300);  // waits for the GPU
  (void)image;
  std::printf("first frame (warm glyph cache, 300x300, llvmpipe): %.1f ms\n", since(t0) * 1e3);
  return 0;
}
