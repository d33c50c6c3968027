// `ghostspace --snapshot OUT.png [--size WxH] INPUT`: off-screen rendering through OSMesa,
// the same SceneRenderer the window uses. The input streams in (files and URLs alike,
// docs/progressive-loading.md); the picture is taken when everything asked for arrived,
// or at --snapshot-at.
#include "app/commands.hpp"
#include "app/frame_log.hpp"
#include "app/layout.hpp"
#include "app/progress_bar.hpp"
#include "formats/input_kind.hpp"
#include "render/context.hpp"
#include "render/movie_players.hpp"
#include "session/splat_inputs.hpp"
#include "session/streaming_session.hpp"
#include "session/world_runtime.hpp"
#include "session/world_view.hpp"

#include <glad/gl.h>
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace gs::app {

render::SceneRendererOptions rendererOptions(const Options& options) {
  render::SceneRendererOptions r;
  r.splatLoader = session::splatLoader();
  r.lod = options.lod;
  r.splatPath = options.splatPath;
  r.textureQuality = options.textureQuality;
  r.shading = options.shading;
  r.traversal.mode = options.mode;
  // GS_SHADER_VARIANTS=0: one generic surface program (benchmarks' "before"; docs/rendering.md).
  if (const char* v = std::getenv("GS_SHADER_VARIANTS"); v != nullptr && std::string_view(v) == "0")
    r.shaderVariants = false;
  // One player per movie for all the viewports made with these options (docs/media.md).
  r.movies = std::make_shared<render::MoviePlayers>();
  return r;
}

session::TilesetOptions tilesetOptions(const Options& options) {
  session::TilesetOptions o;
  o.memoryBytes = static_cast<std::uint64_t>(options.tilesetMemoryMb * 1048576.0);
  return o;
}

net::LoaderOptions loaderOptions(const Options& options) {
  net::LoaderOptions o;
  o.maxRate = options.maxRate;
  o.stopAfterBytes = options.snapshotAtBytes;
  o.stallTimeout = options.stallTimeout;
  o.connectTimeout = std::min(10.0, std::max(1.0, options.stallTimeout));
  return o;
}

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// Bytes arrived and expected over every stream, for the progress bar.
double loadFraction(const session::StreamingSession& session) {
  double have = 0.0, want = 0.0;
  for (const net::StreamProgress& p : session.progress()) {
    have += p.fraction();
    want += 1.0;
  }
  return want > 0.0 ? have / want : 0.0;
}

}  // namespace

