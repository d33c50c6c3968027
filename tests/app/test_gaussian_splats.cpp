// 3D Gaussian splatting scenes through the whole program (docs/splats.md): the corpus's
// captures drawn by `ghostspace --snapshot` against PlayCanvas splat-transform's own
// rasterizer (pictures made by ../shared/peers/splat/render.sh, committed under
// tests/data/splats/peer/), scored as the peer's README scores two renderers: PSNR over
// the peer's foreground less a 1-pixel band around its silhouette.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "base/byte_order.hpp"
#include "base/data_url.hpp"
#include "baseline.hpp"
#include "process.hpp"
#include "qnv/tileset.hpp"
#include "render/image.hpp"
#include "session/tileset_selection.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

/// A world showing `scene` as the peer sees it: the scene turned 180 degrees about Z
/// (as ghostspace opens a capture, and as render.sh draws it), a Viewpoint at `position`
/// looking down -Z, vertical field of view 60 degrees (square pictures).
std::string peerWorld(const std::string& name, const fs::path& scene, const std::string& position) {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path world = dir / (name + ".wrl");
  std::ofstream(world) << "#VRML V2.0 utf8\n"
                       << "Viewpoint { position " << position << " fieldOfView 1.04719755 }\n"
                       << "NavigationInfo { headlight FALSE }\n"
                       << "Transform { rotation 0 0 1 3.14159265 children QuantizedNormalVectors "
                          "{ url \""
                       << scene.string() << "\" } }\n";
  return world.string();
}

/// PSNR (dB) of `ours` against `peer` over the pixels where the peer drew something
/// (a channel above 8), less those within one pixel of a pixel where it did not.
double foregroundPsnr(const std::string& ours, const std::string& peer) {
  const gs::render::Image a = gs::render::readPng(ours), b = gs::render::readPng(peer);
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  const auto lit = [&](int x, int y) {
    if (x < 0 || y < 0 || x >= b.width || y >= b.height) return false;
    const std::size_t i = (static_cast<std::size_t>(y) * b.width + x) * 4;
    return b.rgba[i] > 8 || b.rgba[i + 1] > 8 || b.rgba[i + 2] > 8;
  };
  double squared = 0.0;
  std::size_t count = 0;
  for (int y = 0; y < b.height; ++y) {
    for (int x = 0; x < b.width; ++x) {
      bool inside = true;
      for (int dy = -1; dy <= 1 && inside; ++dy)
        for (int dx = -1; dx <= 1 && inside; ++dx) inside = lit(x + dx, y + dy);
      if (!inside) continue;
      const std::size_t i = (static_cast<std::size_t>(y) * b.width + x) * 4;
      for (int c = 0; c < 3; ++c) {
        const double d = double(a.rgba[i + c]) - double(b.rgba[i + c]);
        squared += d * d;
      }
      count += 3;
    }
  }
  REQUIRE(count > 300);  // the peer drew a picture
  if (squared == 0.0) return INFINITY;
  return 10.0 * std::log10(255.0 * 255.0 / (squared / double(count)));
}

}  // namespace

TEST_CASE("the corpus's Gaussian splatting scenes look as PlayCanvas draws them",
          "[heavy][app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("splat")) return;
  const fs::path peer = gs::test::sourceDir() / "tests/data/splats/peer";
  struct Case {
    const char* name;
    const char* file;
    const char* position;
    double minimum;  // dB
  };
  for (const Case& c : {Case{"bunny", "bunny.spz", "0.017 -0.11 0.3", 40.0},
                        Case{"cthead", "cthead.spz", "0 0 2.6", 38.0}}) {
    SECTION(c.name) {
      const std::string world = peerWorld(std::string("gaussians_") + c.name,
                                          gs::test::corpusDir() / "splat" / c.file, c.position);
      const std::string ours =
          gs::test::snapshot(std::string("gaussians_") + c.name, {"--size", "400x400", world});
      const double psnr = foregroundPsnr(ours, (peer / (std::string(c.name) + ".png")).string());
      WARN(c.name << ": " << psnr << " dB against the peer");
      CHECK(psnr >= c.minimum);
    }
  }
}

