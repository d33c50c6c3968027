// The VRML97 execution model (ISO/IEC 14772-1:1997 clauses 4.10 "Event processing", 4.11
// "Time", 4.6.10 "Bindable children nodes", 4.12 "Scripting"): the route table, the event
// cascade, the clock, the four bindable stacks, TimeSensors and interpolators, and the
// Script host. Depends on vrml/ only; the renderer reads node fields (and their
// revisions, vrml::Node::revision) and the bound nodes, the application advances the
// clock once a frame. Not thread-safe: use it on the thread that draws.
#pragma once

#include "base/fetch.hpp"
#include "particles/particle_system.hpp"
#include "runtime/clock.hpp"
#include "runtime/keys.hpp"
#include "runtime/media_time.hpp"
#include "runtime/pointer.hpp"
#include "runtime/script_host.hpp"
#include "runtime/viewer.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace gs::runtime {

/// One event as it leaves an eventOut (what --trace-events writes).
struct TraceEvent {
  double timestamp = 0.0;  // seconds (SFTime)
  const vrml::Node* node = nullptr;
  int field = -1;  // index into node->type().fields
  const vrml::FieldValue* value = nullptr;
};

/// How far the loading of an X3DUrlObject node (Inline, ImageTexture, MovieTexture,
/// AudioClip ...) got, as its loader reports it to ExecutionModel::setUrlObjectState
/// (X3D 4.0 clause 9.3.2, "X3DUrlObject", load state). A node never reported is loading.
enum class UrlLoadState : std::uint8_t {
  loading,  // not asked for yet, or bytes on their way
  loaded,   // the content arrived and was read (an Inline's world parsed to its end)
  failed,   // no url could be read or decoded
};

/// The four bindable node types of 4.6.10, each with its own stack.
enum class BindableKind { Viewpoint, NavigationInfo, Background, Fog };
inline constexpr int kBindableKindCount = 4;

/// One browser option of ExecutionOptions::browserOptions: its value and the values it takes.
struct BrowserOption {
  std::string value;
  /// Whether `value` is one the option takes (the browser's own spelling, any case: the
  /// caller's parser); empty: any.
  std::function<bool(const std::string& value)> accepts;
};

struct ExecutionOptions {
  /// Called for every event sent (after loop breaking), in order. Empty: no tracing.
  std::function<void(const TraceEvent&)> trace;
  /// Makes Script instances; empty: Scripts do not run (a warning names each Script).
  ScriptFactory scripts;
  ScriptLimits scriptLimits;
  /// Browser.loadURL and Anchor requests (url list, parameter list); empty: ignored.
  std::function<void(const std::vector<std::string>&, const std::vector<std::string>&)> loadUrl;
  /// Reads Script url files (in the background: a Script waits for its file without
  /// holding a frame; scriptsArriving()) and Browser.createVrmlFromURL texts (whole,
  /// during the call); both resolved against the world's URL, which is the referrer. Not
  /// owned; must outlive the model. Null: local files and data: URLs only.
  base::Fetcher* fetcher = nullptr;
  /// Limit on events handled in one timestamp; past it the cascade stops with a
  /// diagnostic (a guard against routes that multiply events).
  std::size_t maxEventsPerCascade = 1'000'000;
  /// The browser options a Script may read and set (Browser.getBrowserOption /
  /// setBrowserOption), by name ("Shading"), with their values at the load; empty: none.
  std::unordered_map<std::string, BrowserOption> browserOptions;
  /// What the renderer can do (Browser.getRenderingProperty); all zero: not known.
  RenderingProperties rendering;
};

/// Counters for benchmarks and tests.
struct ExecutionStatistics {
  std::uint64_t eventsSent = 0;       // eventOuts that passed loop breaking
  std::uint64_t eventsDelivered = 0;  // eventIns handled
  std::uint64_t eventsDropped = 0;    // stopped by the one-event-per-eventOut-per-timestamp rule
  std::uint64_t cascades = 0;         // timestamps processed
};

class ExecutionModel final : public ScriptContext {
 public:
  /// Loads `scene` at SFTime `loadTime` (seconds): builds the route table from
  /// scene.routes, finds the time-dependent nodes, sensors and Scripts of every node
  /// reachable from the root and hidden nodes, binds the first Viewpoint, NavigationInfo,
  /// Background and Fog in file order (isBound TRUE, bindTime), calls every Script's
  /// initialize(), and evaluates the TimeSensors at loadTime (4.10.3's initial events).
  ExecutionModel(std::shared_ptr<const vrml::Scene> scene, double loadTime,
                 ExecutionOptions options = {});
  ~ExecutionModel() override;
  ExecutionModel(const ExecutionModel&) = delete;
  ExecutionModel& operator=(const ExecutionModel&) = delete;

