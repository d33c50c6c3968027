// A Gaussian splatting scene file opened in a session is read in the background
// (session/src/gaussian_scene_load.hpp): the set the renderer gets is empty until a pump
// attaches the decoded splats, then their level-of-detail tree; the session is not settled
// before. A damaged file's set says why (SplatSet::loadError). Over HTTP the scene is
// fetched without blocking and up to the loader's resource limit, not a texture's.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "base/byte_order.hpp"
#include "base/gzip.hpp"
#include "http/fault_server.hpp"
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
  /// The scene's line of the session's progress (the Streams panel's), by its URL's end.
  gs::net::StreamProgress line(const std::string& name) const {
    gs::net::StreamProgress found;
    int lines = 0;
    for (const gs::net::StreamProgress& p : session.progress())
      if (p.kind == gs::net::StreamKind::splats && p.url.ends_with(name)) {
        found = p;
        ++lines;
      }
    CHECK(lines == 1);
    return found;
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

/// Pumps `scene` (of the file `name` whose splats are `whole`, with SH) until it settles,
/// checking each set drawn before every splat came: in file order, with all they hold (the
/// last one's position, rotation, scale and an SH coefficient the whole reader's), the
/// scene's count expected, its line of the Streams panel loading with fewer bytes than
/// the file's. Whether such a set was seen.
bool sawPartialSets(OpenedScene& scene, const gs::splats::GaussianCloud& whole,
                    const std::string& name, std::uint64_t fileBytes) {
  bool sawPart = false;
  for (int i = 0; i < 10000 && !scene.session.settled(); ++i) {
    scene.session.pump();
    const auto& set = *scene.set;
    if (set.gaussians && set.size() > 0 && set.size() < whole.size()) {
      sawPart = true;
      CHECK(set.expectedVectors == whole.size());
      const gs::splats::GaussianCloud& part = *set.gaussians;
      CHECK(part.shDegree == whole.shDegree);
      const std::size_t last = part.size() - 1;
      CHECK(part.positions[last] == whole.positions[last]);
      CHECK(part.rotations[last] == whole.rotations[last]);
      CHECK(part.scales[last] == whole.scales[last]);
      const std::size_t rest = static_cast<std::size_t>(whole.shRestPerSplat());
      CHECK(part.shRest[rest * last + rest - 1] == whole.shRest[rest * last + rest - 1]);
      const gs::net::StreamProgress p = scene.line(name);
      CHECK(p.state == gs::net::StreamState::loading);
      CHECK(p.bytes < fileBytes);
    }
    scene.session.loader().wait(0.01);
  }
  return sawPart;
}

/// Settles `scene` and checks that its set is `whole` sorted by importance, with its tree
/// and no error.
void checkSettledAs(OpenedScene& scene, const gs::splats::GaussianCloud& whole) {
  REQUIRE(scene.settle());
  const gs::splats::GaussianCloud expected = gs::splats::sortByImportance(whole);
  REQUIRE(scene.set->gaussians);
  CHECK(scene.set->loadError.empty());
  CHECK(scene.set->gaussians->positions == expected.positions);
  CHECK(scene.set->gaussians->shRest == expected.shRest);
  CHECK(scene.set->lodTree);
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
  // The Streams panel's line: every splat in, a local file's bytes not counted.
  const gs::net::StreamProgress p = scene.line("bunny_small.spz");
  CHECK(p.state == gs::net::StreamState::done);
  CHECK(p.vectors == scene.set->size());
  CHECK(p.expectedVectors == scene.set->size());
  CHECK(p.fraction() == 1.0);
  CHECK(p.bytes == 0);
  CHECK(p.stage.empty());
}

TEST_CASE("a damaged splat scene file gives a set that says why", "[session][splat]") {
  gs::test::TempDir dir("gaussian_scene_load_bad");
  const std::string bytes = gs::test::readBytes(splatData("bunny_small.ply"));
  OpenedScene scene(dir.write("cut.ply", bytes.substr(0, bytes.size() / 2)));
  REQUIRE(scene.settle());
  CHECK_FALSE(scene.set->gaussians);
  CHECK_THAT(scene.set->loadError, Catch::Contains("cut.ply") && Catch::Contains("expected"));
  const gs::net::StreamProgress p = scene.line("cut.ply");
  CHECK(p.state == gs::net::StreamState::failed);
  CHECK(p.error == scene.set->loadError);
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
    const gs::net::StreamProgress p = scene.line("/bunny.spz");
    CHECK(p.state == gs::net::StreamState::done);
    CHECK(p.bytes == fs::file_size(splatData("bunny_small.spz")));
    CHECK(p.expectedBytes == static_cast<std::int64_t>(p.bytes));
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
      // The Streams panel's line: the splats drawn of the scene's, the bytes that came.
      const gs::net::StreamProgress p = scene.line("/bunny.ply");
      CHECK(p.state == gs::net::StreamState::loading);
      CHECK(p.vectors == set.size());
      CHECK(p.expectedVectors == 3000);
      CHECK(p.fraction() < 1.0);
      CHECK(p.bytes > 0);
      CHECK(p.expectedBytes == static_cast<std::int64_t>(fs::file_size(ply)));
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

TEST_CASE("a compressed PLY over HTTP is previewed while its vertex records arrive",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  // 3,000 vertex records of 16 bytes, then 3,000 sh records of 9 (SH band 1).
  const fs::path ply = splatData("bunny_small.compressed.ply");
  const std::string bytes = gs::test::readBytes(ply);
  nginx.writeFile("bunny.compressed.ply", bytes);
  gs::net::LoaderOptions slow;
  slow.maxRate = 30000;  // bytes a second: about 2.5 s for its 77 KB
  OpenedScene scene(nginx.url("/bunny.compressed.ply"), slow);
  const gs::splats::GaussianCloud whole =
      gs::splats::readGaussians(bytes, ply.string(), gs::splats::SideFileReader{});
  // Splats in file order before the SH arrive: positions, shapes and colours exact, no SH.
  bool sawPart = false;
  for (int i = 0; i < 10000 && !scene.session.settled(); ++i) {
    scene.session.pump();
    const auto& set = *scene.set;
    if (set.gaussians && set.size() > 0 && !set.lodTree && set.expectedVectors == 3000) {
      sawPart |= set.size() < 3000;
      const gs::splats::GaussianCloud& part = *set.gaussians;
      CHECK(part.shDegree == 0);
      const std::size_t last = part.size() - 1;
      CHECK(part.positions[last] == whole.positions[last]);
      CHECK(part.scales[last] == whole.scales[last]);
      CHECK(part.shDc[last] == whole.shDc[last]);
      CHECK(part.opacities[last] == whole.opacities[last]);
    }
    scene.session.loader().wait(0.01);
  }
  CHECK(sawPart);
  REQUIRE(scene.settle());
  // Then the whole file: every splat with its SH, sorted as a local file's.
  const gs::splats::GaussianCloud expected = gs::splats::sortByImportance(whole);
  REQUIRE(scene.set->gaussians);
  CHECK(scene.set->gaussians->shDegree == 1);
  CHECK(scene.set->gaussians->positions == expected.positions);
  CHECK(scene.set->gaussians->shRest == expected.shRest);
  CHECK(scene.set->lodTree);
  // Cut in its sh records: the preview's splats stay drawn, the set says why.
  nginx.writeFile("cut.compressed.ply", bytes.substr(0, bytes.size() - 1000));
  OpenedScene cut(nginx.url("/cut.compressed.ply"));
  REQUIRE(cut.settle());
  CHECK_THAT(cut.set->loadError, Catch::Contains("/cut.compressed.ply"));
  REQUIRE(cut.set->gaussians);
  CHECK(cut.set->size() == 3000);
}

TEST_CASE("an SPZ v4 over HTTP is drawn while its columns arrive side by side",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  // Six zstd streams (positions, alphas, colours, scales, rotations, SH band 1).
  const fs::path spz = splatData("bunny_small.spz");
  const std::string bytes = gs::test::readBytes(spz);
  nginx.writeFile("bunny.spz", bytes);
  gs::net::LoaderOptions slow;
  slow.maxRate = 16000;  // bytes a second: about 2.5 s for its 41 KB
  OpenedScene scene(nginx.url("/bunny.spz"), slow);
  const gs::splats::GaussianCloud whole = gs::splats::readGaussians(bytes, spz.string(), {});
  // Splats in file order with all they hold, SH too, while the rest arrives.
  CHECK(whole.shDegree == 1);
  CHECK(sawPartialSets(scene, whole, "/bunny.spz", bytes.size()));
  REQUIRE(scene.settle());
  CHECK(scene.line("/bunny.spz").expectedBytes == static_cast<std::int64_t>(bytes.size()));
  checkBunny(*scene.set);
  // Every byte fetched once: the head, then each column's rest.
  CHECK(scene.line("/bunny.spz").bytes == bytes.size());
  // The last stream damaged at its end: the set says why, naming the URL and the stream.
  std::string bad = bytes;
  bad[bad.size() - 2] ^= 0x5a;
  bad[bad.size() - 1] ^= 0x5a;
  nginx.writeFile("bad.spz", bad);
  OpenedScene damaged(nginx.url("/bad.spz"), slow);
  REQUIRE(damaged.settle());
  CHECK_THAT(damaged.set->loadError, Catch::Contains("/bad.spz") && Catch::Contains("stream 5"));
}

TEST_CASE("an SPZ v3 over HTTP is drawn while its gzip data arrive", "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  // The bunny's v3 file with SH that vary, as a capture's (its own are all zero: a few
  // bytes at the end of its gzip data): positions, alphas, colours, scales and rotations
  // come first (20 bytes a splat), then the SH (9), which give the splats one by one.
  std::string v3 = gs::base::gunzip(gs::test::readBytes(splatData("bunny_small_v3.spz")), 1 << 24);
  gs::test::fillPseudoRandom(v3, 16 + 3000 * 20, 99);
  const std::string bytes = gs::test::gzip(v3);
  nginx.writeFile("bunny_v3.spz", bytes);
  gs::net::LoaderOptions slow;
  slow.maxRate = 25000;  // bytes a second: about 2.5 s for its 64 KB
  OpenedScene scene(nginx.url("/bunny_v3.spz"), slow);
  const gs::splats::GaussianCloud whole = gs::splats::readGaussians(bytes, "bunny_v3.spz", {});
  CHECK(whole.shDegree == 1);
  CHECK(sawPartialSets(scene, whole, "/bunny_v3.spz", bytes.size()));
  checkSettledAs(scene, whole);
  // Cut in its SH: the splats that came stay drawn, the set says why, naming the URL.
  nginx.writeFile("cut_v3.spz", bytes.substr(0, bytes.size() - 5000));
  OpenedScene cut(nginx.url("/cut_v3.spz"));
  REQUIRE(cut.settle());
  CHECK_THAT(cut.set->loadError, Catch::Contains("/cut_v3.spz: corrupt gzip data: truncated"));
  REQUIRE(cut.set->gaussians);
  CHECK(cut.set->size() > 0);
  CHECK(cut.set->size() < 3000);
}

TEST_CASE("a GLB capture over HTTP is drawn while its accessors arrive side by side",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  const fs::path glb = splatData("bunny_small.glb");  // 3,000 splats, SH band 1, 290 KB
  const std::string bytes = gs::test::readBytes(glb);
  nginx.writeFile("bunny.glb", bytes);
  gs::net::LoaderOptions slow;
  slow.maxRate = 100000;  // bytes a second: about 2.5 s for what it fetches
  OpenedScene scene(nginx.url("/bunny.glb"), slow);
  const gs::splats::GaussianCloud whole = gs::splats::readGaussians(bytes, glb.string(), {});
  CHECK(whole.shDegree == 1);
  CHECK(sawPartialSets(scene, whole, "/bunny.glb", bytes.size()));
  checkSettledAs(scene, whole);
  // No byte fetched twice (its COLOR_0, which the DC stands in for, is not fetched at all
  // unless the head already held it).
  CHECK(scene.line("/bunny.glb").bytes <= bytes.size());
}

TEST_CASE("a .gltf capture over HTTP is drawn while its buffer file arrives",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  // bunny_small.glb as a .gltf whose buffer is a file beside it, in a folder of its own.
  const std::string glb = gs::test::readBytes(splatData("bunny_small.glb"));
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  const std::string bin = glb.substr(20 + jsonLength + 8);
  const auto gltfNaming = [&](const std::string& uri, std::uint64_t byteLength) {
    std::string json = glb.substr(20, jsonLength);
    const std::string from = "\"buffers\":[{\"byteLength\":288000}]";
    REQUIRE(json.find(from) != std::string::npos);
    json.replace(json.find(from), from.size(),
                 "\"buffers\":[{\"byteLength\":" + std::to_string(byteLength) + ",\"uri\":\"" +
                     uri + "\"}]");
    return json;
  };
  const std::string json = gltfNaming("buffers/bunny%20small.bin", bin.size());
  nginx.writeFile("capture/bunny.gltf", json);
  nginx.writeFile("capture/buffers/bunny small.bin", bin);
  gs::net::LoaderOptions slow;
  slow.maxRate = 100000;  // bytes a second: about 2.5 s for what it fetches
  OpenedScene scene(nginx.url("/capture/bunny.gltf"), slow);
  const gs::splats::GaussianCloud whole = gs::splats::readGaussians(
      gs::test::readBytes(splatData("bunny_small.glb")), "bunny_small.glb", {});
  CHECK(sawPartialSets(scene, whole, "/bunny.gltf", json.size() + bin.size()));
  checkSettledAs(scene, whole);
  // The buffer file's columns by range requests, none of it read whole.
  // (nginx logs the URI decoded.)
  int ranges = 0;
  for (const std::string& line : nginx.accessLog(2)) {
    CHECK_FALSE(line.starts_with("GET /capture/buffers/bunny small.bin 200"));
    ranges += line.starts_with("GET /capture/buffers/bunny small.bin 206");
  }
  CHECK(ranges == 8);  // one a column
  CHECK(scene.line("/bunny.gltf").bytes <= json.size() + bin.size());
  // A buffer file shorter than its byteLength: the set says so, naming both.
  nginx.writeFile("capture/long.gltf", gltfNaming("buffers/bunny%20small.bin", bin.size() + 4));
  OpenedScene longer(nginx.url("/capture/long.gltf"));
  REQUIRE(longer.settle());
  CHECK_THAT(longer.set->loadError, Catch::Contains("/capture/long.gltf") &&
                                        Catch::Contains("bunny%20small.bin") &&
                                        Catch::Contains("expected 288004 bytes, got 288000"));
  // One outside the scene's folder is refused as the whole reader refuses it.
  nginx.writeFile("outside.bin", bin);
  nginx.writeFile("capture/outside.gltf", gltfNaming("../outside.bin", bin.size()));
  OpenedScene outside(nginx.url("/capture/outside.gltf"));
  REQUIRE(outside.settle());
  CHECK_THAT(outside.set->loadError, Catch::Contains("not a file beside the scene"));
}

TEST_CASE("an SOG meta.json over HTTP is drawn while its WebP images arrive",
          "[session][splat][http]") {
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  std::uint64_t total = 0;
  for (const fs::path& f : fs::directory_iterator(splatData("bunny_small_sog"))) {
    nginx.writeFile("sog/" + f.filename().string(), gs::test::readBytes(f));
    total += fs::file_size(f);
  }
  const fs::path meta = splatData("bunny_small_sog/meta.json");
  gs::net::LoaderOptions slow;
  slow.maxRate = 20000;  // bytes a second: about 2.5 s for its 53 KB
  OpenedScene scene(nginx.url("/sog/meta.json"), slow);
  const gs::splats::GaussianCloud whole =
      gs::splats::readGaussians(gs::test::readBytes(meta), meta.string(),
                                [](const std::string& file, std::string& out, std::string&) {
                                  out = gs::test::readBytes(splatData("bunny_small_sog") / file);
                                  return !out.empty();
                                });
  CHECK(sawPartialSets(scene, whole, "/meta.json", total));
  checkSettledAs(scene, whole);
  // Each image fetched once, whole (no range).
  int images = 0;
  for (const std::string& line : nginx.accessLog(2))
    if (line.find(".webp 200") != std::string::npos) ++images;
  CHECK(images == 7);
  CHECK(scene.line("/meta.json").bytes == total);
  // An image cut short: the set says so, naming the scene and the image.
  nginx.writeFile("cut/meta.json", gs::test::readBytes(meta));
  for (const fs::path& f : fs::directory_iterator(splatData("bunny_small_sog"))) {
    const std::string bytes = gs::test::readBytes(f);
    if (f.extension() == ".webp")
      nginx.writeFile("cut/" + f.filename().string(),
                      f.filename() == "quats.webp" ? bytes.substr(0, bytes.size() / 2) : bytes);
  }
  OpenedScene cut(nginx.url("/cut/meta.json"));
  REQUIRE(cut.settle());
  CHECK_THAT(cut.set->loadError,
             Catch::Contains("/cut/meta.json: 'quats.webp': damaged WebP data"));
}

TEST_CASE("a remote SPZ's splats come long before its end", "[session][splat][http]") {
  // CThead (122,000 splats, 2.8 MB): its alphas are one zstd block of 122,000 bytes, so
  // they come first; then each of the other streams gives its splats a block at a time.
  if (!gs::test::haveCorpus("splat")) return;
  gs::test::NginxServer nginx;
  if (!nginx.ok()) return;
  const std::string bytes = gs::test::readBytes(gs::test::corpusDir() / "splat/cthead.spz");
  nginx.writeFile("cthead.spz", bytes);
  gs::net::LoaderOptions slow;
  slow.maxRate = 2000000;  // bytes a second: about 1.4 s for its 2.8 MB
  OpenedScene scene(nginx.url("/cthead.spz"), slow);
  std::uint64_t firstAt = 0;  // bytes that had come when the first splats were drawn
  for (int i = 0; i < 10000 && !scene.session.settled() && firstAt == 0; ++i) {
    scene.session.pump();
    if (scene.set->size() > 0) firstAt = scene.line("/cthead.spz").bytes;
    scene.session.loader().wait(0.01);
  }
  INFO("first splats at " << firstAt << " of " << bytes.size() << " bytes");
  CHECK(firstAt > 0);
  CHECK(firstAt < bytes.size() / 2);
  REQUIRE(scene.settle());
  CHECK(scene.set->size() == 122000);
  CHECK(scene.set->loadError.empty());
}

TEST_CASE("a remote SPZ from a server that ignores ranges is read once whole",
          "[session][splat][http]") {
  // Its first column's range request is answered with the whole file: the columns stop
  // and one transfer reads the file (not six transfers each up to their column).
  const std::string bytes = gs::test::readBytes(splatData("bunny_small.spz"));
  gs::test::FaultServer::Config config;
  config.body = bytes;
  config.plan = {gs::test::FaultServer::Behaviour::ignoreRanges};
  config.bytesPerSecond = 20000;  // about 2 s for its 41 KB
  gs::test::FaultServer server(config);
  REQUIRE(server.ok());
  OpenedScene scene(server.url("/bunny.spz"));
  REQUIRE(scene.settle());
  checkBunny(*scene.set);
  // The first whole answer, the columns' (stopped at once), and the whole read.
  CHECK(server.requests().size() <= 8);
  CHECK(scene.line("/bunny.spz").bytes == bytes.size());
  // Every byte received counts, those dropped before a range too: about the file once
  // (each column reading up to itself would be about three times it).
  CHECK(scene.session.loader().budget().totalBytes() < bytes.size() * 3 / 2);
}
