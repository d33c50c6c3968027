#include "session/world_runtime.hpp"
#include "base/url.hpp"

#include "runtime/script_ecmascript.hpp"
#include "runtime/trace.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace gs::session {

namespace {

bool parseNumber(std::string_view text, double& out) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(out);
}

}  // namespace

runtime::ViewerPose viewerPose(const scene::Camera& camera, float aspect) {
  runtime::ViewerPose v;
  v.position = camera.position;
  v.orientation = camera.orientation;
  v.fieldOfView = camera.fieldOfView;
  v.aspect = aspect > 0.0f ? aspect : 1.0f;
  v.nearClip = camera.nearClip;
  v.farClip = camera.farClip;
  return v;
}

bool parseTimeOption(const std::string& text, RuntimeOptions& out) {
  const std::size_t a = text.find(':');
  RuntimeOptions t = out;
  if (a == std::string::npos) {
    if (!parseNumber(text, t.start) || t.start < 0.0) return false;
    t.interval = 0.0;
    t.frames = 1;
  } else {
    const std::size_t b = text.find(':', a + 1);
    if (b == std::string::npos) return false;
    double n = 0.0;
    if (!parseNumber(std::string_view(text).substr(0, a), t.start) ||
        !parseNumber(std::string_view(text).substr(a + 1, b - a - 1), t.interval) ||
        !parseNumber(std::string_view(text).substr(b + 1), n))
      return false;
    if (t.start < 0.0 || !(t.interval > 0.0) || n < 1.0 || n > 100000.0 || n != std::floor(n))
      return false;
    t.frames = static_cast<int>(n);
  }
  t.set = true;
  out = t;
  return true;
}

std::string framePath(const std::string& path, int frame, int frames) {
  if (frames <= 1) return path;
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "-%04d", frame);
  const std::size_t slash = path.find_last_of('/');
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return path + suffix;
  return path.substr(0, dot) + suffix + path.substr(dot);
}

WorldRuntimes::WorldRuntimes(const RuntimeOptions& options, base::Fetcher* fetcher)
    : options_(options), fetcher_(fetcher) {
  if (!options_.traceFile.empty()) {
    trace_ = std::fopen(options_.traceFile.c_str(), "w");
    if (trace_ == nullptr)
      throw std::runtime_error("cannot write '" + options_.traceFile +
                               "': " + std::strerror(errno));
  }
}

WorldRuntimes::~WorldRuntimes() {
  worlds_.clear();  // Scripts' shutdown() may still trace
  if (trace_ != nullptr) std::fclose(trace_);
}

runtime::ExecutionModel& WorldRuntimes::of(const std::shared_ptr<const vrml::Scene>& scene,
                                           double time) {
  Entry& e = worlds_[scene.get()];
  if (!e.model) {
    e.scene = scene;
    runtime::ExecutionOptions o;
    if (trace_ != nullptr)
      o.trace = [f = trace_](const runtime::TraceEvent& ev) {
        const std::string line = runtime::traceJson(ev);
        std::fprintf(f, "%s\n", line.c_str());
      };
    o.loadUrl = [this, s = scene.get()](const std::vector<std::string>& url,
                                        const std::vector<std::string>& parameter) {
      if (link_) {
        link_(*s, url, parameter);
        return;
      }
      // Headless: the request is reported, never followed (README.md, "Links").
      std::string line = "ghostspace: link requested by " + s->url + ":";
      for (const std::string& u : url) line += " \"" + u + "\"";
      if (!parameter.empty()) line += " parameter";
      for (const std::string& p : parameter) line += " \"" + p + "\"";
      std::fprintf(stderr, "%s\n", line.c_str());
    };
    if (options_.scripts) o.scripts = runtime::ecmascriptFactory();
    o.scriptLimits = options_.scriptLimits;
    o.fetcher = fetcher_;
    // The browser options a Script may read and set (render/browser_options.hpp).
    o.browserOptions["Shading"] = {std::string(render::shadingName(options_.shading)),
                                   [](const std::string& value) {
                                     render::ShadingOption parsed;
                                     return render::parseShadingOption(value, parsed);
                                   }};
    // What the renderer can do (Browser.getRenderingProperty): its fixed limits, the
    // samples, and 8 bits per colour channel (the window's and the snapshot's RGB8).
    const render::RenderingLimits limits = render::renderingLimits();
    o.rendering = {limits.maxTextureSize, limits.textureUnits, limits.maxLights,
                   options_.samples > 1, 24};
    e.model = std::make_unique<runtime::ExecutionModel>(scene, time, std::move(o));
  }
  return *e.model;
}

