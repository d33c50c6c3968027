// Progressive loading end to end (docs/progressive-loading.md): the real ghostspace
// executable against a real nginx on loopback and against the tests' own fault server.
// Every run must end: a partial picture and a clear error, never a hang or a crash.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/gzip.hpp"
#include "baseline.hpp"
#include "http/fault_server.hpp"
#include "http/nginx_server.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using gs::test::FaultServer;
using gs::test::NginxServer;
using gs::test::runGhostspace;

namespace {

fs::path outDir() {
  const fs::path d = fs::path(GS_BINARY_DIR) / "progressive-actual";
  fs::create_directories(d);
  return d;
}

/// Runs a snapshot of `input` into outDir()/name.png; returns the process result.
gs::test::ProcessResult shoot(const std::string& name, const std::string& input,
                              std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"--snapshot", (outDir() / (name + ".png")).string(), "--size",
                                   "200x150", "--no-progress"};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(input);
  return runGhostspace(args);
}

double differing(const std::string& a, const std::string& b, int tolerance = 2) {
  return gs::test::fractionDiffering((outDir() / (a + ".png")).string(),
                                     (outDir() / (b + ".png")).string(), tolerance);
}

/// Fraction of pixels that are not the background colour of the top-left pixel.
double covered(const std::string& name) {
  const gs::render::Image image = gs::render::readPng((outDir() / (name + ".png")).string());
  std::size_t n = 0;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t i = 0; i < pixels; ++i)
    for (int c = 0; c < 3; ++c)
      if (image.rgba[i * 4 + c] != image.rgba[c]) {
        ++n;
        break;
      }
  return static_cast<double>(n) / static_cast<double>(pixels);
}

/// A world of `count` boxes side by side, each its own top-level Shape.
std::string boxesWorld(int count) {
  std::string w = "#VRML V2.0 utf8\nViewpoint { position 0 0 16 }\n";
  for (int i = 0; i < count; ++i)
    w += "Transform { translation " + std::to_string(i * 2 - count + 1) +
         " 0 0 children Shape { appearance Appearance { material Material { diffuseColor 1 0.5 "
         "0.2 } } geometry Box { size 1.8 1.8 1.8 } } }\n";
  return w;
}

/// A raw 8-bit volume of n^3 voxels: a ball with a soft edge (for streams of many vectors).
std::string ballVolume(int n) {
  std::string v(static_cast<std::size_t>(n) * n * n, '\0');
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double dx = x - n / 2.0, dy = y - n / 2.0, dz = z - n / 2.0;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz) / (n / 2.0);
        v[(static_cast<std::size_t>(z) * n + y) * n + x] = static_cast<char>(
            static_cast<unsigned char>(std::clamp(255.0 * (1.2 - r), 0.0, 255.0)));
      }
  return v;
}

/// Encodes ballVolume(48) into outDir()/name (about 110,000 vectors, 0.9 MB).
std::string ballStream(const std::string& name) {
  const fs::path raw = outDir() / (name + ".raw"), qnv = outDir() / name;  // one per test
  std::ofstream(raw, std::ios::binary) << ballVolume(48);
  const auto r = runGhostspace(
      {"encode", raw.string(), "--raw-dims", "48,48,48", "-o", qnv.string(), "--no-progress"});
  REQUIRE(r.exitCode == 0);
  return gs::test::readBytes(qnv);
}

fs::path worldsDir() {
  return gs::test::sourceDir() / "assets/worlds";
}

}  // namespace

TEST_CASE("a world, its Inline and textures load over HTTP as from files", "[app][http]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  for (const auto& e : fs::recursive_directory_iterator(worldsDir()))
    if (e.is_regular_file())
      nginx.writeFile(fs::relative(e.path(), worldsDir()).string(), gs::test::readBytes(e.path()));
  const auto local = shoot("features_local", (worldsDir() / "features.wrl").string());
  REQUIRE(local.exitCode == 0);
  const auto remote = shoot("features_http", nginx.url("/features.wrl"));
  INFO(remote.err);
  REQUIRE(remote.exitCode == 0);
  CHECK(differing("features_local", "features_http", 0) == 0.0);
  // The Inline came from the server too, not from the local folder.
  bool inlineFetched = false;
  for (const std::string& line : nginx.accessLog(2))
    inlineFetched |= line.find("/inline_part.wrl") != std::string::npos;
  CHECK(inlineFetched);
}