TEST_CASE("a Gaussian splatting file opens on its own, and a broken one is an error",
          "[app][render][splat]") {
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  // A .ply with Gaussian properties is a splat scene, never a mesh drawn as a black frame.
  const std::string ours = gs::test::snapshot(
      "gaussians_bunny_small", {"--size", "96x96", (data / "bunny_small.ply").string()});
  const gs::render::Image image = gs::render::readPng(ours);
  std::size_t lit = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    lit += image.rgba[i] > 16 || image.rgba[i + 1] > 16 || image.rgba[i + 2] > 16;
  CHECK(lit > 500);  // framed whole: the bunny fills a good part of the picture

  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path bad = dir / "broken.spz";
  std::ofstream(bad, std::ios::binary) << "NGSP\x04 not really a splat scene";
  const auto r = gs::test::runGhostspace(
      {"--snapshot", (dir / "broken.png").string(), "--size", "32x32", bad.string()});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("broken.spz") != std::string::npos);
}

TEST_CASE("a glTF capture opens as its .ply does: on its own and in an Inline",
          "[app][render][splat]") {
  // KHR_gaussian_splatting drawn as Gaussians, not as points with a warning: a .glb of
  // splats alone opens as a capture; in a world, the importer's GaussianSplats node draws
  // it (tests/gltf: a glTF with other primitives too).
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const auto r = gs::test::runGhostspace({"--snapshot", (dir / "gltf_capture.png").string(),
                                          "--size", "96x96", (data / "bunny_small.glb").string()});
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("not supported") == std::string::npos);
  const std::string ply = gs::test::snapshot(
      "gltf_capture_ply", {"--size", "96x96", (data / "bunny_small.ply").string()});
  CHECK(gs::test::fractionDiffering((dir / "gltf_capture.png").string(), ply) < 0.005);
  std::map<std::string, std::string> inlined;
  for (const char* file : {"bunny_small.glb", "bunny_small.ply"}) {
    const fs::path world = dir / (std::string("gltf_inline_") + file + ".wrl");
    std::ofstream(world) << "#VRML V2.0 utf8\nViewpoint { position 0 0 0.4 }\n"
                         << "Inline { url \"" << (data / file).string() << "\" }\n";
    inlined[file] =
        gs::test::snapshot(std::string("gltf_inline_") + file, {"--size", "96x96", world.string()});
  }
  CHECK(gs::test::fractionDiffering(inlined["bunny_small.glb"], inlined["bunny_small.ply"]) <
        0.005);
  const gs::render::Image image = gs::render::readPng(inlined["bunny_small.glb"]);
  std::size_t lit = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    lit += image.rgba[i] > 16 || image.rgba[i + 1] > 16 || image.rgba[i + 2] > 16;
  CHECK(lit > 300);  // the bunny is drawn, not a black frame
  // Its colour space: linear SH colours (lin_rec709_display) are shown through the sRGB
  // transfer function, and stay so encoded as a QNV stream (header byte 51).
  std::string linear = gs::test::readBytes(data / "bunny_small.glb");
  const std::size_t at = linear.find("\"srgb_rec709_display\"");
  REQUIRE(at != std::string::npos);
  linear.replace(at, 21, "\"lin_rec709_display\" ");  // the JSON chunk keeps its length
  const fs::path linearGlb = dir / "gltf_capture_linear.glb", qnv = dir / "gltf_capture_linear.qnv";
  std::ofstream(linearGlb, std::ios::binary) << linear;
  REQUIRE(gs::test::runGhostspace({"encode", linearGlb.string(), "-o", qnv.string()}).exitCode ==
          0);
  const std::string shown =
      gs::test::snapshot("gltf_capture_linear", {"--size", "96x96", linearGlb.string()});
  const std::string encoded =
      gs::test::snapshot("gltf_capture_linear_qnv", {"--size", "96x96", qnv.string()});
  CHECK(gs::test::fractionDiffering(shown, (dir / "gltf_capture.png").string()) > 0.05);
  CHECK(gs::test::fractionDiffering(shown, encoded) < 0.005);
}

