// Four viewports over one stream (Nagasawa, "Beyond VRML", section 4: several streams on
// one display, each at its own resolution): CThead as a .qnv of all its vectors, shown in
// a 2x2 layout at 9%, 25%, 50% and 100% of them, drawn off-screen through the same
// SceneRenderer as the window. Prints the draw time of each viewport (camera moved every
// frame, so every frame sorts again) and of the whole frame.
//
//   bench_viewports [WxH] [FRAMES]     (default 800x600, 3 frames)
#include <glad/gl.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/commands.hpp"
#include "app/layout.hpp"
#include "app/options.hpp"
#include "qnv/encoder.hpp"
#include "qnv/stream.hpp"
#include "render/context.hpp"
#include "render/scene_renderer.hpp"
#include "session/streaming_session.hpp"
#include "session/volume_input.hpp"

namespace fs = std::filesystem;
using namespace gs;
using Clock = std::chrono::steady_clock;

int main(int argc, char** argv) {
  int width = 800, height = 600, frames = 3;
  if (argc > 1 && std::sscanf(argv[1], "%dx%d", &width, &height) != 2) {
    std::fprintf(stderr, "usage: bench_viewports [WxH] [FRAMES]\n");
    return 2;
  }
  if (argc > 2) frames = std::max(1, std::atoi(argv[2]));
  const fs::path cthead = fs::path(GS_CORPUS_DIR) / "volume/cthead/CThead.nhdr";
  if (!fs::exists(cthead)) {
    std::printf("skipped: %s not found\n", cthead.string().c_str());
    return 0;
  }
  const fs::path qnv = fs::temp_directory_path() / "gs_bench_viewports.qnv";
  {
    const std::string bytes =
        qnv::writeStream(qnv::encodeVolume(session::loadVolumeFile(cthead.string()), {}));
    std::ofstream(qnv, std::ios::binary)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }
  auto context = render::createOffscreenContext(width, height);
  session::StreamingSession session;
  std::string error;
  auto scene = session.open(qnv.string(), error);
  if (!scene) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const double lods[] = {0.09, 0.25, 0.5, 1.0};
  std::unique_ptr<render::SceneRenderer> views[4];
  app::ViewportRect rects[4];
  for (int i = 0; i < 4; ++i) {
    render::SceneRendererOptions o = app::rendererOptions(app::Options{});
    o.lod = lods[i];
    views[i] = std::make_unique<render::SceneRenderer>(scene, session.rendererOptions(o));
    rects[i] = app::layoutRect(app::Layout::quad, i, width, height);
  }
  // Load the whole stream (one session: read once for all four viewports). Drawing is
  // what asks for the prefix each level of detail needs.
  auto drawAll = [&](int frame) {
    for (int i = 0; i < 4; ++i) {
      const float aspect = static_cast<float>(rects[i].width) / static_cast<float>(rects[i].height);
      scene::Camera c = views[i]->fitToScene(aspect, views[i]->boundViewpointCamera());
      c.position.x += 0.5f * static_cast<float>(frame);  // a new view: the sort runs again
      scene::fitClipPlanes(c, views[i]->bounds(), views[i]->navigation().nearClip());
      views[i]->draw(c, rects[i].x, rects[i].y, rects[i].width, rects[i].height);
    }
  };
  drawAll(0);
  for (bool drew = true;;) {
    const bool changed = session.pump();
    if (changed) {
      for (auto& v : views) v->sceneChanged();
    }
    if (session.settled() && !changed && !drew) break;
    drew = false;
    if (changed && session.settled()) {
      drawAll(0);
      drew = true;
    }
    session.loader().wait(0.01);
  }
  std::printf("%s; %dx%d in a 2x2 layout; CThead, %llu vectors\n", glGetString(GL_RENDERER), width,
              height, static_cast<unsigned long long>(session.loader().progress().front().vectors));
  for (int frame = 0; frame < frames; ++frame) {
    double seconds[4] = {};
    const auto t0 = Clock::now();
    for (int i = 0; i < 4; ++i) {
      const float aspect = static_cast<float>(rects[i].width) / static_cast<float>(rects[i].height);
      scene::Camera c = views[i]->fitToScene(aspect, views[i]->boundViewpointCamera());
      c.position.x += 0.5f * static_cast<float>(frame);  // a new view: the sort runs again
      scene::fitClipPlanes(c, views[i]->bounds(), views[i]->navigation().nearClip());
      const auto s0 = Clock::now();
      views[i]->draw(c, rects[i].x, rects[i].y, rects[i].width, rects[i].height);
      glFinish();
      seconds[i] = std::chrono::duration<double>(Clock::now() - s0).count();
    }
    const double total = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("frame %d: ", frame);
    for (int i = 0; i < 4; ++i)
      std::printf("%3.0f%% %8zu splats %7.1f ms   ", lods[i] * 100, views[i]->statistics().splats,
                  seconds[i] * 1000);
    std::printf("total %7.1f ms\n", total * 1000);
  }
  fs::remove(qnv);
  return 0;
}