int runSnapshot(const Options& options) {
  session::StreamingSession session(loaderOptions(options));
  session.setTilesetOptions(tilesetOptions(options));
  // One viewport per layout cell; the INPUTs fill them in order and a single INPUT fills
  // them all. A world named twice is loaded once (the session shares its streams).
  const int cells = layoutCells(options.layout);
  std::vector<std::shared_ptr<const vrml::Scene>> scenes;
  for (const std::string& input : options.inputs) {
    std::string error;
    auto scene = session.open(input, error);
    if (!scene) {
      std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
      return 1;
    }
    scenes.push_back(scene);
  }
  auto context = render::createOffscreenContext(options.width, options.height,
                                                options.samples < 0 ? 1 : options.samples);
  const int samples = render::drawFramebufferSamples();  // what the context got
  // One WorldView per cell (session/world_view.hpp): the load below and every frame of
  // life are thin loops over them.
  session::ViewGroup group(session);
  std::vector<std::unique_ptr<session::WorldView>> views;
  const render::SceneRendererOptions shared = rendererOptions(options);  // one movie registry
  for (int i = 0; i < cells && (scenes.size() == 1 || i < static_cast<int>(scenes.size())); ++i) {
    const std::size_t k = scenes.size() == 1 ? 0 : static_cast<std::size_t>(i);
    render::SceneRendererOptions ro = shared;
    ro.lod = viewportLod(options, static_cast<std::size_t>(i));
    auto v = std::make_unique<session::WorldView>(group, scenes[k], ro);
    const ViewportRect rect = layoutRect(options.layout, i, options.width, options.height);
    v->setRect(rect.x, rect.y, rect.width, rect.height);
    // A stream, mesh or volume has no Viewpoint of its own: frame it whole.
    const bool fit = options.fit || session.opensAsSplats(options.inputs[k]);
    // A glTF asset without a camera is framed whole too, as glTF viewers do (asked when
    // drawn: the encoding is known once the asset has arrived).
    v->setCamera([fit, castle = options.castleCamera, scene = scenes[k]](render::SceneRenderer& r,
                                                                         float aspect) {
      scene::Camera c = r.boundViewpointCamera();
      const bool gltf = scene->x3d.encoding == "glTF";
      if (fit && r.viewpoints().empty()) c.orientation = r.defaultOrientation();
      if (fit) c = r.fitToScene(aspect, c);
      if (!fit && (gltf || castle) && r.viewpoints().empty())
        c = scene::wholeSceneCamera(r.bounds(), c);
      scene::fitClipPlanes(c, r.bounds(), r.navigation().nearClip());
      return c;
    });
    views.push_back(std::move(v));
  }
  auto clear = [&] {
    glViewport(0, 0, options.width, options.height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  };

  // Load. Drawing is what asks for Inline worlds and QNV prefixes (the level of detail),
  // so the scene is drawn (at most 4 times a second) whenever it changed, and the load
  // ends when a pump after the last draw finds nothing arriving. The worlds do not run
  // yet: their Scripts start on the whole world, at --time.
  ProgressBar bar("loading", stderr, options.progress);
  const auto t0 = Clock::now();
  auto lastDraw = t0;
  bool needDraw = true, drewSincePump = false;
  for (;;) {
    if (group.pump()) needDraw = true;
    drewSincePump = false;
    if (options.snapshotAtSeconds > 0.0 && secondsSince(t0) >= options.snapshotAtSeconds) {
      session.loader().stopAll("stopped after " + std::to_string(options.snapshotAtSeconds) +
                               " s (--snapshot-at)");
      group.pump();
      for (auto& v : views) v->renderer().sceneChanged();
      break;
    }
    const bool settled = group.settled();
    if (needDraw && (settled || secondsSince(lastDraw) >= 0.25)) {
      clear();
      for (auto& v : views) v->draw();
      lastDraw = Clock::now();
      needDraw = false;
      drewSincePump = true;
    }
    if (settled && !needDraw && !drewSincePump) break;
    bar.update(loadFraction(session));
    if (!drewSincePump) session.loader().wait(0.01);
  }
  bar.finish();

  // Life (docs/runtime.md): each world is loaded at --load-time or --time T (0 by default)
  // and moved
  // through T0 + i * DT at the fixed --time-step, so a frame's pixels depend on the
  // command alone.
  session::RuntimeOptions time = options.time;
  time.samples = samples;
  session::WorldRuntimes runtimes(time, &session.loader());
  // MovieTextures show the frame of their media time, waiting for it (docs/media.md).
  group.attachRuntimes(runtimes, time.load >= 0.0 ? time.load : time.start, true);
  // What the new state references (an Inline a Switch now shows, an Inline or texture url
  // a Script set, a LOD level chosen at T) is asked for while drawing: frames at the same
  // time repeat until a pump finds nothing arriving and nothing more was asked for.
  // Transfers end (arrive, fail or stall past --stall-timeout), so this ends.
  std::unique_ptr<FrameLog> frameLog;
  if (!options.frameLog.empty()) {
    frameLog = std::make_unique<FrameLog>(options.frameLog);
    if (!frameLog->ok()) {
      std::fprintf(stderr, "ghostspace: cannot write --frame-log %s\n", options.frameLog.c_str());
      return 1;
    }
  }
  render::Image image;
  for (int frame = 0; frame < time.frames; ++frame) {
    const double at = time.start + time.interval * frame;
    if (frameLog) frameLog->beginFrame();
    for (;;) {
      clear();
      bool changed = false;
      for (auto& v : views) changed |= v->frame(at);
      if (changed) continue;
      if (group.settled()) break;
      session.loader().wait(0.01);
    }
    image = render::readPixels(0, 0, options.width, options.height);
    if (frameLog) {
      std::vector<std::uint64_t> drawn;
      std::vector<double> lods;
      for (std::size_t i = 0; i < views.size(); ++i) {
        drawn.push_back(views[i]->renderer().statistics().splats);
        lods.push_back(viewportLod(options, i));
      }
      frameLog->endFrame(drawn, lods);
    }
    if (time.frames > 1)
      render::writePng(session::framePath(options.snapshotPath, frame, time.frames), image);
  }
  std::vector<std::pair<bool, std::string>> messages;
  session.drainMessages(messages);
  std::vector<std::string> runtimeMessages;
  runtimes.drainMessages(runtimeMessages);
  for (std::string& m : runtimeMessages) messages.emplace_back(false, std::move(m));
  bool failed = false;
  // Tilesets' indexes too; a splat scene file that failed is its node's error (reported
  // with the renderer's diagnostics below), as any node's url that cannot be loaded.
  for (const net::StreamProgress& p : session.progress())
    failed |= p.state == net::StreamState::failed && p.kind != net::StreamKind::splats;
  for (const auto& [isError, text] : messages) std::fprintf(stderr, "%s\n", text.c_str());
  bool drawError = false;
  for (const auto& v : views)
    for (const auto& d : v->renderer().diagnostics().items) {
      std::fprintf(stderr, "%s\n", d.format().c_str());
      drawError |= d.severity == vrml::Severity::error;
    }
  // An input that is one splat scene, stream or volume (a world made for it) shows nothing
  // when its node could not be loaded: that is a failure, not a black picture.
  bool onlySplatInputs = true;
  for (const std::string& input : options.inputs) onlySplatInputs &= session.opensAsSplats(input);
  if (drawError && onlySplatInputs) return 1;
  // Splat inputs that arrived whole but hold nothing to draw (an empty stream, a scene of
  // no splats): never a silent black picture.
  std::size_t splatsDrawn = 0;
  for (const auto& v : views) splatsDrawn += v->renderer().statistics().splats;
  bool onlyStreams = true;  // QNV streams and Gaussian scenes: what draws splats alone
  for (const std::string& input : options.inputs) {
    const formats::InputKind kind = formats::classifyFile(input);
    onlyStreams &= kind == formats::InputKind::qnv || kind == formats::InputKind::gaussianSplats;
  }
  if (onlyStreams && splatsDrawn == 0 && options.snapshotAtBytes == 0 &&
      options.snapshotAtSeconds == 0.0 && !failed) {
    for (const std::string& input : options.inputs)
      std::fprintf(stderr, "ghostspace: %s: nothing to draw: it holds no vectors or splats\n",
                   input.c_str());
    return 1;
  }
  bool anyError = failed;
  for (const auto& m : messages) anyError |= m.first;
  bool anyNodes = false;
  for (const auto& scene : scenes) anyNodes |= !scene->rootNodes.empty();
  if (!anyNodes && anyError) return 1;  // nothing to show: the reason was printed above
  if (time.frames <= 1) render::writePng(options.snapshotPath, image);
  return failed ? 3 : 0;
}

}  // namespace gs::app
