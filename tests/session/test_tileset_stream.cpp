// session/tileset_stream.hpp end to end on local files (no GL): a tileset written after
// the pinned rule, opened through the session, driven by recorded views.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "qnv/encoder.hpp"
#include "qnv/volume.hpp"
#include "scene/camera.hpp"
#include "session/streaming_session.hpp"
#include "splats/gaussian_tileset.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"
#include "tileset_fixture.hpp"

namespace fs = std::filesystem;
using namespace gs;

namespace {

qnv::EncodedVectors ballVectors(int n) {
  return test::ballVolumeVectors(n);
}

fs::path freshDir(const std::string& name) {
  const fs::path d = fs::path(GS_BINARY_DIR) / "tileset-actual" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Opens `input` in a session, shows its set to one view of `camera` (512 x 512) and
/// pumps until settled. Returns the tileset's statistics and the vectors drawn.
struct Loaded {
  session::TilesetStatistics stats;
  std::vector<qnv::DecodedVector> vectors;
  std::size_t splats = 0;  // a Gaussian tileset's splats drawn
  std::size_t mergedSplats = 0;
  // Splats under the level-of-detail trees of the set and of its merged set (0: none).
  std::size_t treeSplats = 0, mergedTreeSplats = 0;
  std::vector<std::pair<bool, std::string>> messages;
  net::StreamProgress progress;  // the tileset's line of StreamingSession::progress()
};

Loaded load(const std::string& input, const scene::Camera* camera,
            net::LoaderOptions loaderOptions = {}, float distanceScale = 1.0f,
            const session::TilesetOptions* tileset = nullptr) {
  session::StreamingSession s(loaderOptions);
  if (tileset) s.setTilesetOptions(*tileset);
  std::string error;
  auto scene = s.open(input, error);
  REQUIRE(scene);
  auto options = s.rendererOptions({});
  auto set = options.splatLoader(input, "", error);
  REQUIRE(set);
  for (int i = 0; i < 100000 && !(s.pump(), s.settled() && !set->bounds.empty()); ++i)
    s.loader().wait(0.01);
  render::SplatSet::View view;
  view.camera = camera ? *camera : scene::fitCamera(set->bounds, 1.0f, scene::Camera{});
  if (!camera)  // farther along the same line of sight
    view.camera.position =
        set->bounds.center() + (view.camera.position - set->bounds.center()) * distanceScale;
  view.heightPixels = 512;
  view.vectors = set->total();
  const auto request = set->viewRequests->request();
  request->update(view);
  for (int i = 0; i < 100000 && !(s.pump(), s.settled()); ++i) s.loader().wait(0.01);
  Loaded out;
  REQUIRE(s.tilesets().size() == 1);
  out.stats = s.tilesets()[0]->statistics();
  out.vectors = set->vectors;
  out.splats = set->gaussians ? set->gaussians->size() : 0;
  out.mergedSplats = set->merged ? set->merged->size() : 0;
  out.treeSplats = set->lodTree ? set->lodTree->splatCount : 0;
  out.mergedTreeSplats = set->merged && set->merged->lodTree ? set->merged->lodTree->splatCount : 0;
  s.drainMessages(out.messages);
  REQUIRE(!s.progress().empty());
  out.progress = s.progress().back();
  return out;
}

bool byValue(const qnv::DecodedVector& a, const qnv::DecodedVector& b) {
  return std::tie(a.position.x, a.position.y, a.position.z, a.magnitude, a.rgba) <
         std::tie(b.position.x, b.position.y, b.position.z, b.magnitude, b.rgba);
}

}  // namespace

TEST_CASE("tileset stream: the whole view at full refinement holds the single stream's vectors",
          "[tileset][session]") {
  const auto encoded = ballVectors(24);
  const fs::path dir = freshDir("ball24");
  const auto index = test::writeTestTileset(encoded, dir, 512);
  REQUIRE(index.bricks.size() == 9);
  // The single stream, decoded.
  const std::string single = (dir / "single.qnv").string();
  std::ofstream(single, std::ios::binary) << qnv::writeStream(encoded);
  std::string error;
  const auto whole = render::loadQnvFile(single, error);
  REQUIRE(whole);

  for (const std::string& input : {dir.string(), (dir / "index.qnvt").string()}) {
    const Loaded l = load(input, nullptr);
    INFO(input);
    CHECK(l.messages.empty());
    CHECK(l.stats.chosenBricks == 9);
    std::uint64_t files = 0;
    for (const auto& b : index.bricks) files += b.fileBytes;
    CHECK(l.stats.brickBytes == files);
    // Its line in the Streams panel: every byte of the tileset's files, every vector.
    CHECK(l.progress.url.find("index.qnvt") != std::string::npos);
    CHECK(l.progress.state == net::StreamState::idle);
    CHECK(l.progress.bytes == l.stats.indexBytes + files);
    CHECK(l.progress.expectedBytes == static_cast<std::int64_t>(l.stats.indexBytes + files));
    CHECK(l.progress.vectors == encoded.records.size());
    CHECK(l.progress.expectedVectors == encoded.records.size());
    CHECK(l.progress.fraction() == 1.0);
    auto a = l.vectors, b = whole->vectors;
    std::sort(a.begin(), a.end(), byValue);
    std::sort(b.begin(), b.end(), byValue);
    REQUIRE(a.size() == b.size());
    CHECK(std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
      return x.position == y.position && x.magnitude == y.magnitude && x.normal == y.normal &&
             x.rgba == y.rgba;
    }));
  }
}

