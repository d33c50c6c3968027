// The Gaussian splat paths (docs/splats.md): every encoding of one scene draws the same
// picture; the cpu and GL paths agree; the level-of-detail tree's cut of a far view draws
// few splats and the picture of all of them (docs/splats-lod.md).
#include <catch2/catch.hpp>

#include <glad/gl.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <glm/gtc/quaternion.hpp>

#include "base/file.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_renderer.hpp"
#include "splats/lod_tree.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace gs::render;

namespace {

constexpr int kGaussianSize = 160;

std::shared_ptr<SplatSet> gaussianScene(const fs::path& file, bool tree) {
  std::string bytes, error;
  REQUIRE(gs::base::readFile(file.string(), bytes, error, std::size_t{1} << 30));
  const fs::path folder = file.parent_path();
  const gs::splats::SideFileReader side = [&](const std::string& name, std::string& out,
                                              std::string& why) {
    return gs::base::readFile((folder / name).string(), out, why, std::size_t{1} << 30);
  };
  auto set = std::make_shared<SplatSet>();
  set->gaussians = std::make_shared<const gs::splats::GaussianCloud>(
      gs::splats::sortByImportance(gs::splats::readGaussians(bytes, file.string(), side)));
  if (tree)
    set->lodTree =
        std::make_shared<const gs::splats::LodTree>(gs::splats::buildLodTree(*set->gaussians));
  set->computeBounds();
  return set;
}

/// Looks at the set's centre from `distance` bounding-box diagonals along +Z.
gs::scene::Camera gaussianCamera(const SplatSet& set, float distance) {
  gs::scene::Camera cam;
  const glm::vec3 centre = set.bounds.center();
  const float diagonal = glm::length(set.bounds.size());
  cam.position = centre + glm::vec3(0.0f, 0.0f, distance * diagonal);
  cam.orientation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  cam.fieldOfView = 0.6f;
  cam.nearClip = 0.01f * diagonal;
  cam.farClip = (distance + 2.0f) * diagonal;
  return cam;
}

/// `set` drawn by `path` under a budget of `count` splats (default: all of them).
Image drawGaussians(const SplatSet& set, const gs::scene::Camera& cam, SplatPath path,
                    std::size_t* drawn = nullptr, std::size_t count = SIZE_MAX) {
  static auto context = createOffscreenContext(kGaussianSize, kGaussianSize);
  context->makeCurrent();
  SplatRenderer renderer;
  renderer.setPath(path);
  glViewport(0, 0, kGaussianSize, kGaussianSize);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, std::min(count, set.size()), glm::mat4(1.0f), cam, 1.0f, {});
  if (drawn) *drawn = renderer.statistics().splats;
  Image image = readPixels(0, 0, kGaussianSize, kGaussianSize);
  renderer.release();
  return image;
}

std::size_t litPixels(const Image& image) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    n += image.rgba[i] > 8 || image.rgba[i + 1] > 8 || image.rgba[i + 2] > 8;
  return n;
}

}  // namespace

TEST_CASE("every encoding of a Gaussian scene draws the picture of its .ply",
          "[render][splat][gaussian]") {
  const fs::path dir = gs::test::sourceDir() / "tests/data/splats";
  const auto ply = gaussianScene(dir / "bunny_small.ply", false);
  const gs::scene::Camera cam = gaussianCamera(*ply, 1.2f);
  const Image reference = drawGaussians(*ply, cam, SplatPath::cpu);
  REQUIRE(litPixels(reference) > 1000);  // the bunny fills a good part of the picture
  for (const char* name :
       {"bunny_small.compressed.ply", "bunny_small.spz", "bunny_small_v3.spz", "bunny_small.splat",
        "bunny_small.sog", "bunny_small_sog/meta.json", "bunny_small.glb"}) {
    SECTION(name) {
      const auto set = gaussianScene(dir / name, false);
      REQUIRE(set->size() == ply->size());
      const ImageDifference d = compareImages(drawGaussians(*set, cam, SplatPath::cpu), reference);
      WARN(name << ": PSNR " << d.psnr << " dB, " << d.fractionDiffering * 100
                << "% of pixels more than 16 levels off");
      // Quantised encodings (8-bit colours, 11-bit positions ...) move pixels a little.
      CHECK(d.fractionDiffering <= 0.02);
      CHECK(d.psnr >= 30.0);
    }
  }
}

