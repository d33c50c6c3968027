// State of the window application: the worlds opened, the viewports that show them (each
// with its own renderer, camera, level of detail and mode), the log of diagnostics. The
// ImGui panels read and change it.
#pragma once

#include "app/layout.hpp"
#include "app/world_sound.hpp"
#include "render/scene_renderer.hpp"
#include "runtime/keys.hpp"
#include "runtime/pointer.hpp"
#include "scene/camera.hpp"
#include "session/streaming_session.hpp"
#include "session/world.hpp"
#include "session/world_runtime.hpp"
#include "session/world_view.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace gs::app {

/// One line of the log panel.
struct LogLine {
  bool error = false;
  std::string text;
};

/// One cell of the layout. Worlds are shared: two viewports showing the same world
/// share its scene and its streams (loaded once), each with its own session::WorldView
/// (its renderer; the frame step that --snapshot runs too).
struct Viewport {
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::size_t world = kNone;  // index into WindowState::worlds
  /// The world's view in this cell (WindowState::viewGroup()); null while empty.
  std::unique_ptr<session::WorldView> worldView;
  /// The view's renderer; null while empty.
  render::SceneRenderer* renderer() const { return worldView ? &worldView->renderer() : nullptr; }
  scene::ExamineNavigator navigator;
  render::SceneRendererOptions options;  // level of detail, mode, loaders
  /// False once the user moved this camera: until then it is framed again as the world
  /// arrives.
  bool autoFrame = true;
  ViewportRect rect;                  // where it was last drawn (pixels, lower-left origin)
  std::size_t diagnosticsLogged = 0;  // renderer diagnostics already in the log
  /// Whether the navigation type was chosen (from the menu); else NavigationInfo decides.
  bool navigationChosen = false;
  /// Linked viewports follow the camera of the active one when it is linked too.
  bool linked = false;
  /// Automatic level of detail: the fraction moves each frame so that drawing this
  /// viewport takes about WindowState::frameTarget / viewports seconds.
  bool autoLod = false;
  /// At most this many QNV vectors drawn per frame (0: no budget).
  std::uint64_t vectorBudget = 0;
  /// Automatic level of detail: the splats per second the last frame drew (0 before the
  /// first measured frame). It caps the next frame's vectors at what fits twice the
  /// frame-time target, so a stream of millions of vectors arriving between two frames
  /// cannot make one frame take seconds (docs/soak.md).
  double splatRate = 0.0;
  /// What the viewport last saw of its world's execution model: a change of the bound
  /// Viewpoint (or of its fields) moves the camera there (4.6.10, 6.53).
  std::uint64_t bindingSeen = 0;
  std::uint64_t viewpointRevisionSeen = 0;
  const vrml::Node* viewpointSeen = nullptr;
  /// The camera the bound Viewpoint itself gives, as last seen: the user's offset from it
  /// is kept when another viewpoint is bound.
  scene::Camera viewpointCamera;
  /// The user's offset from each viewpoint unbound here (X3D 4.0 clause 23.3.5): one bound
  /// again with retainUserOffsets TRUE goes back to it; with FALSE, to its own camera.
  /// Cleared when the viewport shows another world (`offsetsWorld`).
  std::unordered_map<const vrml::Node*, scene::UserOffset> userOffsets;
  std::size_t offsetsWorld = kNone;
  /// An animated move to a Viewpoint (1 s, position and orientation interpolated).
  struct Transition {
    scene::Camera from, to;
    double start = -1.0;  // seconds (steady clock); < 0: none
  } transition;
  /// WALK gravity (window_navigation.cpp): where the avatar last stood on the ground, and
  /// how fast it falls (metres per second).
  struct Gravity {
    bool settled = false;
    glm::vec3 at{0.0f};
    float speed = 0.0f;
  } gravity;
  /// The worlds (indices into WindowState::worlds) shown here before the current one
  /// (Back) and after it (Forward), as Anchor links replaced them; most recent last.
  std::vector<std::size_t> back, forward;
};