TEST_CASE("tileset stream: a zoom into one corner fetches far fewer bytes", "[tileset][session]") {
  const auto encoded = ballVectors(24);
  const fs::path dir = freshDir("ball24zoom");
  test::writeTestTileset(encoded, dir, 512);
  const Loaded whole = load(dir.string(), nullptr);
  // Close to the corner of the lowest x, y, z octant, looking along +z into it.
  const auto& h = encoded.header;
  scene::Camera zoom;
  zoom.position = h.boundsMin + (h.boundsMax - h.boundsMin) * glm::vec3(0.25f, 0.25f, -0.2f);
  zoom.orientation = glm::angleAxis(3.14159265f, glm::vec3(0, 1, 0));  // looks along +z
  zoom.fieldOfView = 0.3f;
  const Loaded corner = load(dir.string(), &zoom);
  INFO(whole.stats.brickBytes << " bytes for the whole view, " << corner.stats.brickBytes
                              << " for the corner");
  CHECK(corner.stats.chosenBricks < whole.stats.chosenBricks);
  CHECK(corner.stats.brickBytes * 2 < whole.stats.brickBytes);
  CHECK(!corner.vectors.empty());
}

TEST_CASE("tileset stream: the loader's byte cap cuts the bricks and stops the tileset",
          "[tileset][session]") {
  const auto encoded = ballVectors(24);
  const fs::path dir = freshDir("ball24_cap");
  const auto index = test::writeTestTileset(encoded, dir, 512);
  std::uint64_t files = 0;
  for (const auto& b : index.bricks) files += b.fileBytes;
  net::LoaderOptions capped;
  capped.stopAfterBytes = files / 3;
  const Loaded l = load(dir.string(), nullptr, capped);
  CHECK(l.messages.empty());  // a cut is no error: no brick "ends after" its bytes
  CHECK(l.stats.indexBytes + l.stats.brickBytes <= capped.stopAfterBytes);
  CHECK(l.stats.brickBytes > 0);
  CHECK(l.vectors.size() < encoded.records.size());
  CHECK(l.progress.state == net::StreamState::stopped);
  CHECK(l.progress.error.find("--snapshot-at") != std::string::npos);
}