TEST_CASE("the GL path draws the cpu path's Gaussians", "[render][splat][gaussian]") {
  const auto set =
      gaussianScene(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply", false);
  const gs::scene::Camera cam = gaussianCamera(*set, 1.2f);
  const ImageDifference d = compareImages(drawGaussians(*set, cam, SplatPath::geometry),
                                          drawGaussians(*set, cam, SplatPath::cpu));
  WARN("GL against cpu: PSNR " << d.psnr << " dB");
  // The GL paths blend into a half-float layer (render/src/splat_layer_gl.hpp): 57.6 dB
  // measured (59.3 with full floats); 52.4 dB when they blended into the 8-bit framebuffer.
  CHECK(d.fractionDiffering <= 0.001);
  CHECK(d.psnr >= 55.0);
}

TEST_CASE("a haze of faint Gaussians keeps its light on the GL paths",
          "[render][splat][gaussian]") {
  // Sixteen copies of the bunny's Gaussians, each made faint (opacity 0.012, three 8-bit
  // levels): drawn straight into an 8-bit framebuffer, dst = src + dst (1 - alpha) rounds
  // at each of the hundreds of steps a pixel sees, and the haze came out off by several
  // levels (32.7 dB, half the pixels more than 2 levels off); the half-float layer
  // (render/src/splat_layer_gl.hpp) composites it as the cpu path does (58.2 dB).
  const auto scene =
      gaussianScene(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply", false);
  auto cloud = std::make_shared<gs::splats::GaussianCloud>();
  cloud->setShDegree(scene->gaussians->shDegree);
  for (int copy = 0; copy < 16; ++copy)
    for (std::size_t i = 0; i < scene->gaussians->size(); ++i) cloud->append(*scene->gaussians, i);
  for (float& o : cloud->opacities) o = 0.012f;
  SplatSet haze;
  haze.gaussians = cloud;
  haze.computeBounds();
  const gs::scene::Camera cam = gaussianCamera(haze, 1.2f);
  const Image cpu = drawGaussians(haze, cam, SplatPath::cpu);
  REQUIRE(litPixels(cpu) > 1000);  // the haze shows
  for (const SplatPath path : {SplatPath::geometry, SplatPath::gpu}) {
    const ImageDifference d = compareImages(drawGaussians(haze, cam, path), cpu, 2);
    WARN(splatPathName(path) << " against cpu, a faint haze: PSNR " << d.psnr << " dB, "
                             << d.fractionDiffering * 100 << "% of pixels more than 2 levels off");
    CHECK(d.psnr >= 50.0);
    CHECK(d.fractionDiffering <= 0.001);
  }
}

TEST_CASE("the gpu and cpu paths draw a tree's cut by index as the geometry path draws it",
          "[render][splat][gaussian]") {
  // The geometry path draws the cut assembled into a cloud of its own; the gpu and cpu
  // paths draw it by index from one cloud of the tree's every node (originals, then the
  // merged Gaussians): the same splats, so the same picture.
  const auto tree =
      gaussianScene(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply", true);
  for (const float distance : {1.2f, 6.0f, 12.0f}) {
    const gs::scene::Camera cam = gaussianCamera(*tree, distance);
    std::size_t assembled = 0, gpu = 0, cpu = 0;
    const Image geometryImage = drawGaussians(*tree, cam, SplatPath::geometry, &assembled);
    const Image gpuImage = drawGaussians(*tree, cam, SplatPath::gpu, &gpu);
    const Image cpuImage = drawGaussians(*tree, cam, SplatPath::cpu, &cpu);
    INFO(distance << " diagonals: the cut draws " << assembled << " of " << tree->size());
    CHECK(gpu == assembled);
    CHECK(cpu == assembled);
    if (distance > 5.0f) CHECK(assembled < tree->size());  // merged Gaussians drawn
    if (distance > 10.0f) CHECK(assembled < tree->size() / 2);
    REQUIRE(litPixels(geometryImage) > 10);
    const ImageDifference g = compareImages(gpuImage, geometryImage);
    const ImageDifference c = compareImages(cpuImage, geometryImage);
    WARN(distance << " diagonals: gpu against geometry PSNR " << g.psnr << " dB, cpu " << c.psnr
                  << " dB");
    CHECK(g.fractionDiffering <= 0.002);
    CHECK(c.fractionDiffering <= 0.001);
    CHECK(c.psnr >= 55.0);  // 57.6-74 dB measured (the half-float layer; 8-bit: 52-69 dB)
  }
}

TEST_CASE("a far view draws a small cut of the tree that looks like every splat",
          "[render][splat][gaussian][corpus]") {
  if (!gs::test::haveCorpus("splat")) return;
  const fs::path file = gs::test::corpusDir() / "splat/cthead.spz";
  const auto all = gaussianScene(file, false);
  const auto tree = gaussianScene(file, true);
  for (const float distance : {3.0f, 12.0f}) {
    const gs::scene::Camera cam = gaussianCamera(*all, distance);
    std::size_t drawn = 0;
    const Image full = drawGaussians(*all, cam, SplatPath::cpu);
    const Image cut = drawGaussians(*tree, cam, SplatPath::cpu, &drawn);
    const ImageDifference d = compareImages(cut, full);
    const double share = double(drawn) / double(all->size());
    WARN("CThead at " << distance << " diagonals, " << kGaussianSize << " px: the cut draws "
                      << drawn << " of " << all->size() << " (" << share * 100 << "%), "
                      << d.fractionDiffering * 100 << "% of pixels differ, PSNR " << d.psnr);
    REQUIRE(litPixels(full) > 50);
    CHECK(d.fractionDiffering <= 0.02);  // within 2% of the pixels of the full picture
    if (distance >= 12.0f) CHECK(share <= 0.05);
  }
}

namespace {

std::shared_ptr<SplatSet> setOf(gs::splats::GaussianCloud cloud) {
  auto set = std::make_shared<SplatSet>();
  set->gaussians = std::make_shared<const gs::splats::GaussianCloud>(std::move(cloud));
  set->computeBounds();
  return set;
}

}  // namespace

TEST_CASE("a tree over a stream's prefix draws its cut and the splats after it, to the budget",
          "[render][splat][gaussian]") {
  // A progressive stream's tree covers the splats that had arrived when it was built; the
  // splats that came after are drawn whole beside the cut, by every path, until a tree over
  // them replaces it (session/streaming_session.hpp).
  const auto whole =
      gaussianScene(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply", false);
  const gs::splats::GaussianCloud& cloud = *whole->gaussians;
  const std::size_t prefix = cloud.size() / 2;
  gs::splats::GaussianCloud first;
  first.shDegree = cloud.shDegree;
  for (std::size_t i = 0; i < prefix; ++i) first.append(cloud, i);
  const auto prefixTree =
      std::make_shared<const gs::splats::LodTree>(gs::splats::buildLodTree(first));
  auto grown = std::make_shared<SplatSet>(*whole);
  grown->lodTree = prefixTree;
  auto prefixOnly = setOf(first);
  prefixOnly->lodTree = prefixTree;
  for (const float distance : {1.2f, 12.0f}) {
    const gs::scene::Camera cam = gaussianCamera(*whole, distance);
    std::size_t cutOnly = 0, geometry = 0, gpu = 0, cpu = 0;
    const Image full = drawGaussians(*whole, cam, SplatPath::cpu);
    const Image withoutTail = drawGaussians(*prefixOnly, cam, SplatPath::cpu, &cutOnly);
    const Image geometryImage = drawGaussians(*grown, cam, SplatPath::geometry, &geometry);
    const Image gpuImage = drawGaussians(*grown, cam, SplatPath::gpu, &gpu);
    const Image cpuImage = drawGaussians(*grown, cam, SplatPath::cpu, &cpu);
    INFO(distance << " diagonals: the prefix's cut draws " << cutOnly << ", with the rest " << cpu
                  << " of " << cloud.size());
    CHECK(cpu == cutOnly + (cloud.size() - prefix));
    CHECK(gpu == cpu);
    CHECK(geometry == cpu);
    CHECK(compareImages(gpuImage, geometryImage).fractionDiffering <= 0.002);
    CHECK(compareImages(cpuImage, geometryImage).fractionDiffering <= 0.002);
    if (distance < 2.0f) {
      // Near: the cut is the prefix's every splat, so the picture is the whole cloud's,
      // where the prefix alone misses half of it.
      CHECK(cutOnly == prefix);
      CHECK(compareImages(cpuImage, full).psnr >= 55.0);
      CHECK(compareImages(withoutTail, full).psnr < 45.0);
      // Under a budget, only the splats after the prefix that it reaches, as a prefix.
      for (const SplatPath path : {SplatPath::cpu, SplatPath::gpu, SplatPath::geometry}) {
        std::size_t budgeted = 0;
        drawGaussians(*grown, cam, path, &budgeted, prefix + 100);
        CHECK(budgeted == prefix + 100);
      }
    }
  }
}

TEST_CASE("a renderer that drew a prefix tree draws the splats that arrive after it",
          "[render][splat][gaussian]") {
  // The session's cloud grows in place while a tree covers its prefix: the cpu and gpu
  // paths append the new splats to the cloud of the tree's nodes they hold (holdTree)
  // instead of making it again. One renderer drawing the cloud before and after it grew
  // must give the picture a fresh renderer gives of the grown cloud.
  const auto whole =
      gaussianScene(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply", false);
  const gs::splats::GaussianCloud& all = *whole->gaussians;
  auto growing = std::make_shared<gs::splats::GaussianCloud>();
  growing->shDegree = all.shDegree;
  const std::size_t prefix = all.size() / 3;
  for (std::size_t i = 0; i < prefix; ++i) growing->append(all, i);
  auto set = std::make_shared<SplatSet>(*whole);
  set->gaussians = growing;
  set->lodTree = std::make_shared<const gs::splats::LodTree>(gs::splats::buildLodTree(*growing));
  const gs::scene::Camera cam = gaussianCamera(*whole, 1.2f);
  const Image everySplat = drawGaussians(*whole, cam, SplatPath::cpu);
  static auto context = createOffscreenContext(kGaussianSize, kGaussianSize);
  for (const SplatPath path : {SplatPath::cpu, SplatPath::gpu}) {
    INFO("path " << static_cast<int>(path));
    context->makeCurrent();
    growing->resize(prefix);
    const auto frame = [&](SplatRenderer& renderer) {
      glViewport(0, 0, kGaussianSize, kGaussianSize);
      glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      renderer.draw(*set, set->size(), glm::mat4(1.0f), cam, 1.0f, {});
      return readPixels(0, 0, kGaussianSize, kGaussianSize);
    };
    SplatRenderer held;
    held.setPath(path);
    frame(held);  // the prefix alone
    for (std::size_t i = prefix; i < all.size(); ++i) growing->append(all, i);
    const Image grown = frame(held);
    const std::size_t drawn = held.statistics().splats;
    SplatRenderer fresh;
    fresh.setPath(path);
    const Image reference = frame(fresh);
    CHECK(drawn == fresh.statistics().splats);
    CHECK(drawn > prefix);
    CHECK(compareImages(grown, reference).fractionDiffering == 0.0);
    CHECK(compareImages(grown, everySplat).psnr >= 50.0);
    held.release();
    fresh.release();
  }
}

TEST_CASE("a QNV Gaussian stream draws the picture of its .ply, and its prefixes a close one",
          "[render][splat][gaussian][qnv]") {
  const fs::path dir = gs::test::sourceDir() / "tests/data/splats";
  const auto ply = gaussianScene(dir / "bunny_small.ply", false);
  const gs::scene::Camera cam = gaussianCamera(*ply, 1.2f);
  const Image reference = drawGaussians(*ply, cam, SplatPath::cpu);
  const gs::qnv::EncodedVectors encoded = gs::splats::encodeGaussianStream(*ply->gaussians);
  REQUIRE(encoded.header.shDegree == ply->gaussians->shDegree);
  for (const auto coding : {gs::qnv::PacketEncoding::plain, gs::qnv::PacketEncoding::compact}) {
    const std::string bytes = gs::qnv::writeStream(encoded, {encoded.header.packetBytes, coding});
    const auto set = setOf(gs::splats::readQnvGaussians(bytes, "bunny_small.qnv"));
    REQUIRE(set->size() == ply->size());
    const ImageDifference d = compareImages(drawGaussians(*set, cam, SplatPath::cpu), reference);
    WARN("QNV Gaussian stream (" << (coding == gs::qnv::PacketEncoding::plain ? "plain" : "compact")
                                 << "): " << double(bytes.size()) / double(set->size())
                                 << " bytes per splat, PSNR " << d.psnr << " dB, "
                                 << d.fractionDiffering * 100 << "% of pixels off");
    CHECK(d.fractionDiffering <= 0.02);
    CHECK(d.psnr >= 35.0);
    if (coding == gs::qnv::PacketEncoding::compact) {
      // Fewer bytes than the same scene as SPZ (41.9 dB) and SOG (55.9 dB) files
      // (docs/splats.md, "Bytes and pictures against SPZ and SOG").
      CHECK(bytes.size() < fs::file_size(dir / "bunny_small.spz"));
      CHECK(bytes.size() < fs::file_size(dir / "bunny_small.sog"));
      // Half the bytes: the first packet, the largest third of the splats.
      const auto prefix = setOf(gs::splats::readQnvGaussians(
          std::string_view(bytes).substr(0, bytes.size() / 2), "bunny_small.qnv"));
      CHECK(prefix->size() > 0);
      CHECK(prefix->size() < set->size());
      const ImageDifference p =
          compareImages(drawGaussians(*prefix, cam, SplatPath::cpu), reference);
      Image black = reference;
      std::fill(black.rgba.begin(), black.rgba.end(), std::uint8_t{0});
      const double blackPsnr = compareImages(black, reference).psnr;
      WARN("its first half of the bytes: " << prefix->size() << " splats, PSNR " << p.psnr
                                           << " (an empty picture: " << blackPsnr << ")");
      CHECK(p.psnr >= blackPsnr + 2.0);  // the largest splats already draw
      CHECK(p.psnr < d.psnr);
    }
  }
}

TEST_CASE(
    "the cpu path composites only the tiles its splats reach, inside the caller's "
    "scissor box",
    "[render][splat][gaussian]") {
  // Two small red Gaussians near opposite corners: the image is put down as the rectangle
  // of the tiles they reach (a far cut's few splats cost a small upload). A scissor box the
  // caller set (a layer's viewport) still clips it, and is left as it was.
  auto cloud = std::make_shared<gs::splats::GaussianCloud>();
  cloud->resize(2);
  cloud->positions = {glm::vec3(-0.8f, -0.8f, 0.0f), glm::vec3(0.8f, 0.8f, 0.0f)};
  cloud->scales = {glm::vec3(0.03f), glm::vec3(0.03f)};
  cloud->shDc = {glm::vec3(1.5f, -1.8f, -1.8f), glm::vec3(1.5f, -1.8f, -1.8f)};
  SplatSet set;
  set.gaussians = cloud;
  set.computeBounds();
  gs::scene::Camera cam;
  cam.position = glm::vec3(0.0f, 0.0f, 2.0f);
  cam.fieldOfView = 1.0f;
  const auto redAt = [](const Image& image, int x, int y) {
    const std::uint8_t* p = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
    return p[0] > 128 && p[1] < 64;
  };
  // Where each centre lands (x, y from the bottom left): found on the geometry path.
  const Image reference = drawGaussians(set, cam, SplatPath::geometry);
  int lowX = -1, lowY = -1, highX = -1, highY = -1;
  for (int y = 0; y < kGaussianSize; ++y)
    for (int x = 0; x < kGaussianSize; ++x)
      if (redAt(reference, x, y)) {
        if (x < kGaussianSize / 2)
          lowX = x, lowY = y;
        else
          highX = x, highY = y;
      }
  REQUIRE(lowX >= 0);
  REQUIRE(highX >= 0);
  const Image whole = drawGaussians(set, cam, SplatPath::cpu);
  CHECK(redAt(whole, lowX, lowY));
  CHECK(redAt(whole, highX, highY));

  static auto context = createOffscreenContext(kGaussianSize, kGaussianSize);
  context->makeCurrent();
  SplatRenderer renderer;
  renderer.setPath(SplatPath::cpu);
  glViewport(0, 0, kGaussianSize, kGaussianSize);
  glDisable(GL_SCISSOR_TEST);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, kGaussianSize / 2, kGaussianSize / 2);  // the bottom left quarter
  renderer.draw(set, set.size(), glm::mat4(1.0f), cam, 1.0f, {});
  GLint box[4];
  glGetIntegerv(GL_SCISSOR_BOX, box);
  CHECK(glIsEnabled(GL_SCISSOR_TEST) == GL_TRUE);
  CHECK(box[2] == kGaussianSize / 2);
  glDisable(GL_SCISSOR_TEST);
  const Image clipped = readPixels(0, 0, kGaussianSize, kGaussianSize);
  renderer.release();
  CHECK(redAt(clipped, lowX, lowY));
  CHECK_FALSE(redAt(clipped, highX, highY));
}