TEST_CASE("gzip worlds stream: .wrl.gz bytes and gzip Content-Encoding", "[app][http]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  const std::string world = boxesWorld(5);
  nginx.writeFile("boxes.wrl", world);
  const fs::path gz = outDir() / "boxes.wrl.gz";
  {
    // The test's own gzip of the world, by the ghostspace-independent zlib CLI.
    std::ofstream(outDir() / "boxes.wrl", std::ios::binary) << world;
    REQUIRE(std::system(("gzip -kf '" + (outDir() / "boxes.wrl").string() + "'").c_str()) == 0);
  }
  nginx.writeFile("boxes.wrl.gz", gs::test::readBytes(gz));
  REQUIRE(shoot("boxes_local", (outDir() / "boxes.wrl").string()).exitCode == 0);
  REQUIRE(shoot("boxes_gzfile", nginx.url("/boxes.wrl.gz")).exitCode == 0);
  REQUIRE(shoot("boxes_encoded", nginx.url("/gz/boxes.wrl")).exitCode == 0);
  CHECK(covered("boxes_local") > 0.02);
  CHECK(differing("boxes_local", "boxes_gzfile", 0) == 0.0);
  CHECK(differing("boxes_local", "boxes_encoded", 0) == 0.0);
  bool encoded = false;
  for (const std::string& line : nginx.accessLog(3))
    encoded |= line.find("/gz/boxes.wrl") != std::string::npos &&
               line.find("\"gzip\"") != std::string::npos;
  CHECK(encoded);
}

TEST_CASE("a QNV stream over HTTP fetches only the prefix its level of detail draws",
          "[app][http][qnv]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  const fs::path qnv = outDir() / "ball.qnv";
  const std::string bytes = ballStream("ball.qnv");
  nginx.writeFile("sphere.qnv", bytes);
  INFO(bytes.size() << " bytes");
  REQUIRE(shoot("sphere_local_lod", qnv.string(), {"--lod", "0.1"}).exitCode == 0);
  const auto r = shoot("sphere_http_lod", nginx.url("/sphere.qnv"), {"--lod", "0.1"});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(differing("sphere_local_lod", "sphere_http_lod", 0) == 0.0);
  // Range requests only (206), and far fewer bytes than the file.
  const auto log = nginx.accessLog(1);
  for (const std::string& line : log) {
    INFO(line);
    CHECK(line.find(" 206 ") != std::string::npos);
  }
  CHECK(NginxServer::bodyBytes(log) < bytes.size() / 2);
  // The whole stream: same picture as the local file.
  REQUIRE(shoot("sphere_local_all", qnv.string()).exitCode == 0);
  REQUIRE(shoot("sphere_http_all", nginx.url("/sphere.qnv")).exitCode == 0);
  CHECK(differing("sphere_local_all", "sphere_http_all", 0) == 0.0);
}

