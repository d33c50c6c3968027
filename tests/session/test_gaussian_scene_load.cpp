// A Gaussian splatting scene file opened in a session is read in the background
// (session/src/gaussian_scene_load.hpp): the set the renderer gets is empty until a pump
// attaches the decoded splats, then their level-of-detail tree; the session is not settled
// before. A damaged file's set says why (SplatSet::loadError). Over HTTP the scene is
// fetched without blocking and up to the loader's resource limit, not a texture's.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "http/nginx_server.hpp"
#include "render/splat_renderer.hpp"
#include "session/streaming_session.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

fs::path splatData(const char* file) {
  return gs::test::sourceDir() / "tests/data/splats" / file;
}

/// A session that opened `input` (a path or URL) and the splat set of its scene.
struct OpenedScene {
  gs::session::StreamingSession session;
  std::shared_ptr<const gs::render::SplatSet> set;

  explicit OpenedScene(const std::string& input, gs::net::LoaderOptions options = {})
      : session(options) {
    std::string error;
    REQUIRE(session.open(input, error));
    set = session.rendererOptions({}).splatLoader(input, "", error);
    REQUIRE(set);
  }
  /// Pumps until the session settles (at most about 100 s); whether it did.
  bool settle() {
    for (int i = 0; i < 10000; ++i) {
      session.pump();
      if (session.settled()) return true;
      session.loader().wait(0.01);
    }
    return false;
  }
};

/// bunny_small.spz read whole and sorted, as the scene's set must hold it.
gs::splats::GaussianCloud expectedBunny() {
  const fs::path spz = splatData("bunny_small.spz");
  return gs::splats::sortByImportance(gs::splats::readGaussians(
      gs::test::readBytes(spz), spz.string(), gs::splats::SideFileReader{}));
}

void checkBunny(const gs::render::SplatSet& set) {
  const gs::splats::GaussianCloud expected = expectedBunny();
  REQUIRE(set.gaussians);
  REQUIRE(set.gaussians->size() == expected.size());
  CHECK(set.gaussians->positions == expected.positions);
  CHECK(set.gaussians->shRest == expected.shRest);
  CHECK_FALSE(set.bounds.empty());
  REQUIRE(set.lodTree);  // settled means the tree is attached
  CHECK(set.lodTree->splatCount == expected.size());
  CHECK(set.loadError.empty());
}

}  // namespace

TEST_CASE("a splat scene file is read in the background then gets its tree", "[session][splat]") {
  OpenedScene scene(splatData("bunny_small.spz").string());
  // Nothing is attached before a pump: the thread that draws never waited for the file.
  CHECK_FALSE(scene.set->gaussians);
  CHECK(scene.set->size() == 0);
  CHECK_FALSE(scene.session.settled());
  REQUIRE(scene.settle());
  checkBunny(*scene.set);
}

TEST_CASE("a damaged splat scene file gives a set that says why", "[session][splat]") {
  gs::test::TempDir dir("gaussian_scene_load_bad");
  const std::string bytes = gs::test::readBytes(splatData("bunny_small.ply"));
  OpenedScene scene(dir.write("cut.ply", bytes.substr(0, bytes.size() / 2)));
  REQUIRE(scene.settle());
  CHECK_FALSE(scene.set->gaussians);
  CHECK_THAT(scene.set->loadError, Catch::Contains("cut.ply") && Catch::Contains("expected"));
}

TEST_CASE("a splat scene over HTTP is fetched without blocking under the resource limit",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  nginx.writeFile("bunny.spz", gs::test::readBytes(splatData("bunny_small.spz")));
  {
    OpenedScene scene(nginx.url("/bunny.spz"));
    CHECK_FALSE(scene.set->gaussians);
    REQUIRE(scene.settle());
    checkBunny(*scene.set);
  }
  // The loader's limit on one resource applies (LoaderOptions::maxResourceBytes), naming
  // the URL.
  gs::net::LoaderOptions small;
  small.maxResourceBytes = 1000;
  OpenedScene scene(nginx.url("/bunny.spz"), small);
  REQUIRE(scene.settle());
  CHECK_FALSE(scene.set->gaussians);
  CHECK_THAT(scene.set->loadError, Catch::Contains("/bunny.spz"));
}

TEST_CASE("a capture PLY over HTTP is drawn while its rows arrive", "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  const fs::path ply = splatData("bunny_small.ply");  // 3,000 rows of 62 floats
  nginx.writeFile("bunny.ply", gs::test::readBytes(ply));
  gs::net::LoaderOptions slow;
  slow.maxRate = 150000;  // bytes a second: about 2 s for its 276 KB
  OpenedScene scene(nginx.url("/bunny.ply"), slow);
  // Splats in file order while the rest arrives, the scene's count expected.
  bool sawPart = false;
  for (int i = 0; i < 10000 && !scene.session.settled(); ++i) {
    scene.session.pump();
    const auto& set = *scene.set;
    if (set.gaussians && set.size() > 0 && set.size() < 3000) {
      sawPart = true;
      CHECK(set.expectedVectors == 3000);
      CHECK_FALSE(set.lodTree);
    }
    scene.session.loader().wait(0.01);
  }
  CHECK(sawPart);
  REQUIRE(scene.settle());
  const gs::splats::GaussianCloud expected = gs::splats::sortByImportance(
      gs::splats::readGaussians(gs::test::readBytes(ply), ply.string(), {}));
  REQUIRE(scene.set->gaussians);
  CHECK(scene.set->gaussians->positions == expected.positions);
  CHECK(scene.set->gaussians->shRest == expected.shRest);
  CHECK(scene.set->expectedVectors == 0);
  CHECK(scene.set->lodTree);
  // A capture cut short: the rows that came are no scene, the set says why.
  const std::string bytes = gs::test::readBytes(ply);
  nginx.writeFile("cut.ply", bytes.substr(0, bytes.size() - 1000));
  OpenedScene cut(nginx.url("/cut.ply"));
  REQUIRE(cut.settle());
  CHECK_THAT(cut.set->loadError, Catch::Contains("/cut.ply") && Catch::Contains("expected"));
}