  /// The scene (or an Inline scene) gained root nodes or routes (progressive loading):
  /// takes the new ones in
  /// as the constructor took the first (new bindable nodes join their stacks' bottom;
  /// the first of a kind is bound when none is).
  void sceneGrew();
  /// Adds the nodes and routes of an Inline's scene (clause 6.25; once per scene): its
  /// routes and sensors run; its bindable nodes are not bound (the renderer's rule too).
  /// An Inline scene that is still streaming is taken in further by sceneGrew().
  void addInlineScene(std::shared_ptr<const vrml::Scene> scene);
  /// Inline node `inlineNode` shows the world `scene` (null: none yet; ignored): when
  /// Browser.replaceWorld unloads the Inline node, its world is unloaded too, unless an
  /// Inline that stays shows it; a world so unloaded is taken again by addInlineScene()
  /// only once an Inline that was not unloaded shows it. Call it before addInlineScene()
  /// for the Inline nodes a frame met (session::WorldRuntimes::addInlines does).
  void noteInlineWorld(const vrml::Node& inlineNode, const vrml::Scene* scene);

  /// The world's own file was read to its end (`complete`), or its stream ended short
  /// (failed, or stopped): the X3D Scripts' browser callbacks for INITIALIZED_EVENT, or
  /// for INITIALIZED_ERROR when not `complete`, run once (ISO/IEC 19777-1 7.2; a later
  /// call does nothing), after the Scripts made so far ran initialize(). Inline worlds,
  /// textures and Script files still arriving do not hold it back (X_ITE 15's load count
  /// waits for them too). session::WorldRuntimes calls it when StreamingSession says the
  /// world's stream ended.
  void worldLoaded(bool complete = true);
  /// A world this one asked for (Browser.loadURL, an Anchor) could not be opened: the X3D
  /// Scripts' callbacks for INITIALIZED_ERROR run, as X_ITE 15's loadURL calls them when
  /// its file fails (the world stays). Each call sends the event once more.
  void linkFailed();

  /// Moves the clock to `time` (ignored when earlier) and runs one cascade: every
  /// enabled TimeSensor is evaluated, then the events they send, the events queued by
  /// sendEvent() and the Scripts' eventsProcessed() run to completion.
  void advanceTo(double time);
  /// advanceTo(now() + duration) in steps of at most `step` seconds (> 0): how the
  /// headless path moves time deterministically.
  void advanceBy(double duration, double step);
  double now() const override { return clock_.now(); }

  /// Sends `value` to eventIn (or exposedField) `field` of `node` from outside the
  /// graph (the user interface, a test): processed at the next advanceTo, or now with
  /// processEvents(). False (with a diagnostic) when the field cannot take an event of
  /// that type.
  bool postEvent(vrml::Node& node, int field, vrml::FieldValue value);
  /// Runs the events posted since the last cascade as a new timestamp at now().
  void processEvents();

  /// Where the viewer is now: ProximitySensors (6.38) and VisibilitySensors (6.52) compare
  /// it with their boxes at the next advanceTo(). Until the first call there is no viewer
  /// and these sensors stay inactive.
  void setViewer(const ViewerPose& viewer);

  /// The pointing device moved, or its button went down or up (4.6.7, runtime/pointer.hpp):
  /// one new timestamp at now() for TouchSensor, PlaneSensor, SphereSensor,
  /// CylinderSensor and Anchor (a click binds `#Name` Viewpoints or calls
  /// ExecutionOptions::loadUrl). Returns true while a sensor or Anchor holds the pointer
  /// (pressed on one): the application then does not navigate with this drag.
  bool pointer(const PointerEvent& event);
  /// Whether a sensor or an Anchor is under the pointer (or holds it), and the Anchor's
  /// description, as of the last pointer() call.
  PointerHint pointerHint() const;
  /// Whether pointer() can matter: the world has a pointing-device sensor, an Anchor or an
  /// Inline (whose sensors are found when picked), or a sensor holds the pointer. The
  /// application skips picking when false.
  bool wantsPointer() const;

