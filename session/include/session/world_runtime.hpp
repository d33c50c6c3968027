// The execution model of each world a session shows (docs/runtime.md): one
// runtime::ExecutionModel per scene, shared by every viewport that shows it, moved by one
// clock: the wall clock in a window, the virtual clock of --time for --snapshot.
#pragma once

#include "render/browser_options.hpp"
#include "render/scene_renderer.hpp"
#include "runtime/execution_model.hpp"
#include "scene/traversal.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/scene.hpp"

#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <unordered_set>
#include <vector>

namespace gs::session {

/// --time, --time-step, --trace-events and the Script limits (README.md, "Animation,
/// interaction and Scripts").
struct RuntimeOptions {
  bool set = false;       // --time was given
  double start = 0.0;     // T or T0: SFTime seconds (since 1970-01-01 UTC)
  double interval = 0.0;  // DT of T0:DT:N, seconds between frames
  int frames = 1;         // N of T0:DT:N; 1 for a single time
  /// --load-time S: SFTime the worlds load at with --snapshot, then run to T (or T0) at
  /// the fixed step; negative: they load at T (T0). Never after T.
  double load = -1.0;
  double step = 1.0 / 60.0;  // --time-step S: the cascade's fixed step, seconds, > 0
  std::string traceFile;     // --trace-events FILE: one JSON line per event
  bool scripts = true;       // --no-scripts: Script nodes do not run
  /// --script-time-limit S (seconds of one Script call) and --script-memory-limit MB.
  runtime::ScriptLimits scriptLimits;
  /// --shading: the browser option Shading each world starts with; its Scripts may read it
  /// and set it (Browser.getBrowserOption / setBrowserOption("Shading", ...)).
  render::ShadingOption shading = render::ShadingOption::phong;
  /// The picture's samples per pixel (what the window's or the snapshot's context got for
  /// --samples, render::drawFramebufferSamples): Browser.getRenderingProperty("Antialiased")
  /// is true above 1.
  int samples = 1;
};

/// The viewer pose the execution model's sensors see for a camera drawn at `aspect`
/// (width / height).
runtime::ViewerPose viewerPose(const scene::Camera& camera, float aspect);

/// Parses --time "T" or "T0:DT:N" (T0 >= 0, DT > 0, 1 <= N <= 100000). False when
/// malformed; the fields are then unchanged.
bool parseTimeOption(const std::string& text, RuntimeOptions& out);

/// The file a frame of a --time T0:DT:N strip goes to: `path` with "-NNNN" (frame index,
/// four digits) before its extension ("out.png" -> "out-0003.png"); `path` itself when
/// frames == 1.
std::string framePath(const std::string& path, int frame, int frames);

class WorldRuntimes {
 public:
  /// Traces go to `options.traceFile` when set (an error opening it throws
  /// std::runtime_error naming the file).
  /// Script files are read through `fetcher` (the session's net::Loader; null: local files
  /// only; not owned, must outlive the runtimes).
  explicit WorldRuntimes(const RuntimeOptions& options, base::Fetcher* fetcher = nullptr);
  ~WorldRuntimes();
  WorldRuntimes(const WorldRuntimes&) = delete;
  WorldRuntimes& operator=(const WorldRuntimes&) = delete;