TEST_CASE("info describes a splat scene in every encoding", "[app][splat]") {
  // Before, `info capture.ply` described the world made for it: "QuantizedNormalVectors 1,
  // shapes drawn: 0, bounding box: empty".
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  const std::vector<std::pair<std::string, std::string>> files = {
      {"bunny_small.ply", "3D Gaussian splatting PLY (INRIA)"},
      {"bunny_small.compressed.ply", "PlayCanvas compressed PLY"},
      {"bunny_small.spz", "Niantic SPZ"},
      {"bunny_small_v3.spz", "Niantic SPZ"},
      {"bunny_small.sog", "PlayCanvas SOG bundle"},
      {"bunny_small_sog/meta.json", "PlayCanvas SOG (meta.json and WebP images)"},
      {"bunny_small.splat", ".splat (32 bytes a splat)"},
      {"bunny_small.glb", "glTF KHR_gaussian_splatting"}};
  for (const auto& [file, format] : files) {
    INFO(file);
    const auto r = gs::test::runGhostspace({"info", (data / file).string()});
    CHECK(r.exitCode == 0);
    CHECK_THAT(r.out, Catch::Contains(file + ": " + format));
    CHECK_THAT(r.out, Catch::Contains("splats      3000, SH degree " +
                                      std::string(file == "bunny_small.splat" ? "0" : "1") +
                                      ", colours sRGB"));
    CHECK_THAT(r.out, Catch::Contains("bounds      -0.094"));
  }
  // A damaged one: the reader's error, exit 1.
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const std::string ply = gs::test::readBytes(data / "bunny_small.ply");
  std::ofstream(dir / "info_cut.ply", std::ios::binary) << ply.substr(0, ply.size() / 2);
  const auto cut = gs::test::runGhostspace({"info", (dir / "info_cut.ply").string()});
  CHECK(cut.exitCode == 1);
  CHECK_THAT(cut.err, Catch::Contains("info_cut.ply"));
}

TEST_CASE("the corpus's scenes as QNV Gaussian streams: fewer bytes than SPZ, the peer's picture",
          "[heavy][app][render][splat][corpus][qnv]") {
  if (!gs::test::haveCorpus("splat")) return;
  const fs::path peer = gs::test::sourceDir() / "tests/data/splats/peer";
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  struct Case {
    const char* name;
    const char* position;
    double minimum;  // dB against the peer, as its SPZ
  };
  for (const Case& c : {Case{"bunny", "0.017 -0.11 0.3", 40.0}, Case{"cthead", "0 0 2.6", 38.0}}) {
    SECTION(c.name) {
      const fs::path spz = gs::test::corpusDir() / "splat" / (std::string(c.name) + ".spz");
      const fs::path qnv = dir / (std::string(c.name) + "_gaussians.qnv");
      const auto r = gs::test::runGhostspace({"encode", spz.string(), "-o", qnv.string()});
      REQUIRE(r.exitCode == 0);
      const auto qnvBytes = fs::file_size(qnv), spzBytes = fs::file_size(spz);
      const std::string world = peerWorld(std::string("gaussians_qnv_") + c.name, qnv, c.position);
      const std::string ours =
          gs::test::snapshot(std::string("gaussians_qnv_") + c.name, {"--size", "400x400", world});
      const double psnr = foregroundPsnr(ours, (peer / (std::string(c.name) + ".png")).string());
      WARN(c.name << " as a QNV Gaussian stream: " << qnvBytes << " bytes (SPZ " << spzBytes
                  << "), " << psnr << " dB against the peer");
      CHECK(qnvBytes < spzBytes);
      CHECK(psnr >= c.minimum);

      // Progressive: what arrived after 5% of the bytes already shows the scene.
      const std::string part = gs::test::snapshot(
          std::string("gaussians_qnv_5pct_") + c.name,
          {"--size", "400x400", "--snapshot-at", std::to_string(qnvBytes / 20), world});
      const auto lit = [](const std::string& png) {
        const gs::render::Image image = gs::render::readPng(png);
        std::size_t n = 0;
        for (std::size_t i = 0; i < image.rgba.size(); i += 4)
          n += image.rgba[i] > 16 || image.rgba[i + 1] > 16 || image.rgba[i + 2] > 16;
        return n;
      };
      const double covered = double(lit(part)) / double(lit(ours));
      WARN("  after 5% of its bytes: "
           << covered * 100 << "% of the whole picture's pixels lit, "
           << foregroundPsnr(part, (peer / (std::string(c.name) + ".png")).string())
           << " dB against the peer");
      CHECK(covered >= 0.2);  // a surface capture is still sparse: its largest 5% of splats
    }
  }
}

