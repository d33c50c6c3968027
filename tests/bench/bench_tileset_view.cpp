// Viewing a QNV tileset over a slow link (docs/tilesets.md, "Viewing a tileset"): time to
// the first vectors, to all the vectors the view chose and to the first close picture,
// and the bytes fetched, for CThead's top 9.1% as one stream and as a tileset (default
// cut: 64-voxel bricks, K = 16384), for the whole view and for a zoom into one corner.
// The session is driven by a recorded view (512 x 512 pixels) as the renderer records
// it; while it runs, the vectors present are copied every 0.2 s (and at the end), and
// afterwards each copy is drawn off-screen (OSMesa) with that view and compared with the
// last one: "close" is the first copy within bench_progressive's threshold (at most 5% of
// pixels off by more than 48/255), "base" within the baseline tests' (at most 1% off by
// more than 16/255; tests/app/baseline.hpp). Drawing after the run keeps llvmpipe's
// time out of the link's.
//
//   bench_tileset_view ROOT URL [PARALLEL [BRICK_VOXELS]]
//
// ROOT is the folder a web server serves at URL (e.g. nginx with `limit_rate 1250k;` for
// an emulated 10 Mbit/s link per connection): the program writes ROOT/cthead.qnv and
// ROOT/cthead/ (the tileset) there first. PARALLEL is the number of brick transfers at
// once (default 1: the same single connection the stream gets); BRICK_VOXELS the leaf
// block side (default 64).
#include <glad/gl.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/splat_renderer.hpp"
#include "scene/camera.hpp"
#include "session/splat_inputs.hpp"
#include "session/streaming_session.hpp"
#include "session/volume_input.hpp"

namespace fs = std::filesystem;
using namespace gs;
using Clock = std::chrono::steady_clock;

namespace {

void writeFile(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

constexpr int kSize = 512;
constexpr double kCopyEvery = 0.2;  // seconds between copies of the vectors present

struct Copy {
  double seconds;
  std::uint64_t bytes;
  std::vector<qnv::DecodedVector> vectors;
};

struct Result {
  double first = -1, tenth = -1, all = -1;
  double close = -1, base = -1;  // the first picture within each threshold
  std::uint64_t closeBytes = 0, baseBytes = 0;
  std::uint64_t bytes = 0, vectors = 0;
  render::Image final;  // the last picture
};

/// Draws `vectors` (styled as `set`) seen by `camera` at kSize x kSize.
render::Image draw(const render::SplatSet& style, const std::vector<qnv::DecodedVector>& vectors,
                   const scene::Camera& camera) {
  render::SplatSet set;
  set.style = style.style;
  set.vectors = vectors;
  set.computeBounds();
  render::SplatRenderer renderer;
  const render::SplatLight lights[] = {{camera.forward(), glm::vec3(1.0f)}};
  glViewport(0, 0, kSize, kSize);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  renderer.draw(set, set.vectors.size(), glm::mat4(1.0f), camera, 1.0f, lights);
  glFinish();
  return render::readPixels(0, 0, kSize, kSize);
}

/// Opens `url` (a stream or a tileset), shows it to `camera` (or the fitted camera) and
/// pumps until settled.
Result measure(const std::string& url, const scene::Camera* camera, int parallel) {
  net::LoaderOptions lo;
  session::StreamingSession s(lo);
  session::TilesetOptions to;
  to.parallelFetches = parallel;
  s.setTilesetOptions(to);
  const auto t0 = Clock::now();
  auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - t0).count(); };
  std::string error;
  if (!s.open(url, error)) {
    std::fprintf(stderr, "%s\n", error.c_str());
    std::exit(1);
  }
  const std::string node =
      session::tilesetIndexOf(url).empty() ? url : session::tilesetIndexOf(url);
  auto set = s.rendererOptions({}).splatLoader(node, "", error);
  if (!set) {
    std::fprintf(stderr, "%s\n", error.c_str());
    std::exit(1);
  }
  Result r;
  std::vector<std::pair<double, std::uint64_t>> samples;  // (seconds, vectors present)
  std::vector<Copy> copies;
  bool viewed = false;
  scene::Camera view;
  std::unique_ptr<render::SplatViewRequests::Request> request;
  for (;;) {
    s.pump();
    if (!viewed && !set->bounds.empty()) {
      render::SplatSet::View v;
      v.camera = camera ? *camera : scene::fitCamera(set->bounds, 1.0f, scene::Camera{});
      v.heightPixels = kSize;
      v.vectors = set->total();
      request = set->viewRequests->request();
      request->update(v);
      set->wantedVectors = set->total();  // a single stream: the whole prefix (lod 1)
      view = v.camera;
      viewed = true;
      continue;
    }
    const std::uint64_t have = set->vectors.size();
    if (have > 0 && r.first < 0) r.first = seconds();
    if (samples.empty() || samples.back().second != have) samples.push_back({seconds(), have});
    const bool settled = viewed && s.settled();
    if (have > 0 && (settled || copies.empty() || seconds() - copies.back().seconds >= kCopyEvery))
      copies.push_back({seconds(), s.loader().budget().totalBytes(), set->vectors});
    if (settled) break;
    s.loader().wait(0.005);
  }
  r.all = seconds();
  r.vectors = set->vectors.size();
  for (const auto& [t, n] : samples)
    if (n * 10 >= r.vectors) {
      r.tenth = t;
      break;
    }
  r.bytes = s.loader().budget().totalBytes();  // every transfer, index and bricks too
  // The pictures, last first.
  r.final = draw(*set, copies.back().vectors, view);
  for (const Copy& c : copies) {
    const render::Image image = draw(*set, c.vectors, view);
    const double off48 = render::compareImages(image, r.final, 48).fractionDiffering;
    const double off16 = render::compareImages(image, r.final, 16).fractionDiffering;
    if (std::getenv("GS_BENCH_VERBOSE"))
      std::printf("  %6.2f s %9llu B %8zu vectors  off48 %.4f  off16 %.4f\n", c.seconds,
                  static_cast<unsigned long long>(c.bytes), c.vectors.size(), off48, off16);
    if (r.close < 0 && off48 <= 0.05) {
      r.close = c.seconds;
      r.closeBytes = c.bytes;
    }
    if (r.base < 0 && off16 <= 0.01) {
      r.base = c.seconds;
      r.baseBytes = c.bytes;
    }
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_tileset_view ROOT URL [PARALLEL]\n");
    return 2;
  }
  const fs::path root = argv[1];
  const std::string url = argv[2];
  const int parallel = argc > 3 ? std::atoi(argv[3]) : 1;
  qnv::TilesetOptions cut;
  if (argc > 4) cut.brickVoxels = static_cast<std::uint32_t>(std::atoi(argv[4]));
  const fs::path ct = fs::path(GS_CORPUS_DIR) / "volume/cthead/CThead.nhdr";
  if (!fs::exists(ct)) {
    std::printf("skipped: %s is absent\n", ct.c_str());
    return 0;
  }
  const qnv::Volume volume = session::loadVolumeFile(ct.string());
  qnv::VolumeEncodeOptions options;
  options.selection.fraction = 0.091;
  writeFile(root / "cthead.qnv", qnv::writeStream(qnv::encodeVolume(volume, options)));
  const auto tileset = qnv::buildTileset(qnv::selectVolumeVectors(volume, options), cut);
  fs::remove_all(root / "cthead");
  for (const auto& b : tileset.bricks) writeFile(root / "cthead" / b.brick.path(), b.bytes);
  writeFile(root / "cthead/index.qnvt", qnv::serializeTilesetIndex(tileset.index));
  std::printf("CThead top 9.1%%: %llu vectors; stream %llu bytes; tileset %zu bricks, depth %d\n",
              static_cast<unsigned long long>(tileset.index.header.vectorCount),
              static_cast<unsigned long long>(fs::file_size(root / "cthead.qnv")),
              tileset.bricks.size(), tileset.index.depth);