void WorldRuntimes::advanceTo(double time) {
  for (auto& [key, e] : worlds_) {
    if (!e.loaded) {
      const runtime::UrlLoadState state =
          worldLoadState_ ? worldLoadState_(*e.scene) : runtime::UrlLoadState::loaded;
      if (state != runtime::UrlLoadState::loading) {
        e.loaded = true;
        e.model->worldLoaded(state == runtime::UrlLoadState::loaded);
      }
    }
    const double now = e.model->now();
    if (time > now) e.model->advanceBy(time - now, options_.step);
    if (!e.replaced && e.model->worldReplaced()) {
      e.replaced = true;
      e.loaded = true;  // its stream's end is no event of the new world
      if (worldStop_) worldStop_(*e.scene);
    }
  }
}

void WorldRuntimes::linkFailed(const vrml::Scene* scene) {
  const auto it = worlds_.find(scene);
  if (it != worlds_.end()) it->second.model->linkFailed();
}

void WorldRuntimes::addInlines(const vrml::Scene* scene, const scene::SceneTraversal& traversal) {
  const auto it = worlds_.find(scene);
  if (it == worlds_.end()) return;
  // Which Inline shows which world (an Inline that Browser.replaceWorld unloads takes its
  // world along), then each scene is taken once (addInlineScene ignores the ones it has).
  for (const scene::SceneTraversal::InlineLoad& load : traversal.inlineLoads())
    it->second.model->noteInlineWorld(*load.node, load.scene.get());
  for (const auto& s : traversal.inlineScenes()) it->second.model->addInlineScene(s);
  resolveImportedRoutes(it->second, traversal);
  // X3D LoadSensor (X3D 4.0 clause 9.4.3): each Inline's load state until it settles.
  Entry& e = it->second;
  for (const scene::SceneTraversal::InlineLoad& load : traversal.inlineLoads()) {
    if (e.inlinesSettled.contains(load.node)) continue;
    runtime::UrlLoadState state = runtime::UrlLoadState::failed;
    if (load.scene)
      state = worldLoadState_ ? worldLoadState_(*load.scene) : runtime::UrlLoadState::loaded;
    if (state != runtime::UrlLoadState::loading) e.inlinesSettled.insert(load.node);
    e.model->setUrlObjectState(*load.node, state);
  }
}

void WorldRuntimes::sendDrawnOutputs(const vrml::Scene* scene, const vrml::DrawnOutputs& outputs) {
  if (outputs.empty()) return;
  const auto it = worlds_.find(scene);
  if (it != worlds_.end()) it->second.model->sendDrawnOutputs(outputs);
}

void WorldRuntimes::setUrlObjectLoads(
    const vrml::Scene* scene, const std::vector<std::pair<const vrml::Node*, bool>>& loads) {
  const auto it = worlds_.find(scene);
  if (it == worlds_.end()) return;
  for (const auto& [node, loaded] : loads)
    it->second.model->setUrlObjectState(
        *node, loaded ? runtime::UrlLoadState::loaded : runtime::UrlLoadState::failed);
}