TEST_CASE("a Gaussian splatting scene as a QNV tileset draws the scene's picture, by view",
          "[app][render][splat][tileset]") {
  const fs::path ply = gs::test::sourceDir() / "tests/data/splats/bunny_small.ply";
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual" / "bunny_small_tileset";
  // 512 splats a brick: depth 1, a merged root of 16^3 cells.
  const auto r = gs::test::runGhostspace(
      {"encode", ply.string(), "--tileset", dir.string() + "/", "--brick-vectors", "512"});
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.out, Catch::Contains("3000 splats"));
  REQUIRE(fs::is_regular_file(dir / "merged/0/0_0_0.qnv"));
  // Compact packets by default (64,195 bytes in all; plain ones, --coding plain, take about
  // twice that: a default that became plain went unnoticed once).
  std::uintmax_t bytes = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) bytes += e.file_size();
  CHECK(bytes < 80000);
  const auto info = gs::test::runGhostspace({"info", (dir / "index.qnvt").string()});
  CHECK(info.exitCode == 0);
  CHECK_THAT(info.out, Catch::Contains("QNV tileset, Gaussian splats, SH degree 1") &&
                           Catch::Contains("splats      3000 in 9 bricks, depth 1"));
  // Near, every splat is fetched: the scene file's picture (measured 50.2 dB). Far, the
  // merged root stands for the scene, merged further to the pixel by its own tree (31.0 dB
  // over its few pixels; 29.6 without that tree).
  struct View {
    const char* name;
    const char* position;
    double minimum;
  };
  for (const View& v :
       {View{"near", "0.017 -0.11 0.3", 40.0}, View{"far", "0.017 -0.11 3", 27.0}}) {
    const std::string name = std::string("bunny_small_tileset_") + v.name;
    const std::string scene = gs::test::snapshot(
        name + "_ply", {"--size", "400x400", peerWorld(name + "_ply", ply, v.position)});
    const std::string tileset = gs::test::snapshot(
        name, {"--size", "400x400", peerWorld(name, dir / "index.qnvt", v.position)});
    const double psnr = foregroundPsnr(tileset, scene);
    WARN(v.name << ": the tileset's picture " << psnr << " dB against the scene file's");
    CHECK(psnr >= v.minimum);
  }
}

