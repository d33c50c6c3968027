#include "app/window_state.hpp"

#include <glad/gl.h>

#include <algorithm>

namespace gs::app {

void WindowState::open(const std::string& path) {
  std::string error;
  auto scene = session->open(path, error);
  if (!scene) {
    log.push_back({true, error});
    showLog = true;
    return;
  }
  log.push_back({false, "opening " + path});
  recent.erase(std::remove(recent.begin(), recent.end(), path), recent.end());
  recent.insert(recent.begin(), path);
  if (recent.size() > 10) recent.resize(10);
  LoadedWorld w;
  w.scene = std::const_pointer_cast<vrml::Scene>(scene);
  w.readable = true;
  worlds.push_back(std::move(w));
  show(worlds.size() - 1);
}

void WindowState::update() {
  if (session->pump() && renderer) {
    renderer->sceneChanged();
    if (autoFrame) resetView();
  }
  std::vector<std::pair<bool, std::string>> messages;
  session->drainMessages(messages);
  for (auto& [error, text] : messages) {
    log.push_back({error, std::move(text)});
    if (error) showLog = true;
  }
}

void WindowState::show(std::size_t index) {
  if (index >= worlds.size()) return;
  current = index;
  renderer = std::make_unique<render::SceneRenderer>(worlds[index].scene,
                                                     session->rendererOptions(rendererOptions));
  renderDiagnosticsLogged = 0;
  autoFrame = true;
  resetView();
}

void WindowState::resetView() {
  if (!renderer) return;
  // The bound Viewpoint; a world without one is framed whole (a KiCad part, say, lies
  // far from the VRML97 default viewpoint's view), as other browsers do.
  render::Camera camera = renderer->initialCamera(lastAspect);
  const vrml::Bounds& b = renderer->bounds();
  // Orbit around the point of the view axis nearest the scene's centre.
  glm::vec3 center = camera.position + camera.forward() * 10.0f;
  if (!b.empty()) {
    const float along = glm::dot(b.center() - camera.position, camera.forward());
    center = camera.position + camera.forward() * std::max(along, 1e-3f);
  }
  navigator.setSceneBounds(b, renderer->navigation().nearClip());
  navigator.setHome(camera, center);
}

void WindowState::fitToScene() {
  if (!renderer) return;
  autoFrame = false;
  const render::Camera fitted = renderer->fitToScene(lastAspect, navigator.camera());
  navigator.setHome(fitted, renderer->bounds().center());
}

void WindowState::setMode(render::RenderMode mode) {
  rendererOptions.traversal.mode = mode;
  if (!renderer) return;
  const render::Camera camera = navigator.camera();
  renderer.reset();  // its GL objects go while the context is current
  renderer = std::make_unique<render::SceneRenderer>(worlds[current].scene,
                                                     session->rendererOptions(rendererOptions));
  navigator.setCamera(camera);
}

void WindowState::setLod(double lod) {
  rendererOptions.lod = lod;
  if (renderer) renderer->setLod(lod);
}

void WindowState::jumpToViewpoint(std::size_t index) {
  if (!renderer || index >= renderer->viewpoints().size()) return;
  autoFrame = false;
  navigator.setCamera(renderer->viewpointCamera(index));
}

void WindowState::drawScene(int x, int y, int width, int height) {
  lastAspect = static_cast<float>(width) / static_cast<float>(std::max(1, height));
  if (renderer) {
    renderer->draw(navigator.camera(), x, y, width, height);
    // Diagnostics found while drawing (textures, Inlines) go to the log once.
    const auto& items = renderer->diagnostics().items;
    for (; renderDiagnosticsLogged < items.size(); ++renderDiagnosticsLogged) {
      const auto& d = items[renderDiagnosticsLogged];
      log.push_back({d.severity == vrml::Severity::error, d.format()});
    }
    return;
  }
  glViewport(x, y, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

}  // namespace gs::app
