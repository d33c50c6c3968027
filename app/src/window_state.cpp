#include "app/window_state.hpp"
#include "app/auto_lod.hpp"
#include "runtime/clock.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "render/image.hpp"

#include <glm/gtc/quaternion.hpp>

namespace gs::app {

WindowState::WindowState() : viewports(1) {}

WindowState::~WindowState() {
  viewports.clear();  // the views (renderers, with their loaders) before the session
}

session::ViewGroup& WindowState::viewGroup() {
  if (!group) group = std::make_unique<session::ViewGroup>(*session);
  return *group;
}

void WindowState::makeView(std::size_t index) {
  Viewport& v = viewports[index];
  v.worldView.reset();  // its GL objects go while the context is current
  v.worldView = std::make_unique<session::WorldView>(viewGroup(), worlds[v.world].scene, v.options);
  // The view draws, and its world's sensors see, the viewport's navigated camera.
  v.worldView->setCamera([this, index](render::SceneRenderer&, float) {
    return index < viewports.size() ? viewports[index].navigator.camera() : scene::Camera{};
  });
  v.worldView->setRect(v.rect.x, v.rect.y, v.rect.width, v.rect.height);
  v.worldView->renderer().setVectorBudget(v.vectorBudget);
}

void WindowState::setLayout(Layout next) {
  const int cells = layoutCells(next);
  layout = next;
  const std::size_t world = view().world;
  const std::size_t before = viewports.size();
  viewports.resize(static_cast<std::size_t>(cells));  // the renderers of cells removed go
  for (std::size_t i = before; i < viewports.size(); ++i)
    if (world != Viewport::kNone) show(world, i);
  active = std::min(active, viewports.size() - 1);
}

std::size_t WindowState::load(const std::string& path) {
  for (std::size_t i = 0; i < worlds.size(); ++i)
    if (worlds[i].scene->url == path) return i;  // shared, not loaded twice
  std::string error;
  auto scene = session->open(path, error);
  if (!scene) {
    log.push_back({true, error});
    showLog = true;
    return Viewport::kNone;
  }
  log.push_back({false, "opening " + path});
  recent.erase(std::remove(recent.begin(), recent.end(), path), recent.end());
  recent.insert(recent.begin(), path);
  if (recent.size() > 10) recent.resize(10);
  session::LoadedWorld w;
  w.scene = std::const_pointer_cast<vrml::Scene>(scene);
  w.readable = true;
  worlds.push_back(std::move(w));
  return worlds.size() - 1;
}

void WindowState::open(const std::string& path) {
  const std::size_t world = load(path);
  if (world != Viewport::kNone) show(world, active);
}

bool WindowState::openInNewViewport(const std::string& path) {
  const std::size_t world = load(path);
  if (world == Viewport::kNone) return false;
  auto empty = [&] {
    for (std::size_t i = 0; i < viewports.size(); ++i)
      if (viewports[i].world == Viewport::kNone) return i;
    return Viewport::kNone;
  };
  std::size_t target = empty();
  if (target == Viewport::kNone && layout != Layout::quad) {
    const std::size_t before = viewports.size();
    layout = layout == Layout::single ? Layout::sideBySide : Layout::quad;
    viewports.resize(static_cast<std::size_t>(layoutCells(layout)));
    target = before;
  }
  if (target == Viewport::kNone) target = active;
  show(world, target);
  active = target;
  return true;
}

void WindowState::openInputs(const std::vector<std::string>& inputs,
                             const std::vector<double>& lods) {
  std::vector<std::size_t> loaded;
  for (const std::string& input : inputs) loaded.push_back(load(input));
  for (std::size_t i = 0; i < viewports.size(); ++i) {
    if (inputs.size() != 1 && i >= inputs.size()) break;
    const std::size_t world = loaded[inputs.size() == 1 ? 0 : i];
    if (world == Viewport::kNone) continue;
    viewports[i].options = rendererOptions;
    if (!lods.empty()) viewports[i].options.lod = lods[std::min(i, lods.size() - 1)];
    viewports[i].world = world;  // options set: show() keeps them
    show(world, i);
  }
}

void WindowState::show(std::size_t world, std::size_t index) {
  if (world >= worlds.size() || index >= viewports.size()) return;
  Viewport& v = viewports[index];
  if (v.world == Viewport::kNone) {
    v.options = rendererOptions;
  }
  v.world = world;
  makeView(index);
  v.autoFrame = true;
  v.diagnosticsLogged = 0;
  home(v);
}

void WindowState::update() {
  if (updateViews()) {
    for (Viewport& v : viewports)
      if (v.renderer() && v.autoFrame) home(v);
  }
  std::vector<std::pair<bool, std::string>> messages;
  session->drainMessages(messages);
  for (auto& [error, text] : messages) {
    log.push_back({error, std::move(text)});
    if (error) showLog = true;
  }
  followLinks();
  // Problems found while drawing (textures, Inlines), each once.
  for (Viewport& v : viewports) {
    if (!v.renderer()) continue;
    const auto& items = v.renderer()->diagnostics().items;
    for (; v.diagnosticsLogged < items.size(); ++v.diagnosticsLogged) {
      const auto& d = items[v.diagnosticsLogged];
      log.push_back({d.severity == vrml::Severity::error, d.format()});
    }
  }
}

namespace {

double secondsNow() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void WindowState::setNavigation(scene::NavigationMode mode) {
  view().navigator.setMode(mode);
  view().navigationChosen = true;
}

bool WindowState::updateViews() {
  const bool made = !runtimes;
  if (made) {
    runtimes = std::make_unique<session::WorldRuntimes>(time, &session->loader());
    // Clips from the network arrive in the background: a frame never waits for them.
    sounds = std::make_unique<WorldSounds>(true, &session->loader());
    if (!sounds->note().empty()) std::fprintf(stderr, "ghostspace: %s\n", sounds->note().c_str());
    clockOffset = time.set ? time.start - runtime::wallClockSeconds() : 0.0;
    runtimes->setLinkHandler([this](const vrml::Scene& scene, const std::vector<std::string>& url,
                                    const std::vector<std::string>& parameter) {
      links.push_back(
          {&scene, pointerViewport < viewports.size() ? pointerViewport : active, url, parameter});
    });
  }
  const double now = worldTime();
  // Every world opened runs, shown or not (a world a link replaced keeps its clock).
  for (const session::LoadedWorld& w : worlds) runtimes->of(w.scene, now);
  session::ViewGroup& views = viewGroup();
  // MovieTextures follow the window's clock and never hold a frame (docs/media.md).
  if (made) views.attachRuntimes(*runtimes, now, false);
  // The frame step of every viewport (session/world_view.hpp); the active viewport's
  // camera wins for a world two viewports show (ViewGroup::advanceTo sets it last). A
  // window with no view pumps and advances through the group itself.
  const session::WorldView* activeView =
      active < viewports.size() ? viewports[active].worldView.get() : nullptr;
  const std::uint64_t before = views.generation();
  bool any = false;
  for (Viewport& v : viewports) {
    if (!v.worldView) continue;
    any = true;
    v.worldView->update(now, activeView);
  }
  if (!any) {
    views.pump();
    views.advanceTo(now);
  }
  for (Viewport& v : viewports) {
    if (!v.renderer() || v.world >= worlds.size()) continue;
    const runtime::ExecutionModel& model = runtimes->of(worlds[v.world].scene, now);
    const vrml::Node* vp = model.bound(runtime::BindableKind::Viewpoint);
    const std::uint64_t revision = vp ? vrml::revisionWithFields(*vp) : 0;
    if (model.bindingRevision() != v.bindingSeen || vp != v.viewpointSeen ||
        revision != v.viewpointRevisionSeen) {
      // A newly bound or animated Viewpoint takes the camera (4.6.10, 6.53).
      const bool first = v.viewpointSeen == nullptr && v.bindingSeen == 0;
      const bool newlyBound = vp != v.viewpointSeen;
      if (v.offsetsWorld != v.world) {
        v.userOffsets.clear();
        v.offsetsWorld = v.world;
      } else if (newlyBound && v.viewpointSeen != nullptr) {
        // Where the user had moved from the viewpoint now unbound (23.3.5).
        v.userOffsets[v.viewpointSeen] = scene::userOffset(v.navigator.camera(), v.viewpointCamera);
      }
      v.bindingSeen = model.bindingRevision();
      v.viewpointSeen = vp;
      v.viewpointRevisionSeen = revision;
      const scene::Camera defined = v.renderer()->boundViewpointCamera();
      if (!first && vp != nullptr) {
        v.autoFrame = false;
        if (newlyBound) {
          // A Viewpoint bound from the menu, an Anchor or a Script: an animated move, to
          // where the user had left it when it retains user offsets, else to itself.
          v.transition.from = v.navigator.camera();
          const auto kept = v.userOffsets.find(vp);
          v.transition.to = kept != v.userOffsets.end() &&
                                    vp->get<vrml::FieldType::SFBool>("retainUserOffsets", false)
                                ? scene::withUserOffset(defined, kept->second)
                                : defined;
          v.transition.start = secondsNow();
        } else {  // the bound Viewpoint itself moves (a route into its fields)
          v.transition.start = -1.0;
          v.navigator.setCamera(defined);
        }
      }
      if (vp != nullptr) v.viewpointCamera = defined;
    }
  }
  if (sounds && active < viewports.size() && viewports[active].world < worlds.size())
    sounds->update(
        worlds[viewports[active].world].scene, viewports[active].navigator.camera(), *runtimes, now,
        viewports[active].renderer() ? &viewports[active].renderer()->traversal() : nullptr);
  std::vector<std::string> lines;
  runtimes->drainMessages(lines);
  for (std::string& line : lines) {
    log.push_back({true, std::move(line)});
    showLog = true;
  }
  return views.generation() != before;
}

void WindowState::home(Viewport& v) {
  if (!v.renderer()) return;
  // A world's NavigationInfo chooses the navigation; without one, EXAMINE (as most
  // browsers do for a model) rather than VRML97's default WALK.
  const scene::NavigationSettings& nav = v.renderer()->navigation();
  if (!v.navigationChosen)
    v.navigator.setMode(nav.node != nullptr
                            ? scene::navigationModeOf(nav.type, scene::NavigationMode::examine)
                            : scene::NavigationMode::examine);
  const float aspect = static_cast<float>(v.rect.width) / static_cast<float>(v.rect.height);
  // The bound Viewpoint; a world without one is framed whole (a KiCad part, say, lies
  // far from the VRML97 default viewpoint's view), as other browsers do.
  scene::Camera camera = v.renderer()->initialCamera(aspect > 0.0f ? aspect : lastAspect);
  const vrml::Bounds& b = v.renderer()->bounds();
  // Orbit around the point of the view axis nearest the scene's centre.
  glm::vec3 center = camera.position + camera.forward() * 10.0f;
  if (!b.empty()) {
    const float along = glm::dot(b.center() - camera.position, camera.forward());
    center = camera.position + camera.forward() * std::max(along, 1e-3f);
  }
  v.navigator.setSceneBounds(b, v.renderer()->navigation().nearClip());
  v.navigator.setHome(camera, center);
}

bool WindowState::restless() const {
  if (session && !session->settled()) return true;
  if (runtimes && runtimes->animating()) return true;
  for (const Viewport& v : viewports) {
    if (v.transition.start >= 0.0) return true;
    if (v.navigator.mode() == scene::NavigationMode::walk && !v.gravity.settled) return true;
  }
  return false;
}

void WindowState::resetView() {
  view().autoFrame = true;
  home(view());
}

void WindowState::fitToScene() {
  Viewport& v = view();
  if (!v.renderer()) return;
  v.autoFrame = false;
  const scene::Camera fitted = v.renderer()->fitToScene(lastAspect, v.navigator.camera());
  v.navigator.setHome(fitted, v.renderer()->bounds().center());
}

void WindowState::setMode(scene::RenderMode mode) {
  Viewport& v = view();
  v.options.traversal.mode = mode;
  rendererOptions.traversal.mode = mode;  // for viewports made later
  if (!v.renderer()) return;
  const scene::Camera camera = v.navigator.camera();
  makeView(active);
  v.navigator.setCamera(camera);
}

render::ShadingOption WindowState::shading() const {
  const Viewport& v = view();
  if (!runtimes || v.world >= worlds.size()) return rendererOptions.shading;
  return runtimes->shading(worlds[v.world].scene.get());
}

bool WindowState::setShading(render::ShadingOption shading) {
  const Viewport& v = view();
  if (!runtimes || v.world >= worlds.size()) return false;
  return runtimes->setShading(worlds[v.world].scene.get(), shading);
}

void WindowState::setLod(double lod) {
  Viewport& v = view();
  v.options.lod = lod;
  if (v.renderer()) v.renderer()->setLod(lod);
}

void WindowState::setVectorBudget(std::uint64_t vectors) {
  Viewport& v = view();
  v.vectorBudget = vectors;
  if (v.renderer()) v.renderer()->setVectorBudget(vectors);
}

void WindowState::jumpToViewpoint(std::size_t index) {
  Viewport& v = view();
  if (!v.renderer() || index >= v.renderer()->viewpoints().size()) return;
  v.autoFrame = false;
  // The Viewpoints menu binds through the stack (4.6.10): isBound and bindTime go out and
  // updateRuntimes() moves the camera.
  if (auto* node = const_cast<vrml::Node*>(v.renderer()->viewpoints()[index].node);
      node != nullptr && runtimes && v.world < worlds.size()) {
    runtime::ExecutionModel& model = runtimes->of(worlds[v.world].scene, worldTime());
    const int setBind = node->type().findField("set_bind");
    if (setBind >= 0 &&
        model.postEvent(*node, setBind, vrml::FieldValue::make<vrml::FieldType::SFBool>(true))) {
      model.processEvents();
      return;
    }
  }
  v.transition.from = v.navigator.camera();
  v.transition.to = v.renderer()->viewpointCamera(index);
  v.transition.start = secondsNow();
}

void WindowState::saveScreenshot(int width, int height) {
  if (screenshotPath.empty()) return;
  ViewportRect r{0, 0, width, height};
  if (screenshotViewportOnly) r = view().rect;
  try {
    render::writePng(screenshotPath, render::readPixels(r.x, r.y, r.width, r.height));
    log.push_back({false, "screenshot saved to " + screenshotPath});
  } catch (const std::exception& e) {
    log.push_back({true, std::string("screenshot: ") + e.what()});
    showLog = true;
  }
  screenshotPath.clear();
}

std::size_t WindowState::viewportAt(float x, float y, int height) const {
  const float fromBottom = static_cast<float>(height) - y;
  for (std::size_t i = 0; i < viewports.size(); ++i) {
    const ViewportRect& r = viewports[i].rect;
    if (x >= static_cast<float>(r.x) && x < static_cast<float>(r.x + r.width) &&
        fromBottom >= static_cast<float>(r.y) && fromBottom < static_cast<float>(r.y + r.height))
      return i;
  }
  return Viewport::kNone;
}

void WindowState::drawScene(int x, int y, int width, int height) {
  glViewport(x, y, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const double now = secondsNow();
  for (Viewport& v : viewports) {
    if (v.transition.start < 0.0) continue;
    // Smoothstep from the old camera to the Viewpoint's.
    const double t = std::clamp((now - v.transition.start) / 1.0, 0.0, 1.0);
    const float s = static_cast<float>(t * t * (3.0 - 2.0 * t));
    scene::Camera c = v.transition.to;
    c.position = glm::mix(v.transition.from.position, v.transition.to.position, s);
    c.orientation = glm::slerp(v.transition.from.orientation, v.transition.to.orientation, s);
    c.fieldOfView = glm::mix(v.transition.from.fieldOfView, v.transition.to.fieldOfView, s);
    v.navigator.setCamera(c);
    if (t >= 1.0) v.transition.start = -1.0;
  }
  // Linked viewports follow the active one's camera.
  if (view().linked)
    for (Viewport& v : viewports)
      if (&v != &view() && v.linked && v.renderer()) {
        v.navigator.setCamera(view().navigator.camera());
        v.autoFrame = false;
      }
  for (std::size_t i = 0; i < viewports.size(); ++i) {
    Viewport& v = viewports[i];
    v.rect = layoutRect(layout, static_cast<int>(i), width, height);
    v.rect.x += x;
    v.rect.y += y;
    if (i == active)
      lastAspect = static_cast<float>(v.rect.width) / static_cast<float>(v.rect.height);
    if (!v.renderer()) continue;
    const double target = frameTarget / static_cast<double>(viewports.size());
    v.renderer()->setVectorBudget(v.autoLod ? autoLodBudget(v.vectorBudget, v.splatRate, target)
                                            : v.vectorBudget);
    const double t0 = secondsNow();
    v.worldView->setRect(v.rect.x, v.rect.y, v.rect.width, v.rect.height);
    v.worldView->draw();  // step 6 of the frame (session/world_view.hpp)
    const std::uint64_t drawn = v.renderer()->statistics().splats;
    if (v.autoLod && drawn > 0) {
      // Hold the frame-time target: move the fraction by the ratio of target to time
      // taken (damped, at most x2 or /2 a frame). Timing waits for the GPU.
      glFinish();
      const double taken = std::max(secondsNow() - t0, 1e-4);
      v.splatRate = static_cast<double>(drawn) / taken;
      v.options.lod = std::clamp(v.options.lod * autoLodRatio(target, taken), 1e-4, 1.0);
      v.renderer()->setLod(v.options.lod);
    }
  }
}

}  // namespace gs::app