TEST_CASE("tileset stream: a hostile index is refused with a message naming it",
          "[tileset][session]") {
  const fs::path dir = freshDir("hostile");
  const auto index = test::writeTestTileset(ballVectors(12), dir, 64);
  std::string bytes = qnv::serializeTilesetIndex(index);
  bytes[20] ^= 0x40;  // inside the template header: the CRC no longer holds
  std::ofstream(dir / "index.qnvt", std::ios::binary) << bytes;
  session::StreamingSession s;
  std::string error;
  const std::string url = (dir / "index.qnvt").string();
  REQUIRE(s.open(url, error));
  auto set = s.rendererOptions({}).splatLoader(url, "", error);
  REQUIRE(set);
  for (int i = 0; i < 100000 && !(s.pump(), s.settled()); ++i) s.loader().wait(0.01);
  std::vector<std::pair<bool, std::string>> messages;
  s.drainMessages(messages);
  REQUIRE(messages.size() == 1);
  CHECK(messages[0].first);
  CHECK(messages[0].second.find(url) != std::string::npos);
  CHECK(set->vectors.empty());
  REQUIRE(s.progress().size() >= 1);
  CHECK(s.progress().back().state == net::StreamState::failed);
  CHECK(s.progress().back().error.find(url) != std::string::npos);
}

TEST_CASE("tileset stream: a new view re-chooses, and far bricks go over the memory budget",
          "[tileset][session]") {
  const auto encoded = ballVectors(24);
  const fs::path dir = freshDir("ball24memory");
  const auto index = test::writeTestTileset(encoded, dir, 512);
  session::TilesetOptions options;
  options.memoryBytes = 6000 * sizeof(qnv::DecodedVector);  // about half the vectors
  session::StreamingSession s;
  s.setTilesetOptions(options);
  std::string error;
  REQUIRE(s.open(dir.string(), error));
  auto set = s.rendererOptions({}).splatLoader((dir / "index.qnvt").string(), "", error);
  REQUIRE(set);
  auto settle = [&] {
    for (int i = 0; i < 100000 && !(s.pump(), s.settled()); ++i) s.loader().wait(0.01);
  };
  settle();
  REQUIRE(!set->bounds.empty());
  const auto& h = encoded.header;
  // Two views, one after the other, each into an opposite corner octant.
  auto corner = [&](glm::vec3 at, float turn) {
    render::SplatSet::View v;
    v.camera.position = h.boundsMin + (h.boundsMax - h.boundsMin) * at;
    v.camera.orientation = glm::angleAxis(turn, glm::vec3(0, 1, 0));
    v.camera.fieldOfView = 0.3f;
    v.heightPixels = 512;
    v.vectors = set->total();
    return v;
  };
  auto request = set->viewRequests->request();
  request->update(corner({0.25f, 0.25f, -0.2f}, 3.14159265f));  // looks along +z
  settle();
  const auto first = s.tilesets()[0]->statistics();
  CHECK(first.chosenBricks == 3);  // root and the two octants of that column
  CHECK(first.residentVectors <= 6000 + index.header.recordsPerPacket());
  request->update(corner({0.75f, 0.75f, 1.2f}, 0.0f));  // the opposite column, along -z
  settle();
  const auto second = s.tilesets()[0]->statistics();
  CHECK(second.chosenBricks == 3);
  CHECK(second.requests > first.requests);
  CHECK(second.evictedBricks >= 1);
  CHECK(second.residentVectors <= 6000 + index.header.recordsPerPacket());
  CHECK(set->vectors.size() == second.chosenVectors);
  // A closed viewport releases its request: no view asks for bricks any more (regression:
  // a view used to stay in the set until the session ended).
  request.reset();
  CHECK(set->viewRequests->views().empty());
  settle();
  CHECK(s.tilesets()[0]->statistics().chosenBricks == 0);
}

