// `ghostspace --snapshot OUT.png [--size WxH] INPUT`: off-screen rendering through OSMesa,
// the same SceneRenderer the window uses.
#include "app/commands.hpp"
#include "app/splat_inputs.hpp"
#include "app/world.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <cstdio>

namespace gs::app {

namespace {

/// The first error of a load, for the one-line failure message.
const vrml::Diagnostic* firstError(const vrml::Diagnostics& d) {
  for (const auto& item : d.items)
    if (item.severity == vrml::Severity::error) return &item;
  return nullptr;
}

void printDiagnostics(const vrml::Diagnostics& d) {
  for (const auto& item : d.items) std::fprintf(stderr, "%s\n", item.format().c_str());
}

}  // namespace

render::SceneRendererOptions rendererOptions(const Options& options) {
  render::SceneRendererOptions r;
  r.splatLoader = splatLoader();
  r.lod = options.lod;
  r.traversal.mode = options.mode == "splats"     ? render::RenderMode::splats
                     : options.mode == "outlines" ? render::RenderMode::outlines
                                                  : render::RenderMode::polygons;
  return r;
}

int runSnapshot(const Options& options) {
  const LoadedWorld w = loadWorld(options.inputs.front());
  const vrml::Diagnostic* error = firstError(w.scene->diagnostics);
  if (!w.readable || (w.scene->rootNodes.empty() && error != nullptr)) {
    // Nothing to show: one line, the reason.
    std::fprintf(stderr, "ghostspace: %s\n",
                 error != nullptr ? error->format().c_str() : "cannot read the input");
    return 1;
  }
  printDiagnostics(w.scene->diagnostics);

  auto context = render::createOffscreenContext(options.width, options.height);
  render::SceneRenderer renderer(w.scene, rendererOptions(options));
  render::Camera camera = renderer.boundViewpointCamera();
  // A stream, mesh or volume has no Viewpoint of its own: frame it whole.
  if (options.fit || isSplatInput(options.inputs.front()))
    camera = renderer.fitToScene(
        static_cast<float>(options.width) / static_cast<float>(options.height), camera);
  render::fitClipPlanes(camera, renderer.bounds(), renderer.navigation().nearClip());
  renderer.draw(camera, 0, 0, options.width, options.height);
  const render::Image image = render::readPixels(0, 0, options.width, options.height);
  printDiagnostics(renderer.diagnostics());
  render::writePng(options.snapshotPath, image);
  return 0;
}

}  // namespace gs::app
