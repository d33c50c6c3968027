// Several viewports in one image (--layout): each shows its own world at its own level of
// detail, exactly as a single-viewport snapshot of that world would, and a stream shown
// twice is fetched once.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/layout.hpp"
#include "http/nginx_server.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using gs::test::runGhostspace;

namespace {

fs::path outDir() {
  const fs::path d = fs::path(GS_BINARY_DIR) / "layout-actual";
  fs::create_directories(d);
  return d;
}

/// The w x h block of `image` whose top-left corner is (x, y) (image rows top first).
gs::render::Image crop(const gs::render::Image& image, int x, int y, int w, int h) {
  gs::render::Image out(w, h);
  for (int row = 0; row < h; ++row)
    std::copy_n(image.rgba.begin() + ((static_cast<std::ptrdiff_t>(y) + row) * image.width + x) * 4,
                w * 4, out.rgba.begin() + static_cast<std::ptrdiff_t>(row) * w * 4);
  return out;
}

double differing(const gs::render::Image& a, const gs::render::Image& b) {
  return gs::render::compareImages(a, b, 2).fractionDiffering;
}

}  // namespace

TEST_CASE("layout rectangles tile the framebuffer", "[app][layout]") {
  using gs::app::Layout;
  using gs::app::layoutCells;
  using gs::app::layoutFromName;
  using gs::app::layoutRect;
  CHECK(layoutCells(*layoutFromName("1x1")) == 1);
  CHECK(layoutCells(*layoutFromName("2x1")) == 2);
  CHECK(layoutCells(*layoutFromName("2x2")) == 4);
  CHECK_FALSE(layoutFromName("3x3"));
  for (const auto& info : gs::app::kLayouts) CHECK(layoutFromName(info.name) == info.layout);
  const auto left = layoutRect(Layout::sideBySide, 0, 641, 480),
             right = layoutRect(Layout::sideBySide, 1, 641, 480);
  CHECK((left.x == 0 && left.width == 320 && left.y == 0 && left.height == 480));
  CHECK((right.x == 320 && right.width == 321));
  // 2x2: index 0 is the top left, so it has the highest y (lower-left origin).
  const auto topLeft = layoutRect(Layout::quad, 0, 640, 481),
             bottomRight = layoutRect(Layout::quad, 3, 640, 481);
  CHECK((topLeft.x == 0 && topLeft.y == 241 && topLeft.height == 240));
  CHECK((bottomRight.x == 320 && bottomRight.y == 0 && bottomRight.height == 241));
}

TEST_CASE("two worlds side by side at their own levels of detail", "[app][layout]") {
  const fs::path welcome = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  const fs::path qnv = outDir() / "sphere.qnv";
  REQUIRE(runGhostspace({"encode", (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string(),
                         "-o", qnv.string(), "--no-progress"})
              .exitCode == 0);
  const fs::path both = outDir() / "both.png", a = outDir() / "a.png", b = outDir() / "b.png";
  auto r = runGhostspace({"--snapshot", both.string(), "--size", "320x120", "--layout", "2x1",
                          "--lod", "1,0.2", "--no-progress", welcome.string(), qnv.string()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  REQUIRE(runGhostspace(
              {"--snapshot", a.string(), "--size", "160x120", "--no-progress", welcome.string()})
              .exitCode == 0);
  REQUIRE(runGhostspace({"--snapshot", b.string(), "--size", "160x120", "--lod", "0.2",
                         "--no-progress", qnv.string()})
              .exitCode == 0);
  const auto image = gs::render::readPng(both.string());
  CHECK(differing(crop(image, 0, 0, 160, 120), gs::render::readPng(a.string())) == 0.0);
  CHECK(differing(crop(image, 160, 0, 160, 120), gs::render::readPng(b.string())) == 0.0);
  // The other level of detail looks different: the viewports are really independent.
  const fs::path full = outDir() / "b_full.png";
  REQUIRE(runGhostspace(
              {"--snapshot", full.string(), "--size", "160x120", "--no-progress", qnv.string()})
              .exitCode == 0);
  CHECK(differing(crop(image, 160, 0, 160, 120), gs::render::readPng(full.string())) > 0.01);
}

TEST_CASE("one stream in two viewports is fetched once", "[app][layout][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  const fs::path qnv = outDir() / "sphere2.qnv";
  REQUIRE(runGhostspace({"encode", (gs::test::sourceDir() / "assets/volumes/sphere.nrrd").string(),
                         "-o", qnv.string(), "--no-progress"})
              .exitCode == 0);
  const std::string bytes = gs::test::readBytes(qnv);
  nginx.writeFile("s.qnv", bytes);
  const fs::path out = outDir() / "shared.png";
  const auto r = runGhostspace({"--snapshot", out.string(), "--size", "200x100", "--layout", "2x1",
                                "--lod", "0.3,1", "--no-progress", nginx.url("/s.qnv")});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(gs::test::NginxServer::bodyBytes(nginx.accessLog(1)) == bytes.size());
  // Bad layouts and too many inputs are usage errors.
  CHECK(runGhostspace({"--snapshot", out.string(), "--layout", "3x3", qnv.string()}).exitCode == 2);
  CHECK(runGhostspace({"--snapshot", out.string(), qnv.string(), qnv.string()}).exitCode == 2);
  for (const char* bad : {"0", "1.5", "0.1,x", "0.1,"})
    CHECK(runGhostspace({"--snapshot", out.string(), "--lod", bad, qnv.string()}).exitCode == 2);
}