TEST_CASE("CThead's capture as a QNV tileset looks as PlayCanvas draws it",
          "[heavy][app][render][splat][corpus][tileset]") {
  if (!gs::test::haveCorpus("splat")) return;
  const fs::path spz = gs::test::corpusDir() / "splat/cthead.spz";
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual" / "cthead_tileset";
  const auto r = gs::test::runGhostspace({"encode", spz.string(), "--tileset", dir.string() + "/"});
  REQUIRE(r.exitCode == 0);
  const std::string ours = gs::test::snapshot(
      "cthead_tileset",
      {"--size", "400x400", peerWorld("cthead_tileset", dir / "index.qnvt", "0 0 2.6")});
  const double psnr =
      foregroundPsnr(ours, (gs::test::sourceDir() / "tests/data/splats/peer/cthead.png").string());
  WARN("CThead as a Gaussian tileset: " << psnr << " dB against the peer");
  CHECK(psnr >= 38.0);  // as its stream
  // The scene's default K (splats::defaultGaussianBrickVectors: 8192 for its 122,000
  // splats) makes the octree 2 deep, so that its level-1 nodes have merged bricks.
  CHECK_THAT(r.out, Catch::Contains("(13 leaves, depth 2)"));
  // At 10 units the merged root is too coarse but the level-1 merged bricks stand for the
  // scene: the view fetches them, not the leaves' prefixes (0.45 MB of the tileset's
  // 3.1 MB; 1.84 of 2.57 MB with the leaves at level 1), and draws the level-of-detail
  // tree's cut of them: about as few splats as the scene file's own tree cut (23,709).
  {
    const std::string indexBytes = gs::test::readBytes(dir / "index.qnvt");
    std::string error;
    const auto index = gs::qnv::parseTilesetIndex(indexBytes, "index.qnvt", error);
    REQUIRE(index);
    gs::session::TilesetView view;
    view.position = glm::vec3(0.0f, 0.0f, 10.0f);
    view.verticalFov = 1.04719755f;
    view.heightPixels = 400;
    view.model = glm::rotate(glm::mat4(1.0f), 3.14159265f, glm::vec3(0.0f, 0.0f, 1.0f));
    const gs::session::MergedChoice merged = gs::session::chooseMerged(*index, {view});
    std::uint64_t fetched =
        gs::session::totalBytes(gs::session::selectBricks(*index, view, {}, merged.skip));
    for (const std::size_t b : merged.merged)
      fetched += fs::file_size(dir / index->bricks[b].mergedPath());
    std::uint64_t all = 0;
    for (const auto& entry : fs::recursive_directory_iterator(dir))
      if (entry.is_regular_file() && entry.path().extension() != ".csv" &&
          entry.path().extension() != ".png")
        all += entry.file_size();
    WARN("CThead's tileset at 10 units fetches " << fetched << " of " << all << " bytes, "
                                                 << merged.merged.size() << " merged bricks");
    CHECK(merged.merged.size() == 8);  // the level-1 nodes
    CHECK(fetched * 4 < all);
  }
  const fs::path log = dir / "middle.csv";
  const std::string middle = gs::test::snapshot(
      "cthead_tileset_middle", {"--size", "400x400", "--frame-log", log.string(),
                                peerWorld("cthead_tileset_middle", dir / "index.qnvt", "0 0 10")});
  const std::string scene = gs::test::snapshot(
      "cthead_middle", {"--size", "400x400", peerWorld("cthead_middle", spz, "0 0 10")});
  const double middlePsnr = foregroundPsnr(middle, scene);
  std::string lastLine;  // the snapshot's frame
  std::istringstream lines(gs::test::readBytes(log));
  for (std::string line; std::getline(lines, line);)
    if (!line.empty()) lastLine = line;
  WARN("CThead's tileset at 10 units: " << middlePsnr << " dB against the scene file's picture; "
                                        << lastLine);
  CHECK(middlePsnr >= 32.0);  // 35.1 against the stream's picture (30.7 with depth 1)
  // At 30 units the merged root stands for the scene: 32^3 cells for this capture
  // (splats::defaultGaussianMergedCellsLog2), 33.3 dB against the stream's picture (16^3
  // cells: 26.2).
  const std::string far = gs::test::snapshot(
      "cthead_tileset_far",
      {"--size", "400x400", peerWorld("cthead_tileset_far", dir / "index.qnvt", "0 0 30")});
  const std::string sceneFar = gs::test::snapshot(
      "cthead_far", {"--size", "400x400", peerWorld("cthead_far", spz, "0 0 30")});
  const double farPsnr = foregroundPsnr(far, sceneFar);
  WARN("CThead's tileset at 30 units: " << farPsnr << " dB against the scene file's picture");
  CHECK(farPsnr >= 30.0);
  std::istringstream fields(lastLine);
  std::string field;
  for (int i = 0; i < 5; ++i) std::getline(fields, field, ',');  // vectors0, the fifth
  const unsigned long drawn = std::strtoul(field.c_str(), nullptr, 10);
  CHECK(drawn > 10000);
  CHECK(drawn < 30000);
}

TEST_CASE("an Inline opens splat scenes, QNV streams, meshes and volumes beside polygons",
          "[app][render][splat]") {
  // As X3D 4.0's Inline opens glTF, an Inline opens every file ghostspace opens: each is
  // the world that file opens as, placed under the Inline's Transform. Each picture must
  // differ from the same world without the Inline.
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path qnv = dir / "inline_cube.qnv";
  const auto encoded = gs::test::runGhostspace(
      {"encode", (gs::test::sourceDir() / "assets/meshes/cube_ascii.ply").string(), "-o",
       qnv.string()});
  REQUIRE(encoded.exitCode == 0);
  const auto world = [&](const std::string& name, const std::string& inlined,
                         const std::string& scale) {
    const fs::path path = dir / (name + ".wrl");
    std::ofstream(path) << "#VRML V2.0 utf8\nViewpoint { position 0 0 6 }\n"
                        << "Transform { translation -1.5 0 0 children Shape { appearance "
                           "Appearance { material Material { diffuseColor 0 0 1 } } geometry "
                           "Box { size 1 1 1 } } }\n"
                        << "Transform { translation 1.2 0 0 scale " << scale << " " << scale << " "
                        << scale << " children " << inlined << " }\n";
    return path.string();
  };
  const fs::path splats = gs::test::sourceDir() / "tests/data/splats";
  const fs::path tileset = dir / "inline_bunny_tileset";
  REQUIRE(gs::test::runGhostspace({"encode", (splats / "bunny_small.ply").string(), "--tileset",
                                   tileset.string() + "/", "--brick-vectors", "512"})
              .exitCode == 0);
  const std::vector<std::array<std::string, 3>> inputs = {
      {"inline_spz", (splats / "bunny_small.spz").string(), "8"},
      {"inline_gaussian_tileset", (tileset / "index.qnvt").string(), "8"},
      {"inline_ply_capture", (splats / "bunny_small.ply").string(), "8"},
      {"inline_qnv", qnv.string(), "1"},
      {"inline_mesh", (gs::test::sourceDir() / "assets/meshes/cube_ascii.ply").string(), "1"},
      {"inline_vdb", (gs::test::sourceDir() / "tests/data/vdb/cthead_skin_ls.vdb").string(),
       "0.01"}};
  for (const auto& [name, url, scale] : inputs) {
    INFO(name);
    const std::string with = gs::test::snapshot(
        name, {"--size", "128x96", world(name, "Inline { url \"" + url + "\" }", scale)});
    const std::string without = gs::test::snapshot(
        name + "_none", {"--size", "128x96", world(name + "_none", "Group {}", scale)});
    CHECK(gs::test::fractionDiffering(with, without) > 0.01);
  }
}