TEST_CASE("a Gaussian stream and tileset and PLY over HTTP are turned as the local capture is",
          "[app][http][qnv][splat]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  // Captures are y-down (docs/splats.md, "Axes"): a URL says nothing of the kind, so the
  // header's kind byte decides, as a local file's does.
  const fs::path ply = gs::test::sourceDir() / "tests/data/splats/bunny_small.ply";
  const fs::path qnv = outDir() / "bunny_small_http.qnv", tileset = outDir() / "bunny_small_http";
  REQUIRE(gs::test::runGhostspace({"encode", ply.string(), "-o", qnv.string()}).exitCode == 0);
  REQUIRE(gs::test::runGhostspace({"encode", ply.string(), "--tileset", tileset.string() + "/",
                                   "--brick-vectors", "512"})
              .exitCode == 0);
  nginx.writeFile("bunny.qnv", gs::test::readBytes(qnv));
  for (const auto& entry : fs::recursive_directory_iterator(tileset))
    if (entry.is_regular_file())
      nginx.writeFile("t/" + fs::relative(entry.path(), tileset).string(),
                      gs::test::readBytes(entry.path()));
  REQUIRE(shoot("bunny_qnv_local", qnv.string()).exitCode == 0);
  REQUIRE(shoot("bunny_tileset_local", (tileset / "index.qnvt").string()).exitCode == 0);
  const auto stream = shoot("bunny_qnv_http", nginx.url("/bunny.qnv"));
  INFO(stream.err);
  REQUIRE(stream.exitCode == 0);
  const auto index = shoot("bunny_tileset_http", nginx.url("/t/"));
  INFO(index.err);
  REQUIRE(index.exitCode == 0);
  CHECK(covered("bunny_qnv_local") > 0.05);
  CHECK(differing("bunny_qnv_local", "bunny_qnv_http", 0) == 0.0);
  CHECK(differing("bunny_tileset_local", "bunny_tileset_http", 0) == 0.0);
  // And the tileset shows what the stream shows.
  CHECK(differing("bunny_qnv_local", "bunny_tileset_local", 16) < 0.002);
  // A capture's own .ply over HTTP: its header says it is no mesh (one range request), and
  // it is the local file's picture; --snapshot-at draws the rows that came.
  nginx.writeFile("bunny.ply", gs::test::readBytes(ply));
  REQUIRE(shoot("bunny_ply_local", ply.string()).exitCode == 0);
  const auto remotePly = shoot("bunny_ply_http", nginx.url("/bunny.ply"));
  INFO(remotePly.err);
  REQUIRE(remotePly.exitCode == 0);
  CHECK(differing("bunny_ply_local", "bunny_ply_http", 0) == 0.0);
  const auto part = shoot("bunny_ply_part", nginx.url("/bunny.ply"), {"--snapshot-at", "60000"});
  INFO(part.err);
  CHECK(part.exitCode == 0);
  CHECK(covered("bunny_ply_part") > 0.0);
  CHECK(differing("bunny_ply_local", "bunny_ply_part", 16) > 0.01);
  // An SOG meta.json over HTTP: its images fetched beside it (off the drawing thread).
  const fs::path sog = gs::test::sourceDir() / "tests/data/splats/bunny_small_sog";
  for (const auto& entry : fs::directory_iterator(sog))
    nginx.writeFile("sog/" + entry.path().filename().string(), gs::test::readBytes(entry.path()));
  REQUIRE(shoot("bunny_sog_local", (sog / "meta.json").string()).exitCode == 0);
  const auto remoteSog = shoot("bunny_sog_http", nginx.url("/sog/meta.json"));
  INFO(remoteSog.err);
  REQUIRE(remoteSog.exitCode == 0);
  CHECK(covered("bunny_sog_local") > 0.05);
  CHECK(differing("bunny_sog_local", "bunny_sog_http", 0) == 0.0);
  // A glTF capture (.glb of KHR_gaussian_splatting primitives alone) over HTTP: its JSON
  // chunk, in the same range request, says it is a capture: the local file's picture.
  const fs::path glb = gs::test::sourceDir() / "tests/data/splats/bunny_small.glb";
  nginx.writeFile("bunny.glb", gs::test::readBytes(glb));
  REQUIRE(shoot("bunny_glb_local", glb.string()).exitCode == 0);
  const auto remoteGlb = shoot("bunny_glb_http", nginx.url("/bunny.glb"));
  INFO(remoteGlb.err);
  REQUIRE(remoteGlb.exitCode == 0);
  CHECK(covered("bunny_glb_local") > 0.05);
  CHECK(differing("bunny_glb_local", "bunny_glb_http", 0) == 0.0);
  CHECK(differing("bunny_glb_local", "bunny_ply_local", 16) < 0.005);
  // An SPZ v3 over HTTP, its gzip data inflated as they come: the local file's picture;
  // --snapshot-at three quarters of its bytes draws the splats whose SH had come (the
  // bunny's SH made to vary, as a capture's: its own are all zero, a few bytes of gzip).
  std::string v3 = gs::base::gunzip(
      gs::test::readBytes(gs::test::sourceDir() / "tests/data/splats/bunny_small_v3.spz"), 1 << 24);
  gs::test::fillPseudoRandom(v3, 16 + 3000 * 20, 7);
  const std::string spz = gs::test::gzip(v3);
  const fs::path spzFile = outDir() / "bunny_v3.spz";
  std::ofstream(spzFile, std::ios::binary) << spz;
  nginx.writeFile("bunny_v3.spz", spz);
  REQUIRE(shoot("bunny_v3_local", spzFile.string()).exitCode == 0);
  const auto remoteSpz = shoot("bunny_v3_http", nginx.url("/bunny_v3.spz"));
  INFO(remoteSpz.err);
  REQUIRE(remoteSpz.exitCode == 0);
  CHECK(covered("bunny_v3_local") > 0.05);
  CHECK(differing("bunny_v3_local", "bunny_v3_http", 0) == 0.0);
  const auto spzPart = shoot("bunny_v3_part", nginx.url("/bunny_v3.spz"),
                             {"--snapshot-at", std::to_string(spz.size() * 3 / 4)});
  INFO(spzPart.err);
  CHECK(spzPart.exitCode == 0);
  CHECK(covered("bunny_v3_part") > 0.0);
  CHECK(differing("bunny_v3_local", "bunny_v3_part", 16) > 0.01);
  // A .ply that is not there: the server's answer, not the mesh rule.
  const auto missingPly = shoot("bunny_ply_missing", nginx.url("/none.ply"));
  CHECK(missingPly.exitCode == 1);
  CHECK_THAT(missingPly.err, Catch::Contains("/none.ply: HTTP 404"));
  // A tileset whose index cannot be fetched: the picture of an incomplete input, exit 3
  // (it exited 0 before: only the loader's own streams were counted), the URL named.
  const auto missing = shoot("bunny_tileset_missing", nginx.url("/missing/"));
  CHECK(missing.exitCode == 3);
  CHECK_THAT(missing.err, Catch::Contains("/missing/index.qnvt") && Catch::Contains("404"));
}

