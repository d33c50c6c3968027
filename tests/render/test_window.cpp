// The GLFW window context and switching between it and an OSMesa context in one process
// (docs/architecture.md, "One renderer for window and snapshot": every GL call goes through the
// current context's loader). Needs a display: skipped without DISPLAY (run under xvfb-run to
// include it).
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "render_test_util.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>

using namespace gs::test;

namespace {
bool red(const gs::render::Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return p[0] > 250 && p[1] < 5 && p[2] < 5;
}
void drawRedBox(gs::render::GlContext& c) {
  auto shape = shapeWith(makeNode("TestBox"),
                         {{"emissiveColor", sfColor(1, 0, 0)}, {"diffuseColor", sfColor(0, 0, 0)}});
  gs::render::SceneRenderer r(makeScene({shape}), testRendererOptions());
  r.draw(r.boundViewpointCamera(), 0, 0, c.width(), c.height());
  glFinish();
}
}  // namespace

TEST_CASE("window and off-screen contexts draw in one process", "[render][window]") {
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || *display == '\0') {
    gs::test::missingFixture("no DISPLAY for a GLFW window (run the tests under xvfb-run)");
    return;
  }
  auto window = gs::render::createWindowContext("GhostSpace test", 64, 64);
  REQUIRE(window->glfwHandle() != nullptr);
  drawRedBox(*window);
  auto img = gs::render::readPixels(0, 0, window->width(), window->height());
  CHECK(red(img, img.width / 2, img.height / 2));
  const std::string windowRenderer = gs::render::glInfo().renderer;

  auto offscreen = gs::render::createOffscreenContext(48, 48);
  drawRedBox(*offscreen);
  img = gs::render::readPixels(0, 0, 48, 48);
  CHECK(red(img, 24, 24));

  // Back to the window: its functions are reloaded.
  window->makeCurrent();
  CHECK(gs::render::glInfo().renderer == windowRenderer);
  drawRedBox(*window);
  img = gs::render::readPixels(0, 0, window->width(), window->height());
  CHECK(red(img, img.width / 2, img.height / 2));
  window->swapBuffers();
}