  /// A key went down (X3D 4.0 clause 21, runtime/keys.hpp) at SFTime `time` (seconds):
  /// when `time` is later than now() the clock first moves there (advanceTo(time), so
  /// TimeSensors run as in a frame); an earlier time counts as now(). Then one new
  /// timestamp at now() in which every enabled KeySensor (21.4.1) and StringSensor
  /// (21.4.2) of the world reacts, in the order the execution model met them:
  /// - KeySensor: isActive TRUE when it held no key; then keyPress (SFString, the
  ///   character as UTF-8) for a character, actionKeyPress (SFInt32, table 21.2) for an
  ///   action key, or shiftKey / controlKey / altKey TRUE for a modifier. A key pressed
  ///   again before its release (auto-repeat) sends keyPress / actionKeyPress again, no
  ///   isActive (a repeated modifier sends nothing).
  /// - StringSensor: a printable character (not below U+0020, not U+007F) appends to
  ///   enteredText (isActive TRUE first when inactive); kKeyBackspace removes the last
  ///   character when deletionAllowed and the text is not empty; kKeyEnter, while
  ///   active, sends finalText (the text), enteredText "" and isActive FALSE. Other
  ///   keys are ignored.
  /// Sensors whose enabled is FALSE ignore keys. An invalid key (Key::valid()) is
  /// ignored without a timestamp.
  void keyPress(const Key& key, double time);
  /// A key went up, at SFTime `time` as keyPress() takes it. A KeySensor that saw the key
  /// go down (while enabled) sends keyRelease / actionKeyRelease or shiftKey /
  /// controlKey / altKey FALSE, then isActive FALSE once it holds no key; a key it did
  /// not see go down is ignored. StringSensors ignore releases.
  void keyRelease(const Key& key, double time);
  /// Whether the world has a KeySensor or StringSensor whose enabled is TRUE (the
  /// application then lets the world have the keyboard: no keyboard navigation).
  bool wantsKeys() const;

  /// The avatar collided with the children (or proxy) of `collisionNodes` (Collision,
  /// 6.8; scene::walkStep says which): one new timestamp at now() in which each sends
  /// collideTime = now(). Nodes that are not Collision nodes are ignored.
  void collided(const std::vector<vrml::Node*>& collisionNodes);

  /// Output events that drawing computed (vrml/drawn_output.hpp: a LOD's or GeoLOD's
  /// level_changed and children, a shader's isValid and isSelected, a TextureProjector's
  /// aspectRatio): one new timestamp at now() in which each is sent by its node, in order.
  /// An output of a node this world does not hold, of a field its type lacks, or of a value
  /// of another type is ignored; nothing is sent when none is left. The levels a LOD and a
  /// GeoLOD show are kept: the walks of ProximitySensor, VisibilitySensor, TransformSensor
  /// and the picking sensors follow them (the first level, the root, until one is told).
  void sendDrawnOutputs(const vrml::DrawnOutputs& outputs);

  /// The top of a bindable stack (4.6.10), or null when the stack is empty.
  vrml::Node* bound(BindableKind kind) const;
  /// Counts changes of any bindable stack's top: a renderer rereads bound nodes when it
  /// differs from what it saw.
  std::uint64_t bindingRevision() const { return bindingRevision_; }
  /// Every node of a stack, bottom first (for tests).
  std::vector<vrml::Node*> bindStack(BindableKind kind) const;

  /// MovieTexture (6.28) and AudioClip (6.3), runtime/media_time.hpp. The application
  /// that decoded `node`'s media reports its duration in seconds (-1: unreadable): a
  /// duration_changed event goes out at now() (once per distinct value) and the node,
  /// which cannot become active before its duration is known, is evaluated at once.
  /// Ignored for other nodes. It is also the node's load report for LoadSensors
  /// (setUrlObjectState): a duration means loaded, -1 failed.
  void setMediaDuration(const vrml::Node& node, double seconds);
  /// The media state of a MovieTexture or AudioClip of this world as of the last cascade
  /// (media time, isActive, duration); empty for other nodes.
  std::optional<MediaState> media(const vrml::Node& node) const;
  /// media(node)->mediaTime when `node` is a media node of this world: the seconds into
  /// the clip to show or play now.
  std::optional<double> mediaTime(const vrml::Node& node) const;
  /// The simulation of ParticleSystem `node` of this world (X3D 4.0 clause 40; moved by
  /// every advanceTo(), runtime/src/particle_systems.cpp), or null when `node` is none.
  const particles::ParticleSimulation* particleSimulation(const vrml::Node& node) const;

  /// X3D LoadSensor (X3D 4.0 clause 9.4.3, runtime/src/load_sensors.cpp): whoever loads
  /// `node`'s url (session::WorldRuntimes for Inlines and textures; setMediaDuration for
  /// MovieTexture and AudioClip) reports how far it got. A change of state opens one new
  /// timestamp at now() in which every enabled LoadSensor watching `node` is evaluated:
  /// all its watched nodes loaded: progress 1, isLoaded TRUE, loadTime = now(), then
  /// isActive FALSE; one failed: isLoaded FALSE, isActive FALSE; otherwise progress (the
  /// fraction of its watched nodes loaded) when it changed. A report of the state the node
  /// already has does nothing; so does one for a node no LoadSensor watches (it is kept for
  /// sensors that start watching later).
  void setUrlObjectState(const vrml::Node& node, UrlLoadState state);
  /// The state last reported for `node` (loading when none was).
  UrlLoadState urlObjectState(const vrml::Node& node) const;