void WorldRuntimes::resolveImportedRoutes(Entry& e, const scene::SceneTraversal& traversal) {
  const vrml::X3dInfo& x3d = e.scene->x3d;
  // The node an IMPORT's local name stands for, once its Inline's world has arrived:
  // null while it has not; `missing` set when it arrived without that EXPORT.
  auto importedNode = [&](const std::string& local, bool& missing) -> vrml::NodePtr {
    for (const vrml::X3dImport& im : x3d.imports) {
      if (im.localName != local || !im.inlineNode) continue;
      const auto inlined = traversal.loadedInline(*im.inlineNode);
      if (!inlined) return nullptr;
      for (const vrml::X3dExport& ex : inlined->x3d.exports)
        if (ex.exportedName == im.exportedName) return ex.node;
      missing = true;
      return nullptr;
    }
    missing = true;
    return nullptr;
  };
  // What Scripts' getImportedNode answers (each IMPORT once its node is known).
  e.importKnown.resize(x3d.imports.size(), 0);
  for (std::size_t i = 0; i < x3d.imports.size(); ++i) {
    if (e.importKnown[i]) continue;
    bool missing = false;
    if (vrml::NodePtr n = importedNode(x3d.imports[i].localName, missing)) {
      e.model->setImportedNode(x3d.imports[i].localName, std::move(n));
      e.importKnown[i] = 1;
    } else if (missing) {
      e.importKnown[i] = 1;
    }
  }
  if (x3d.importedRoutes.empty()) return;
  e.importedRouteDone.resize(x3d.importedRoutes.size(), 0);
  for (std::size_t i = 0; i < x3d.importedRoutes.size(); ++i) {
    if (e.importedRouteDone[i]) continue;
    const vrml::X3dImportedRoute& r = x3d.importedRoutes[i];
    bool missing = false;
    const vrml::NodePtr from = r.fromNode ? r.fromNode : importedNode(r.fromImport, missing);
    const vrml::NodePtr to = r.toNode ? r.toNode : importedNode(r.toImport, missing);
    if (missing) {
      e.importedRouteDone[i] = 1;
      e.model->scriptDiagnostic(
          vrml::Severity::error, r.location,
          "ROUTE to or from an IMPORTed node the Inline does not EXPORT (X3D 4.4.6)");
      continue;
    }
    if (!from || !to) continue;  // an Inline still loading
    e.importedRouteDone[i] = 1;
    e.model->addRoute(from, r.fromField, to, r.toField);
  }
}

void WorldRuntimes::setViewer(const vrml::Scene* scene, const runtime::ViewerPose& viewer) {
  const auto it = worlds_.find(scene);
  if (it != worlds_.end()) it->second.model->setViewer(viewer);
}

void WorldRuntimes::scenesGrew() {
  for (auto& [key, e] : worlds_) e.model->sceneGrew();
}

scene::BoundNodes WorldRuntimes::bound(const vrml::Scene* scene) const {
  scene::BoundNodes b;
  const auto it = worlds_.find(scene);
  if (it == worlds_.end()) return b;
  const runtime::ExecutionModel& m = *it->second.model;
  b.viewpoint = m.bound(runtime::BindableKind::Viewpoint);
  b.navigationInfo = m.bound(runtime::BindableKind::NavigationInfo);
  b.background = m.bound(runtime::BindableKind::Background);
  b.fog = m.bound(runtime::BindableKind::Fog);
  return b;
}

render::ShadingOption WorldRuntimes::shading(const vrml::Scene* scene) const {
  render::ShadingOption shading = options_.shading;
  const auto it = worlds_.find(scene);
  if (it == worlds_.end() || !it->second.model) return shading;
  if (const std::string* value = it->second.model->browserOption("Shading"))
    render::parseShadingOption(*value, shading);
  return shading;
}

bool WorldRuntimes::setShading(const vrml::Scene* scene, render::ShadingOption shading) {
  const auto it = worlds_.find(scene);
  if (it == worlds_.end() || !it->second.model) return false;
  return it->second.model->setBrowserOption("Shading", std::string(render::shadingName(shading)));
}

render::MediaClock WorldRuntimes::mediaClock(const vrml::Scene* scene) const {
  return [this, scene](const vrml::Node& node) -> std::optional<double> {
    const auto it = worlds_.find(scene);
    if (it == worlds_.end()) return std::nullopt;
    return it->second.model->mediaTime(node);
  };
}

scene::ParticleSource WorldRuntimes::particleSource(const vrml::Scene* scene) const {
  return [this, scene](const vrml::Node& node) -> const particles::ParticleSimulation* {
    const auto it = worlds_.find(scene);
    if (it == worlds_.end()) return nullptr;
    return it->second.model->particleSimulation(node);
  };
}

void WorldRuntimes::setMediaDurations(
    const vrml::Scene* scene, const std::vector<std::pair<const vrml::Node*, double>>& durations) {
  const auto it = worlds_.find(scene);
  if (it == worlds_.end()) return;
  for (const auto& [node, seconds] : durations) it->second.model->setMediaDuration(*node, seconds);
}

void WorldRuntimes::drainMessages(std::vector<std::string>& out) {
  for (auto& [key, e] : worlds_) {
    const auto& items = e.model->diagnostics().items;
    for (; e.diagnosticsShown < items.size(); ++e.diagnosticsShown)
      out.push_back(items[e.diagnosticsShown].format());
  }
}

}  // namespace gs::session