  /// The execution model of `scene`, made (loaded at `time`, seconds) on first use.
  runtime::ExecutionModel& of(const std::shared_ptr<const vrml::Scene>& scene, double time);
  /// Every world's clock to `time` (seconds) in steps of at most the --time-step. First, a
  /// world whose file has been read to its end, or whose stream ended short (the world
  /// load state function; unset: read whole, at once) hears so
  /// (runtime::ExecutionModel::worldLoaded: INITIALIZED_EVENT or INITIALIZED_ERROR).
  void advanceTo(double time);
  /// A link `scene` asked for (a Script's Browser.loadURL, an Anchor) was refused or its
  /// world could not be opened: its Scripts hear INITIALIZED_ERROR
  /// (runtime::ExecutionModel::linkFailed). A scene without runtime is ignored.
  void linkFailed(const vrml::Scene* scene);
  /// The Inline worlds `traversal` (a renderer of `scene`) loaded since the last call
  /// join `scene`'s execution model (their routes and sensors run), and the ROUTEs of
  /// `scene` to or from IMPORTed nodes (vrml::X3dImportedRoute, X3D clause 4.4.6) whose
  /// Inline has arrived are added (a name the Inline does not EXPORT is a diagnostic).
  /// The Inline nodes `traversal` met report their load state to the execution model's
  /// LoadSensors (runtime::ExecutionModel::setUrlObjectState): failed when no url could be
  /// loaded, otherwise the state of its world as the world load state function says
  /// (setWorldLoadState; unset: loaded).
  void addInlines(const vrml::Scene* scene, const scene::SceneTraversal& traversal);
  /// How far an Inline's world got while it streams in (StreamingSession::worldLoadState).
  using WorldLoadState = std::function<runtime::UrlLoadState(const vrml::Scene&)>;
  void setWorldLoadState(WorldLoadState state) { worldLoadState_ = std::move(state); }
  /// What stops the stream of a world whose Script replaced it (Browser.replaceWorld;
  /// StreamingSession::abandonWorld), called once per world after the advance that
  /// replaced it; the world then counts as loaded (no INITIALIZED_ERROR for its stream).
  using WorldStop = std::function<void(const vrml::Scene&)>;
  void setWorldStop(WorldStop stop) { worldStop_ = std::move(stop); }
  /// X3D LoadSensor: the url objects whose loading ended (true: loaded, false: failed;
  /// render::SceneRenderer::takeUrlObjectLoads) go to `scene`'s execution model
  /// (runtime::ExecutionModel::setUrlObjectState); ignored when it has none yet.
  void setUrlObjectLoads(const vrml::Scene* scene,
                         const std::vector<std::pair<const vrml::Node*, bool>>& loads);
  /// Output events that drawing computed (render::SceneRenderer::takeDrawnOutputs) go to
  /// `scene`'s execution model (runtime::ExecutionModel::sendDrawnOutputs); ignored for a
  /// scene without one.
  void sendDrawnOutputs(const vrml::Scene* scene, const vrml::DrawnOutputs& outputs);
  /// The viewer of `scene`'s world (ProximitySensor, VisibilitySensor); ignored when the
  /// world has no execution model yet.
  void setViewer(const vrml::Scene* scene, const runtime::ViewerPose& viewer);
  /// Tells every world that its scene grew (progressive loading).
  void scenesGrew();
  /// Where Anchor clicks and Browser.loadURL go (after `#Name` links, which the runtime
  /// binds itself): the scene that asked, its url list and parameter list. Unset (the
  /// headless default): each request is written to stderr. Set it before of().
  using LinkHandler =
      std::function<void(const vrml::Scene& scene, const std::vector<std::string>& url,
                         const std::vector<std::string>& parameter)>;
  void setLinkHandler(LinkHandler handler) { link_ = std::move(handler); }
  /// The nodes bound in `scene`'s execution model; nothing bound when it has none.
  scene::BoundNodes bound(const vrml::Scene* scene) const;
  /// MovieTexture and AudioClip (docs/media.md): the media clock a renderer of `scene`
  /// reads (runtime::ExecutionModel::mediaTime; empty before the world runs), and the
  /// durations its decoders found, handed to the execution model.
  render::MediaClock mediaClock(const vrml::Scene* scene) const;
  void setMediaDurations(const vrml::Scene* scene,
                         const std::vector<std::pair<const vrml::Node*, double>>& durations);
  /// ParticleSystems (X3D 4.0 clause 40): where a traversal of `scene` finds their
  /// particles (runtime::ExecutionModel::particleSimulation; none before the world runs).
  scene::ParticleSource particleSource(const vrml::Scene* scene) const;
  /// The browser option Shading of `scene`'s world: what its Scripts set last, or
  /// RuntimeOptions::shading (also before the world runs).
  render::ShadingOption shading(const vrml::Scene* scene) const;
  /// Sets the browser option Shading of `scene`'s world, as its Scripts'
  /// Browser.setBrowserOption("Shading", ...) does (the window's View > Shading): every
  /// viewport of that world draws with it from the next frame, and its Scripts read it.
  /// False when the world does not run yet (nothing changed).
  bool setShading(const vrml::Scene* scene, render::ShadingOption shading);
  /// Whether any world may change without input (runtime::ExecutionModel::animating:
  /// an active TimeSensor or media node, a Script with pending work, a LoadSensor's
  /// timeOut still to pass): the window keeps drawing while true.
  bool animating() const {
    for (const auto& [scene, e] : worlds_)
      if (e.model && e.model->animating()) return true;
    return false;
  }
  /// Diagnostics of every world not returned before, formatted, appended to `out`.
  void drainMessages(std::vector<std::string>& out);

 private:
  RuntimeOptions options_;
  base::Fetcher* fetcher_ = nullptr;
  std::FILE* trace_ = nullptr;
  LinkHandler link_;
  WorldLoadState worldLoadState_;
  WorldStop worldStop_;
  struct Entry {
    std::shared_ptr<const vrml::Scene> scene;
    std::unique_ptr<runtime::ExecutionModel> model;
    bool loaded = false;    // ExecutionModel::worldLoaded was called
    bool replaced = false;  // a Script replaced the world: its stream was stopped
    std::size_t diagnosticsShown = 0;
    std::vector<char> importedRouteDone;  // per scene->x3d.importedRoutes
    std::vector<char> importKnown;        // per scene->x3d.imports: resolved or missing
    /// Inline nodes whose load ended (loaded or failed): not asked about again.
    std::unordered_set<const vrml::Node*> inlinesSettled;
  };
  std::map<const vrml::Scene*, Entry> worlds_;
  void resolveImportedRoutes(Entry& e, const scene::SceneTraversal& traversal);
};

}  // namespace gs::session