// bunny_small (3,000 splats) as a Gaussian tileset of K-splat bricks (512: depth 1, a
// merged root) with 2^cellsLog2 merged cells a node, written under the build folder in a
// folder named for `test` (ctest runs the cases at once: each writes its own); returns it.
fs::path bunnyGaussianTileset(const std::string& test, std::uint64_t brickVectors = 512,
                              std::uint8_t cellsLog2 = 4) {
  const std::string ply = test::readBytes(test::sourceDir() / "tests/data/splats/bunny_small.ply");
  const splats::GaussianCloud cloud = splats::readPlyGaussians(ply, "bunny_small.ply");
  qnv::TilesetOptions cut;
  cut.brickVectors = brickVectors;
  cut.mergedCellsLog2 = cellsLog2;
  const splats::GaussianTilesetFiles files = splats::buildGaussianTileset(cloud, cut);
  const fs::path dir = freshDir("bunny_small_gaussians_" + test);
  for (const qnv::BrickFile& b : files.bricks) {
    fs::create_directories((dir / b.brick.path()).parent_path());
    std::ofstream(dir / b.brick.path(), std::ios::binary) << b.bytes;
  }
  for (std::size_t i = 0, m = 0; i < files.index.bricks.size(); ++i)
    if (files.index.hasMerged(files.index.bricks[i].level)) {
      const fs::path path = dir / files.index.bricks[i].mergedPath();
      fs::create_directories(path.parent_path());
      std::ofstream(path, std::ios::binary) << files.merged[m++].second;
    }
  std::ofstream(dir / "index.qnvt", std::ios::binary) << qnv::serializeTilesetIndex(files.index);
  return dir;
}

TEST_CASE("tileset stream: a Gaussian tileset draws its splats and counts splats",
          "[tileset][session][splat]") {
  const fs::path dir = bunnyGaussianTileset("draws");
  // Near: every splat of every brick, and the Streams panel counts splats.
  const Loaded near = load(dir.string(), nullptr);
  CHECK(near.messages.empty());
  CHECK(near.splats == 3000);
  CHECK(near.vectors.empty());
  CHECK(near.mergedSplats == 0);
  CHECK(near.progress.vectors == 3000);
  CHECK(near.progress.expectedVectors == 3000);
  CHECK(near.progress.fraction() == 1.0);
  CHECK(near.progress.bytesPerSecond > 0.0);  // the bricks' bytes over their transfers' time
  // Settled means the level-of-detail tree over the set's splats is attached: each view
  // draws its cut.
  CHECK(near.treeSplats == 3000);
  // Far: the merged root stands for the scene, a few hundred splats and no brick.
  const Loaded far = load(dir.string(), nullptr, {}, 40.0f);
  CHECK(far.messages.empty());
  CHECK(far.splats == 0);
  CHECK(far.mergedSplats > 100);
  CHECK(far.mergedSplats < 3000);
  CHECK(far.stats.brickBytes == 0);
  // The merged Gaussians have a tree of their own (merged further below a pixel).
  CHECK(far.mergedTreeSplats == far.mergedSplats);
}

TEST_CASE("tileset stream: a deep Gaussian tileset draws merged bricks below level 1",
          "[tileset][session][splat]") {
  // K = 8: depth 3; 32^3 cells a node, so qnv::deepestMergedLevel is 1, yet level 2 has
  // merged bricks too (the index's mergedEveryLevel). Levels 0 and 1 have at most 1 + 8
  // nodes, so a choice of more than 8 merged nodes holds level 2's (3 times the fitting
  // distance: 45 nodes; 6 times: level 1's 8; 2 times: the leaves' splats).
  const fs::path dir = bunnyGaussianTileset("deep", 8, 5);
  session::TilesetOptions options;
  options.mergedTreeOnThisThread = 0;  // every merged set's tree on a thread of its own
  bool deep = false;
  for (const float scale : {2.0f, 3.0f, 6.0f}) {
    INFO("distance scale " << scale);
    const Loaded l = load(dir.string(), nullptr, {}, scale, &options);
    CHECK(l.messages.empty());
    if (l.stats.chosenMerged == 0) continue;
    // Settled waits for the merged set's tree built on its own thread.
    CHECK(l.mergedTreeSplats == l.mergedSplats);
    if (l.stats.chosenMerged > 8 && l.splats == 0) {
      deep = true;
      CHECK(l.stats.brickBytes == 0);
      CHECK(l.mergedSplats < 3000);
    }
  }
  CHECK(deep);
}