TEST_CASE("a server that ignores ranges still gives the whole QNV picture", "[app][http][qnv]") {
  const fs::path qnv = outDir() / "ball_ir.qnv";
  ballStream("ball_ir.qnv");
  FaultServer server(gs::test::readBytes(qnv), FaultServer::Behaviour::ignoreRanges);
  REQUIRE(server.ok());
  REQUIRE(shoot("sphere_ir_local", qnv.string()).exitCode == 0);
  const auto r = shoot("sphere_ir_http", server.url("/sphere.qnv"));
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(differing("sphere_ir_local", "sphere_ir_http", 0) == 0.0);
}

TEST_CASE("a transfer reset mid-stream resumes with a range", "[app][http]") {
  const std::string world = boxesWorld(6);
  const std::size_t cut = world.size() / 2 + 10;  // each response is reset after this much
  FaultServer server(world, FaultServer::Behaviour::resetMidway, cut);
  REQUIRE(server.ok());
  const auto r = shoot("boxes_reset", server.url("/boxes.wrl"), {"--stall-timeout", "2"});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  const auto requests = server.requests();
  REQUIRE(requests.size() >= 2);
  CHECK(requests[1].range == "bytes=" + std::to_string(cut) + "-");
  std::ofstream(outDir() / "boxes6_reset.wrl", std::ios::binary) << world;
  REQUIRE(shoot("boxes6_reset_local", (outDir() / "boxes6_reset.wrl").string()).exitCode == 0);
  CHECK(differing("boxes6_reset_local", "boxes_reset", 0) == 0.0);
}