struct WindowState {
  std::vector<gs::session::LoadedWorld> worlds;  // every world opened, in order
  /// What the viewports' WorldViews share (made on first use over `session`, which is
  /// not replaced after that); declared before `viewports`, which it outlives.
  std::unique_ptr<session::ViewGroup> group;
  Layout layout = Layout::single;
  std::vector<Viewport> viewports;  // layoutCells(layout) of them
  std::size_t active = 0;           // the viewport the menus and the mouse act on
  std::vector<LogLine> log;
  std::vector<std::string> recent;  // paths and URLs opened, most recent first
  bool showLog = false;
  bool showOpenDialog = false;
  bool showStreams = false;
  bool quitRequested = false;
  char openPath[1024] = {};
  float lastAspect = 1.0f;          // of the active viewport
  double frameTarget = 1.0 / 30.0;  // seconds per frame the automatic levels of detail aim at
  /// A screenshot asked for from the menu: written after the next scene draw.
  std::string screenshotPath;
  bool screenshotViewportOnly = false;
  /// How new viewports draw: splat loader, level of detail (--lod), mode (--mode).
  render::SceneRendererOptions rendererOptions;
  /// --time, --time-step, --trace-events: the window's clock starts at time.start when
  /// time.set, else at the wall clock (docs/runtime.md).
  session::RuntimeOptions time;
  /// The execution model of every world opened, made on the first update().
  std::unique_ptr<session::WorldRuntimes> runtimes;
  /// The active viewport's Sounds (docs/media.md), made with runtimes.
  std::unique_ptr<WorldSounds> sounds;
  double clockOffset = 0.0;  // world time = wallClockSeconds() + clockOffset
  /// Set by a script's `time` / `advance`: the window's clock is virtual from then on
  /// (virtualTime), no longer the wall clock.
  bool virtualClock = false;
  double virtualTime = 0.0;
  /// The pointing device (window_pointer.cpp): what is under it for the cursor and the
  /// tooltip; whether a sensor or Anchor holds it (the drag does not navigate); the
  /// viewport it was last in; the links clicked, followed in update().
  runtime::PointerHint pointerHint;
  bool pointerHeld = false;
  std::size_t pointerViewport = static_cast<std::size_t>(-1);
  struct LinkRequest {
    const vrml::Scene* scene = nullptr;
    std::size_t viewport = 0;
    std::vector<std::string> url, parameter;
  };
  std::vector<LinkRequest> links;
  /// Streams every world opened (files and URLs) while the window keeps drawing.
  std::unique_ptr<gs::session::StreamingSession> session =
      std::make_unique<gs::session::StreamingSession>();

  WindowState();
  ~WindowState();
  WindowState(const WindowState&) = delete;
  WindowState& operator=(const WindowState&) = delete;

  /// The ViewGroup of every viewport (made over `session` on the first call).
  session::ViewGroup& viewGroup();

  /// The active viewport (there is always at least one).
  Viewport& view() { return viewports[active]; }
  const Viewport& view() const { return viewports[active]; }

  /// Switches to `layout` (app/layout.hpp). New cells show
  /// the active viewport's world; cells removed are freed.
  void setLayout(Layout layout);
  /// Starts loading `path` (a file or an http(s) URL) and shows it in the active
  /// viewport as it arrives; a failure is logged (and the log shown), never thrown.
  void open(const std::string& path);
  /// As open(), but in the first empty viewport, growing the layout (1x1, 2x1, 2x2) when
  /// none is empty; with four full viewports, the active one (the web-browser helper).
  /// False when the world could not be opened (logged).
  bool openInNewViewport(const std::string& path);
  /// Fills the viewports in order with `inputs` (a single input fills them all); viewport
  /// i draws at level of detail lods[i] (the last one repeats; none: rendererOptions.lod).
  void openInputs(const std::vector<std::string>& inputs, const std::vector<double>& lods);
  /// Shows worlds[world] in viewports[viewport]: new renderer, camera at its bound
  /// Viewpoint.
  void show(std::size_t world, std::size_t viewport);
  /// Once per frame: moves arrived bytes into the worlds and streams, redraws what grew,
  /// logs messages.
  void update();
  /// Whether the window must go on drawing without input (issue 42, friction 4): streams
  /// still arriving, a world that may change by itself (WorldRuntimes::animating), a
  /// Viewpoint transition or a WALK fall under way. At rest the window waits for input.
  bool restless() const;
  /// Returns the active viewport's camera to its world's bound Viewpoint.
  void resetView();
  /// Frames the active viewport's whole scene keeping the view direction.
  void fitToScene();
  /// Draws the active viewport in `mode` (a new renderer; the view stays).
  void setMode(scene::RenderMode mode);
  /// The browser option Shading of the active viewport's world (View > Shading), or the
  /// command line's when no world runs there yet.
  render::ShadingOption shading() const;
  /// Sets it (session::WorldRuntimes::setShading): every viewport of that world draws with
  /// it from the next frame. False when no world runs in the active viewport.
  bool setShading(render::ShadingOption shading);
  /// Sets the active viewport's level of detail (fraction of every QNV stream, 0..1).
  void setLod(double lod);
  /// Sets the active viewport's vector budget (vectors per frame in all; 0: none).
  void setVectorBudget(std::uint64_t vectors);
  /// Moves the active viewport to Viewpoint `index` of its world, animated over 1 s
  /// (VRML97 clause 6.53: jump TRUE viewpoints may be reached by a transition).
  void jumpToViewpoint(std::size_t index);
  /// Sets the active viewport's navigation type (EXAMINE, WALK, FLY), overriding its
  /// NavigationInfo.
  void setNavigation(scene::NavigationMode mode);
  /// WALK and FLY (window_navigation.cpp): moves the active viewport's camera `forward`,
  /// `right` and `up` metres as ExamineNavigator::move, but stopped by walls, and, in
  /// WALK, on the ground (scene::walkStep; falls of at most `maxFall` metres at once);
  /// the Collision nodes met send collideTime. EXAMINE: ExamineNavigator::move.
  void moveViewer(float forward, float right, float up, float maxFall);
  /// Once a frame: WALK viewports whose avatar is above the ground fall towards it
  /// (9.81 m/s^2 over `seconds` since the last frame).
  void applyGravity(float seconds);
  /// Shows worlds[world] in viewports[viewport] as a link does: the world shown there
  /// before goes to its Back history, and its Forward history is dropped.
  void showLinked(std::size_t world, std::size_t viewport);
  /// Back / Forward (Alt+Left / Alt+Right) in the active viewport's history; false when
  /// there is nothing to go to.
  bool goBack();
  bool goForward();

