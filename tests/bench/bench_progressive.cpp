// Progressive loading over an emulated slow link (docs/progressive-loading.md): time to
// the first frame and to an image within a set distance of the final one, against the
// time to transfer the plain file whole (Nagasawa, "Beyond VRML", section 3.4: one third
// of the plain transfer time; our aim is a tenth).
//
//   bench_progressive [RATE_BYTES_PER_S]     (default 1250000 = 10 Mbit/s)
//
// Inputs (skipped when ../shared/corpus is absent): CThead as a .qnv of its top 9.1% of
// voxels, and the KiCad DSUB-62 connector as its plain .wrl and as an outline-first world
// (ghostspace encode --outline), each also gzip-compressed. The link is emulated by the
// transfer layer's rate limit (FetchRequest::maxRate, the --max-rate option), which paces
// file and HTTP transfers alike. "Close" means at most 5% of pixels differ by more than
// 48/255 in a channel from the final image, seen by the same camera (render::compareImages).
#include <zlib.h>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "app/commands.hpp"
#include "app/options.hpp"
#include "outline/outline_world.hpp"
#include "qnv/encoder.hpp"
#include "qnv/stream.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "session/streaming_session.hpp"
#include "session/volume_input.hpp"
#include "session/world.hpp"

namespace fs = std::filesystem;
using namespace gs;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kWidth = 320, kHeight = 240;
constexpr int kTolerance = 48;
constexpr double kClose = 0.05;

