// `ghostspace --snapshot OUT.png [--size WxH] INPUT`: off-screen rendering through OSMesa,
// the same SceneRenderer the window uses. The input streams in (files and URLs alike,
// docs/progressive-loading.md); the picture is taken when everything asked for arrived,
// or at --snapshot-at.
#include "app/commands.hpp"
#include "app/progress_bar.hpp"
#include "app/splat_inputs.hpp"
#include "app/streaming_session.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace gs::app {

render::SceneRendererOptions rendererOptions(const Options& options) {
  render::SceneRendererOptions r;
  r.splatLoader = splatLoader();
  r.lod = options.lod;
  r.traversal.mode = options.mode == "splats"     ? render::RenderMode::splats
                     : options.mode == "outlines" ? render::RenderMode::outlines
                                                  : render::RenderMode::polygons;
  return r;
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
double loadFraction(const net::Loader& loader) {
  double have = 0.0, want = 0.0;
  for (const net::StreamProgress& p : loader.progress()) {
    have += p.fraction();
    want += 1.0;
  }
  return want > 0.0 ? have / want : 0.0;
}

}  // namespace

int runSnapshot(const Options& options) {
  const std::string& input = options.inputs.front();
  StreamingSession session(loaderOptions(options));
  std::string error;
  const auto scene = session.open(input, error);
  if (!scene) {
    std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
    return 1;
  }
  auto context = render::createOffscreenContext(options.width, options.height);
  render::SceneRenderer renderer(scene, session.rendererOptions(rendererOptions(options)));
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  // A stream, mesh or volume has no Viewpoint of its own: frame it whole.
  const bool fit = options.fit || isSplatInput(input);
  auto camera = [&] {
    render::Camera c = renderer.boundViewpointCamera();
    if (fit) c = renderer.fitToScene(aspect, c);
    render::fitClipPlanes(c, renderer.bounds(), renderer.navigation().nearClip());
    return c;
  };
  auto draw = [&] { renderer.draw(camera(), 0, 0, options.width, options.height); };

  // Load. Drawing is what asks for Inline worlds and QNV prefixes (the level of detail),
  // so the scene is drawn (at most 4 times a second) whenever it changed, and the load
  // ends when a pump after the last draw finds nothing arriving.
  ProgressBar bar("loading", stderr, options.progress);
  const auto t0 = Clock::now();
  auto lastDraw = t0;
  bool needDraw = true, drewSincePump = false;
  for (;;) {
    if (session.pump()) {
      renderer.sceneChanged();
      needDraw = true;
    }
    drewSincePump = false;
    if (options.snapshotAtSeconds > 0.0 && secondsSince(t0) >= options.snapshotAtSeconds) {
      session.loader().stopAll("stopped after " + std::to_string(options.snapshotAtSeconds) +
                               " s (--snapshot-at)");
      session.pump();
      renderer.sceneChanged();
      break;
    }
    const bool settled = session.settled();
    if (needDraw && (settled || secondsSince(lastDraw) >= 0.25)) {
      draw();
      lastDraw = Clock::now();
      needDraw = false;
      drewSincePump = true;
    }
    if (settled && !needDraw && !drewSincePump) break;
    bar.update(loadFraction(session.loader()));
    if (!drewSincePump) session.loader().wait(0.01);
  }
  bar.finish();

  draw();
  const render::Image image = render::readPixels(0, 0, options.width, options.height);
  std::vector<std::pair<bool, std::string>> messages;
  session.drainMessages(messages);
  bool failed = false;
  for (const net::StreamProgress& p : session.loader().progress())
    failed |= p.state == net::StreamState::failed;
  for (const auto& [isError, text] : messages) std::fprintf(stderr, "%s\n", text.c_str());
  for (const auto& d : renderer.diagnostics().items)
    std::fprintf(stderr, "%s\n", d.format().c_str());
  bool anyError = failed;
  for (const auto& m : messages) anyError |= m.first;
  if (scene->rootNodes.empty() && anyError) {
    // Nothing to show: the reason was printed above.
    if (messages.empty()) std::fprintf(stderr, "ghostspace: %s: nothing to show\n", input.c_str());
    return 1;
  }
  render::writePng(options.snapshotPath, image);
  return failed ? 3 : 0;
}

}  // namespace gs::app