TEST_CASE("a world cut mid-transfer shows what arrived and says why", "[app][http]") {
  const std::string world = boxesWorld(6);
  // Cut inside the fourth box: three complete top-level nodes arrived.
  std::size_t cut = 0;
  for (int i = 0; i < 4; ++i) cut = world.find("Transform", cut + 1);
  cut += 40;
  FaultServer server(world, FaultServer::Behaviour::stall, cut);
  REQUIRE(server.ok());
  const auto r = shoot("boxes_cut", server.url("/boxes.wrl"), {"--stall-timeout", "1"});
  INFO(r.err);
  CHECK(r.exitCode == 3);  // a picture, from an incomplete input
  CHECK(r.err.find(server.url("/boxes.wrl")) != std::string::npos);
  REQUIRE(fs::exists(outDir() / "boxes_cut.png"));
  const double part = covered("boxes_cut");
  std::ofstream(outDir() / "boxes6.wrl", std::ios::binary) << world;
  REQUIRE(shoot("boxes6", (outDir() / "boxes6.wrl").string()).exitCode == 0);
  CHECK(part > 0.01);
  CHECK(part < covered("boxes6") * 0.75);
}

TEST_CASE("HTTP errors and stalls end with a clear message, never a hang", "[app][http]") {
  const std::string world = boxesWorld(3);
  struct Case {
    FaultServer::Behaviour behaviour;
    const char* expected;
    int exitCode;
  };
  for (const Case c : {Case{FaultServer::Behaviour::notFound, "404", 1},
                       Case{FaultServer::Behaviour::serverError, "500", 1},
                       Case{FaultServer::Behaviour::stall, "stall", 3},
                       Case{FaultServer::Behaviour::wrongLengthShort, "bytes", 3},
                       Case{FaultServer::Behaviour::redirectToFile, "", 1}}) {
    FaultServer server(world, c.behaviour, world.size() / 2);
    REQUIRE(server.ok());
    const auto r = shoot("fault", server.url("/w.wrl"), {"--stall-timeout", "1"});
    INFO(r.err);
    CHECK(r.exitCode == c.exitCode);
    CHECK(r.err.find(c.expected) != std::string::npos);
  }
}

TEST_CASE("content from the network never reads local files", "[app][http]") {
  NginxServer nginx;
  if (!nginx.ok()) return;
  const fs::path local = outDir() / "secret.wrl";
  std::ofstream(local, std::ios::binary) << boxesWorld(2);
  nginx.writeFile("evil.wrl",
                  "#VRML V2.0 utf8\nViewpoint { position 0 0 30 }\n"
                  "Inline { url \"file://" +
                      local.string() + "\" }\n");
  const auto r = shoot("evil", nginx.url("/evil.wrl"));
  INFO(r.err);
  CHECK(r.exitCode == 0);
  CHECK(r.err.find("may only reference http(s)") != std::string::npos);
  CHECK(covered("evil") == 0.0);
}

TEST_CASE("snapshot-at renders the state after part of the bytes", "[app]") {
  const std::string world = boxesWorld(6);
  const fs::path path = outDir() / "boxes6_at.wrl";
  std::ofstream(path, std::ios::binary) << world;
  std::size_t cut = 0;
  for (int i = 0; i < 3; ++i) cut = world.find("Transform", cut + 1);
  const auto r = shoot("boxes_at", path.string(), {"--snapshot-at", std::to_string(cut)});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  REQUIRE(shoot("boxes_at_all", path.string()).exitCode == 0);
  const double part = covered("boxes_at"), all = covered("boxes_at_all");
  CHECK(part > 0.01);
  CHECK(part < all * 0.6);
  CHECK(shoot("bad_at", path.string(), {"--snapshot-at", "12x"}).exitCode == 2);
}

TEST_CASE("relative URLs resolve after redirects", "[app][http]") {
  // The fault server redirects every path to its own /target, which serves a world
  // inlining "part.wrl": that must be fetched as /part.wrl (relative to /target), not as
  // /w/part.wrl (relative to the URL first asked).
  FaultServer::Request seen;
  {
    FaultServer server("#VRML V2.0 utf8\nInline { url \"part.wrl\" }\n",
                       FaultServer::Behaviour::redirect);
    REQUIRE(server.ok());
    shoot("redirect", server.url("/w/start.wrl"));
    const auto requests = server.requests();
    REQUIRE(requests.size() >= 3);
    seen = requests[2];
  }
  CHECK(seen.path == "/part.wrl");
}
