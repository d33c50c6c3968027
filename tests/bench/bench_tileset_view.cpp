// Viewing a QNV tileset over a slow link (docs/tilesets.md, "Viewing a tileset"): time to
// the first vectors and to all the vectors the view chose, and the bytes
// fetched, for CThead's top 9.1% as one stream and as a tileset (default cut: 64-voxel
// bricks, K = 16384), for the whole view and for a zoom into one corner. No GL: the
// session is driven by a recorded view (512 x 512 pixels) as the renderer records it.
//
//   bench_tileset_view ROOT URL [PARALLEL [BRICK_VOXELS]]
//
// ROOT is the folder a web server serves at URL (e.g. nginx with `limit_rate 1250k;` for
// an emulated 10 Mbit/s link per connection): the program writes ROOT/cthead.qnv and
// ROOT/cthead/ (the tileset) there first. PARALLEL is the number of brick transfers at
// once (default 1: the same single connection the stream gets); BRICK_VOXELS the leaf
// block side (default 64).
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"
#include "render/camera.hpp"
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

struct Result {
  double first = -1, tenth = -1, all = -1;
  std::uint64_t bytes = 0, vectors = 0;
};

/// Opens `url` (a stream or a tileset), shows it to `camera` (or the fitted camera) and
/// pumps until settled.
Result measure(const std::string& url, const render::Camera* camera, int parallel) {
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
  bool viewed = false;
  for (;;) {
    s.pump();
    if (!viewed && !set->bounds.empty()) {
      render::SplatSet::View v;
      v.camera = camera ? *camera : render::fitCamera(set->bounds, 1.0f, render::Camera{});
      v.heightPixels = 512;
      v.vectors = set->total();
      set->views[&r] = v;
      set->wantedVectors = set->total();  // a single stream: the whole prefix (lod 1)
      viewed = true;
      continue;
    }
    const std::uint64_t have = set->vectors.size();
    if (have > 0 && r.first < 0) r.first = seconds();
    if (samples.empty() || samples.back().second != have) samples.push_back({seconds(), have});
    if (viewed && s.settled()) break;
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
  render::Camera zoom = render::fitCamera(box, 1.0f, render::Camera{});
  const glm::vec3 target = h.boundsMin + (h.boundsMax - h.boundsMin) * glm::vec3(0.2f, 0.8f, 0.5f);
  zoom.orientation = glm::quatLookAt(glm::normalize(target - zoom.position), glm::vec3(0, 1, 0));
  zoom.fieldOfView /= 4.0f;

  std::printf("%-22s %9s %9s %9s %12s %10s\n", "", "first s", "10% s", "all s", "bytes", "vectors");
  for (const auto& [name, input, camera] :
       {std::tuple{"stream, whole view", url + "/cthead.qnv", (const render::Camera*)nullptr},
        std::tuple{"stream, corner zoom", url + "/cthead.qnv", (const render::Camera*)&zoom},
        std::tuple{"tileset, whole view", url + "/cthead/", (const render::Camera*)nullptr},
        std::tuple{"tileset, corner zoom", url + "/cthead/", (const render::Camera*)&zoom}}) {
    const Result r = measure(input, camera, parallel);
    std::printf("%-22s %9.3f %9.3f %9.3f %12llu %10llu\n", name, r.first, r.tenth, r.all,
                static_cast<unsigned long long>(r.bytes),
                static_cast<unsigned long long>(r.vectors));
  }
  return 0;
}