  /// Records that the world's IMPORT `localName` stands for `node` (its Inline's world
  /// arrived and EXPORTs it; session::WorldRuntimes), for Scripts' getImportedNode.
  void setImportedNode(const std::string& localName, vrml::NodePtr node);

  const vrml::Diagnostics& diagnostics() const { return diagnostics_; }
  const ExecutionStatistics& statistics() const { return stats_; }
  /// Scripts not made yet because a url file they may run from is still on its way
  /// (ExecutionOptions::fetcher, FetchMode::background): each is made and initialized at
  /// the first advanceTo() or sceneGrew() after its file answered (arrived or failed).
  std::size_t scriptsArriving() const;
  /// Whether anything in the world may still change without input: an active
  /// TimeSensor, a Script with pending work, an active LoadSensor with a timeOut.
  bool animating() const;

  // ---- ScriptContext ----
  void emitScriptEvent(vrml::Node& script, int field, vrml::FieldValue value) override;
  void sendEvent(vrml::Node& node, int field, vrml::FieldValue value) override;
  double frameRate() const override { return frameRate_; }
  void setFrameRate(double fps) { frameRate_ = fps; }
  std::string worldUrl() const override;
  bool addRoute(const vrml::NodePtr& from, const std::string& eventOut, const vrml::NodePtr& to,
                const std::string& eventIn) override;
  bool deleteRoute(const vrml::NodePtr& from, const std::string& eventOut, const vrml::NodePtr& to,
                   const std::string& eventIn) override;
  bool hasRoute(const vrml::NodePtr& from, const std::string& eventOut, const vrml::NodePtr& to,
                const std::string& eventIn) const override;
  std::vector<vrml::NodePtr> createVrmlFromString(const std::string& text) override;
  std::shared_ptr<vrml::Scene> createSceneFromString(const std::string& text,
                                                     const vrml::Node* script,
                                                     const std::string& url = {}) override;
  const vrml::Scene* currentScene() const override;
  const vrml::Scene* sceneOf(const vrml::Node& script) const override;
  vrml::NodePtr importedNode(const std::string& localName) const override;
  /// The world's Scene changes: it must not be an object defined const (the session makes
  /// it with std::make_shared<vrml::Scene>); nor an Inline's world (the Inline loader
  /// makes each with std::make_shared<vrml::Scene>), whose roots changeInlineRoots changes.
  bool addRootNode(const vrml::NodePtr& node) override;
  bool removeRootNode(const vrml::NodePtr& node) override;
  bool changeInlineRoots(const vrml::Scene& scene, const vrml::NodePtr& node, bool add) override;
  void loadUrl(const std::vector<std::string>& url,
               const std::vector<std::string>& parameter) override;
  bool fetchText(const std::string& url, std::string& text, std::string& error) override;
  void replaceWorld(const std::vector<vrml::NodePtr>& nodes) override;
  /// Whether a Script replaced the world (Browser.replaceWorld): the world's own file,
  /// if it still streams, must add no more root nodes (session::WorldRuntimes then stops
  /// its stream).
  bool worldReplaced() const;
  void setDescription(const std::string& text) override;
  const std::string* browserOption(const std::string& name) const override;
  bool setBrowserOption(const std::string& name, const std::string& value) override;
  const RenderingProperties* renderingProperties() const override;
  void print(const std::string& text) override;
  void scriptDiagnostic(vrml::Severity severity, const vrml::SourceLocation& where,
                        const std::string& message) override;

  /// Implementation state (runtime/src/); public so its parts can be split over files.
  struct State;

 private:
  std::unique_ptr<State> s_;
  Clock clock_;
  ExecutionOptions options_;
  ExecutionStatistics stats_;
  vrml::Diagnostics diagnostics_;
  std::uint64_t bindingRevision_ = 0;
  double frameRate_ = 0.0;
  std::unordered_map<std::string, vrml::NodePtr> imported_;  // setImportedNode
  /// Runs every Script's browser callbacks for `event`, then the cascade they start.
  void sendBrowserEvent(BrowserEvent event);
  /// Counts the nodes of `made` (a Script's text, parsed) among the Scripts' made nodes;
  /// throws ScriptLimitError, counting none, when they would pass ScriptLimits::madeNodes.
  void countMadeNodes(const vrml::Scene& made);
  friend struct State;
};

}  // namespace gs::runtime