  /// The pointing device at (x, y), pixels from the top left of the scene area of height
  /// `height`, with its left button up or down: picks in the viewport under it (the one
  /// it was pressed in while a sensor holds it) and tells that world's execution model.
  /// Returns pointerHeld.
  bool pointerInput(float x, float y, bool buttonDown, int height);
  /// A key went down (`press`) or up (X3D 4.0 clause 21, runtime/keys.hpp): the active
  /// viewport's world gets it at worldTime() (ExecutionModel::keyPress / keyRelease) for
  /// its KeySensors and StringSensors. Nothing when the viewport shows no world.
  void keyInput(const runtime::Key& key, bool press);
  /// Whether the active viewport's world has an enabled KeySensor or StringSensor: the
  /// keyboard is then the world's (WALK / FLY keys do not move the viewer).
  bool worldWantsKeys() const;
  /// The world time of the window's clock (seconds): virtualTime or the wall clock.
  double worldTime() const;
  /// Makes the clock virtual at `time` (ignored when earlier than now) and runs every
  /// world's execution model to it (a script's `time` and `advance`).
  void setWorldTime(double time);
  /// Follows the links clicked (Anchor, Browser.loadURL): worlds replace the world of the
  /// viewport (or open in a new one), other documents go to xdg-open (pointer_input.hpp
  /// decideLink says what is allowed).
  void followLinks();
  /// The viewport under the point (x, y) in pixels from the top left of the scene area of
  /// height `height`, or Viewport::kNone.
  std::size_t viewportAt(float x, float y, int height) const;
  /// Writes the screenshot asked for (screenshotPath) from the scene just drawn into the
  /// rectangle of drawScene(); logs where it went or why not.
  void saveScreenshot(int width, int height);
  /// Renders every viewport into its cell of the rectangle (pixels, origin bottom left)
  /// of the current framebuffer; empty cells are cleared to black.
  void drawScene(int x, int y, int width, int height);

 private:
  /// Opens `path` in the session (once per path) and returns its index in worlds, or
  /// Viewport::kNone after logging why not.
  std::size_t load(const std::string& path);
  void home(Viewport& v);
  /// Makes viewport `index` a new WorldView of its world with its options (the old
  /// view's GL objects go first, while the context is current).
  void makeView(std::size_t index);
  /// Once per frame from update(): the execution models made (first call), every world
  /// to the window's clock, each viewport's WorldView::update (the frame step shared with
  /// --snapshot), a newly bound Viewpoint to the camera, sounds, messages. Returns
  /// whether a pump changed a scene.
  bool updateViews();
};

/// Draws the main menu bar (File, View, Viewpoints, Help) and acts on it; returns its
/// height in pixels. `aspect` is the active viewport's width / height.
int drawMenuBar(WindowState& state, float aspect);
/// Draws the open-file dialog, the stream panel and the log panel when they are shown.
void drawPanels(WindowState& state);
/// With several viewports, a frame around the active one (ImGui's background draw list,
/// over the scene, under the panels). `windowHeight`: the framebuffer's height in pixels.
void drawActiveViewportFrame(const WindowState& state, int windowHeight);

}  // namespace gs::app