TEST_CASE("a glTF of a mesh and Gaussian splats shows both", "[app][render][splat]") {
  // bunny_small.glb with a red triangle beside the bunny (glTF's axes: the bunny within
  // x -0.06..0.09, y -0.19..-0.03), its positions in a data: buffer of their own: the
  // importer draws the triangle as a Shape and the splats by a GaussianSplats node.
  const fs::path data = gs::test::sourceDir() / "tests/data/splats";
  const std::string glb = gs::test::readBytes(data / "bunny_small.glb");
  const std::uint32_t jsonBytes = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  nlohmann::json doc = nlohmann::json::parse(glb.substr(20, jsonBytes));
  const std::string bin = glb.substr(20 + jsonBytes);  // the BIN chunk, its header too
  const float triangle[9] = {0.12f, -0.19f, 0.0f, 0.30f, -0.19f, 0.0f, 0.12f, -0.03f, 0.0f};
  const std::string positions(reinterpret_cast<const char*>(triangle), sizeof triangle);
  doc["buffers"].push_back({{"byteLength", positions.size()},
                            {"uri", gs::base::makeDataUrl("application/octet-stream", positions)}});
  doc["bufferViews"].push_back(
      {{"buffer", doc["buffers"].size() - 1}, {"byteOffset", 0}, {"byteLength", 36}});
  doc["accessors"].push_back({{"bufferView", doc["bufferViews"].size() - 1},
                              {"componentType", 5126},
                              {"count", 3},
                              {"type", "VEC3"},
                              {"min", {0.12, -0.19, 0.0}},
                              {"max", {0.30, -0.03, 0.0}}});
  doc["materials"] =
      nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 1.0}}}},
                              {"emissiveFactor", {1.0, 0.0, 0.0}},
                              {"doubleSided", true}}});
  doc["meshes"].push_back(
      {{"primitives",
        {{{"attributes", {{"POSITION", doc["accessors"].size() - 1}}}, {"material", 0}}}}});
  doc["nodes"].push_back({{"mesh", doc["meshes"].size() - 1}});
  doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
  std::string json = doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  std::string mixed = "glTF";
  const auto le32 = [&](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) mixed.push_back(static_cast<char>((v >> (8 * k)) & 0xff));
  };
  le32(2);
  le32(static_cast<std::uint32_t>(12 + 8 + json.size() + bin.size()));
  le32(static_cast<std::uint32_t>(json.size()));
  le32(0x4E4F534Au);
  mixed += json + bin;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path file = dir / "gltf_mixed.glb", png = dir / "gltf_mixed.png";
  std::ofstream(file, std::ios::binary) << mixed;
  const auto r =
      gs::test::runGhostspace({"--snapshot", png.string(), "--size", "128x128", file.string()});
  REQUIRE(r.exitCode == 0);
  CHECK(r.err.find("not supported") == std::string::npos);
  const gs::render::Image image = gs::render::readPng(png.string());
  std::size_t red = 0, bunny = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const int R = image.rgba[i], G = image.rgba[i + 1], B = image.rgba[i + 2];
    const bool isRed = R > 150 && G < 40 && B < 40;
    red += isRed;
    // The bunny's colours (its SH are its normals: purples, blues, greens), neither the
    // grey background nor the red triangle.
    bunny += !isRed && std::max({R, G, B}) - std::min({R, G, B}) > 30;
  }
  CHECK(red > 700);    // the triangle (1,437 pixels)
  CHECK(bunny > 800);  // and the splats (1,732)
}