  // The corner zoom: from the fitted camera's place, a quarter of its field of view
  // turned towards the box point at (0.2, 0.8, 0.5) of each axis.
  const auto& h = tileset.index.header;
  vrml::Bounds box;
  box.extend(h.boundsMin);
  box.extend(h.boundsMax);
  scene::Camera zoom = scene::fitCamera(box, 1.0f, scene::Camera{});
  const glm::vec3 target = h.boundsMin + (h.boundsMax - h.boundsMin) * glm::vec3(0.2f, 0.8f, 0.5f);
  zoom.orientation = glm::quatLookAt(glm::normalize(target - zoom.position), glm::vec3(0, 1, 0));
  zoom.fieldOfView /= 4.0f;

  auto context = render::createOffscreenContext(kSize, kSize);
  std::printf("%-22s %7s %7s %7s %7s %10s %7s %10s %10s %8s\n", "", "first s", "10% s", "close s",
              "close B", "base s", "base B", "all s", "bytes", "vectors");
  std::map<std::string, render::Image> finals;
  for (const auto& [name, input, camera] :
       {std::tuple{"stream, whole view", url + "/cthead.qnv", (const scene::Camera*)nullptr},
        std::tuple{"stream, corner zoom", url + "/cthead.qnv", (const scene::Camera*)&zoom},
        std::tuple{"tileset, whole view", url + "/cthead/", (const scene::Camera*)nullptr},
        std::tuple{"tileset, corner zoom", url + "/cthead/", (const scene::Camera*)&zoom}}) {
    const Result r = measure(input, camera, parallel);
    std::printf("%-22s %7.3f %7.3f %7.3f %10llu %7.3f %10llu %7.3f %10llu %8llu\n", name, r.first,
                r.tenth, r.close, static_cast<unsigned long long>(r.closeBytes), r.base,
                static_cast<unsigned long long>(r.baseBytes), r.all,
                static_cast<unsigned long long>(r.bytes),
                static_cast<unsigned long long>(r.vectors));
    finals[name] = r.final;
  }
  // The tileset's final picture against the stream's, the same view.
  for (const char* v : {"whole view", "corner zoom"}) {
    const auto d = render::compareImages(finals[std::string("tileset, ") + v],
                                         finals[std::string("stream, ") + v], 16);
    std::printf("final pictures, %s: tileset vs stream %.4f of pixels off by > 16/255\n", v,
                d.fractionDiffering);
  }
  return 0;
}