TEST_CASE("tileset stream: a Gaussian tileset's memory budget counts the splats' tree too",
          "[tileset][session][splat]") {
  const fs::path dir = bunnyGaussianTileset("budget");
  // bunny_small's splats (SH degree 1) decode to 92 bytes each, and their share of the
  // level-of-detail tree is 4 + 0.34 (44 + 92) = 50 more: 142 bytes, so this budget holds
  // 1,500 of the 3,000 splats (2,315 at their decoded size alone).
  session::TilesetOptions options;
  options.memoryBytes = 1500 * 142;
  const Loaded near = load(dir.string(), nullptr, {}, 1.0f, &options);
  CHECK(near.messages.empty());
  INFO(near.splats);
  CHECK(near.splats > 1000);
  CHECK(near.splats <= 1500 + 128);  // whole packets of 128 splats may pass it by less than one
  CHECK(near.treeSplats == near.splats);
}

namespace {

/// A session that has opened the tileset in `dir` and settled on it: its set, a view that
/// fits it (512 pixels high), and that view's request to update.
struct OpenTileset {
  explicit OpenTileset(const fs::path& dir, const session::TilesetOptions& options = {}) {
    s.setTilesetOptions(options);
    std::string error;
    REQUIRE(s.open(dir.string(), error));
    set = s.rendererOptions({}).splatLoader(dir.string(), "", error);
    REQUIRE(set);
    settle();
    view.camera = scene::fitCamera(set->bounds, 1.0f, scene::Camera{});
    view.heightPixels = 512;
    view.vectors = set->total();
    request = set->viewRequests->request();
  }
  /// Pumps until the session has settled.
  void settle() {
    for (int i = 0; i < 100000 && !(s.pump(), s.settled() && !set->bounds.empty()); ++i)
      s.loader().wait(0.01);
  }
  session::StreamingSession s;
  std::shared_ptr<const render::SplatSet> set;
  render::SplatSet::View view;
  decltype(set->viewRequests->request()) request;
};

}  // namespace

TEST_CASE("tileset stream: merged bricks no view draws are let go under the memory budget",
          "[tileset][session][splat]") {
  // The deep tileset above: from 3 times the fitting distance 45 merged nodes (2,994 merged
  // splats), from 6 the 8 of level 1, from 12 the root's. A budget of 2,000 bunny splats
  // (142 bytes each) holds the first choice but not all three.
  const fs::path dir = bunnyGaussianTileset("evicted", 8, 5);
  std::uint64_t resident[2] = {0, 0};
  for (const bool tight : {false, true}) {
    INFO((tight ? "tight" : "unbounded") << " budget");
    session::TilesetOptions options;
    if (tight) options.memoryBytes = 2000 * 142;
    OpenTileset t(dir, options);
    const scene::Camera fitted = t.view.camera;
    const auto& set = t.set;
    for (const float scale : {3.0f, 6.0f, 12.0f}) {
      t.view.camera = fitted;
      t.view.camera.position =
          set->bounds.center() + (fitted.position - set->bounds.center()) * scale;
      t.request->update(t.view);
      t.settle();
      CHECK(set->merged->size() > 0);
      CHECK(set->gaussians->empty());
    }
    const session::TilesetStatistics stats = t.s.tilesets()[0]->statistics();
    CHECK((stats.evictedMerged > 0) == tight);
    resident[tight] = stats.residentVectors;
  }
  // Unbounded, every merged brick fetched stays (those of levels 0 to 2); held to the
  // budget, those of the last views only.
  CHECK(resident[1] < resident[0]);
}

TEST_CASE("tileset stream: a view that moves without changing the choice keeps the tree",
          "[tileset][session][splat]") {
  OpenTileset t(bunnyGaussianTileset("moves"));
  const auto& set = t.set;
  t.request->update(t.view);
  t.settle();
  const std::shared_ptr<const splats::LodTree> tree = set->lodTree;
  REQUIRE(tree);
  const auto cloud = set->gaussians;
  // Near, every splat is chosen from anywhere about as close: a step sideways changes
  // nothing the set is made of, so neither its splats nor their tree are made again.
  t.view.camera.position += 0.01f * glm::length(set->bounds.size()) * glm::vec3(1, 0, 0);
  t.request->update(t.view);
  t.settle();
  CHECK(set->gaussians == cloud);
  CHECK(set->lodTree == tree);
}