bool writeFile(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

std::string gzip(const std::string& bytes) {
  z_stream z{};
  deflateInit2(&z, 9, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
  std::string out(deflateBound(&z, bytes.size()), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(bytes.data()));
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

struct Frame {
  double seconds;
  std::uint64_t bytes;
  render::Image image;
};

bool blank(const render::Image& image) {
  for (std::size_t i = 4; i < image.rgba.size(); ++i)
    if (image.rgba[i] != image.rgba[i % 4]) return false;
  return true;
}

/// Streams `input` at `rate` bytes/s into an off-screen renderer, drawing with `camera`
/// (null: the final camera is not known yet; the scene is framed as it stands) at most
/// 5 times a second. Returns every frame drawn; the last one is the complete picture.
std::vector<Frame> stream(const std::string& input, double rate, const scene::Camera* camera,
                          double lod, scene::Camera* finalCamera, std::uint64_t stopAfter = 0) {
  net::LoaderOptions lo;
  lo.maxRate = rate;
  lo.stopAfterBytes = stopAfter;
  session::StreamingSession session(lo);
  std::string error;
  auto scene = session.open(input, error);
  std::vector<Frame> frames;
  if (!scene) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return frames;
  }
  render::SceneRendererOptions ro = app::rendererOptions(app::Options{});
  ro.lod = lod;
  render::SceneRenderer renderer(scene, session.rendererOptions(ro));
  const float aspect = static_cast<float>(kWidth) / kHeight;
  auto cameraNow = [&] {
    if (camera) return *camera;
    scene::Camera c = renderer.fitToScene(aspect, renderer.boundViewpointCamera());
    scene::fitClipPlanes(c, renderer.bounds(), renderer.navigation().nearClip());
    return c;
  };
  const auto t0 = Clock::now();
  auto last = t0 - std::chrono::seconds(1);
  bool dirty = true, drew = false;
  for (;;) {
    if (session.pump()) {
      renderer.sceneChanged();
      dirty = true;
    }
    const bool settled = session.settled();
    drew = false;
    // Until something shows, draw whenever anything arrived (the first frame's time);
    // then at most 5 frames a second.
    const bool showing = !frames.empty() && !blank(frames.back().image);
    if (dirty && (settled || !showing || Clock::now() - last > std::chrono::milliseconds(200))) {
      renderer.draw(cameraNow(), 0, 0, kWidth, kHeight);
      std::uint64_t bytes = 0;
      for (const auto& p : session.loader().progress()) bytes += p.bytes;
      frames.push_back({std::chrono::duration<double>(Clock::now() - t0).count(), bytes,
                        render::readPixels(0, 0, kWidth, kHeight)});
      last = Clock::now();
      dirty = false;
      drew = true;
    }
    if (settled && !dirty && !drew) break;
    if (!drew) session.loader().wait(0.005);
  }
  if (finalCamera) *finalCamera = cameraNow();
  return frames;
}

/// Streams `input` once at full speed for the final picture and camera, then at `rate`,
/// and prints the times.
void measure(const char* label, const std::string& input, double rate, double plainBytes,
             double lod = 1.0) {
  scene::Camera camera;
  const auto reference = stream(input, 0.0, nullptr, lod, &camera);
  if (reference.empty()) return;
  const render::Image& final = reference.back().image;
  const auto frames = stream(input, rate, &camera, lod, nullptr);
  if (frames.empty()) return;
  double first = -1.0, close = -1.0;
  std::uint64_t closeBytes = 0;
  const bool verbose = std::getenv("GS_BENCH_VERBOSE") != nullptr;
  for (const Frame& f : frames) {
    if (verbose)
      std::printf("  %6.2f s %9llu B %s %.3f\n", f.seconds,
                  static_cast<unsigned long long>(f.bytes), blank(f.image) ? "blank" : "     ",
                  render::compareImages(f.image, final, kTolerance).fractionDiffering);
    if (first < 0.0 && !blank(f.image)) first = f.seconds;
    if (close < 0.0 &&
        render::compareImages(f.image, final, kTolerance).fractionDiffering <= kClose) {
      close = f.seconds;
      closeBytes = f.bytes;
    }
  }
  const double plain = plainBytes / rate;
  const auto size = static_cast<std::uint64_t>(fs::file_size(input));
  // The smallest prefix whose complete picture is close (binary search to 1/256 of the
  // file, no rate limit): its link time does not depend on how fast llvmpipe draws.
  std::uint64_t lo = 0, hi = size;
  while (hi - lo > std::max<std::uint64_t>(size / 256, 1024)) {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    const auto part = stream(input, 0.0, &camera, lod, nullptr, mid);
    const bool ok =
        !part.empty() &&
        render::compareImages(part.back().image, final, kTolerance).fractionDiffering <= kClose;
    (ok ? hi : lo) = mid;
  }
  std::printf(
      "%-30s %9llu B  whole %6.2f s  first frame %5.2f s  close %5.2f s (%8llu B)  close "
      "prefix %8llu B = %5.2f s link  link / plain %.2f\n",
      label, static_cast<unsigned long long>(size), frames.back().seconds, first, close,
      static_cast<unsigned long long>(closeBytes), static_cast<unsigned long long>(hi), hi / rate,
      hi / rate / plain);
}

}  // namespace

int main(int argc, char** argv) {
  const double rate = argc > 1 ? std::atof(argv[1]) : 1250000.0;
  const fs::path corpus = fs::path(GS_CORPUS_DIR);
  const fs::path cthead = corpus / "volume/cthead/CThead.nhdr";
  const fs::path kicad =
      corpus /
      "vrml/kicad/Connector_Dsub__DSUB-62-HD_Male_Horizontal_P2.41x1.98mm_EdgePinOffset9.40mm.wrl";
  if (!fs::exists(cthead) || !fs::exists(kicad)) {
    std::printf("skipped: %s not found\n", corpus.string().c_str());
    return 0;
  }
  auto context = render::createOffscreenContext(kWidth, kHeight);
  const fs::path dir = fs::temp_directory_path() / "gs_bench_progressive";
  fs::create_directories(dir);
  std::printf("link %.0f bytes/s (%.1f Mbit/s), %dx%d, close = <= %.0f%% of pixels off by > %d\n",
              rate, rate * 8 / 1e6, kWidth, kHeight, kClose * 100, kTolerance);

  // CThead: its top 9.1% as a .qnv (the paper's figure 2); "plain" is the raw volume.
  {
    const auto volume = session::loadVolumeFile(cthead.string());
    qnv::VolumeEncodeOptions opt;
    opt.selection.fraction = 0.091;
    writeFile(dir / "cthead.qnv", qnv::writeStream(qnv::encodeVolume(volume, opt)));
    const double raw = static_cast<double>(volume.samples.size()) * 2.0;
    std::printf("CThead raw volume %.0f bytes: %.2f s at this rate\n", raw, raw / rate);
    measure("CThead 9.1% .qnv (lod 1)", (dir / "cthead.qnv").string(), rate, raw);
  }
  // KiCad DSUB-62: plain, outline-first, and both gzip-compressed.
  {
    std::ifstream in(kicad, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    const std::string plain = s.str();
    const session::LoadedWorld world = session::loadWorld(kicad.string());
    outline::OutlineWorldSummary summary;
    const std::string outlined = outline::writeOutlineWorld(world.scene, {}, &summary);
    writeFile(dir / "plain.wrl", plain);
    writeFile(dir / "plain.wrl.gz", gzip(plain));
    writeFile(dir / "outline.wrl", outlined);
    writeFile(dir / "outline.wrl.gz", gzip(outlined));
    const double plainBytes = static_cast<double>(plain.size());
    std::printf(
        "DSUB-62 plain .wrl %.0f bytes: %.2f s at this rate; outline world %zu groups, "
        "outlines in the first %zu bytes\n",
        plainBytes, plainBytes / rate, summary.groups, summary.outlineBytes);
    measure("DSUB-62 plain .wrl", (dir / "plain.wrl").string(), rate, plainBytes);
    measure("DSUB-62 plain .wrl.gz", (dir / "plain.wrl.gz").string(), rate, plainBytes);
    measure("DSUB-62 outline-first .wrl", (dir / "outline.wrl").string(), rate, plainBytes);
    measure("DSUB-62 outline-first .wrl.gz", (dir / "outline.wrl.gz").string(), rate, plainBytes);
  }
  fs::remove_all(dir);
  return 0;
}
