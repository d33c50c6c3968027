// One viewport's world (docs/architecture.md, "A per-frame step"): a WorldView owns what
// one viewport needs (its scene, its SceneRenderer, the camera it is handed, its rectangle)
// and is linked, through a ViewGroup, to the StreamingSession and the WorldRuntimes that
// every viewport of the session shares. Its frame(time) is the one per-frame step of the
// window and of --snapshot, in one fixed order:
//
//   1. pump transfers: what arrived joins the scenes (the renderers and the execution
//      models are told the scenes grew);
//   2. the Inline worlds the renderer loaded so far join the world's execution model;
//   3. every world's execution model advances to `time` (the viewers' poses first, once
//      per time);
//   4. the media durations the renderer found, and the textures whose loading ended
//      (LoadSensor), go to the execution model;
//   5. the bound nodes (Viewpoint, NavigationInfo, Background, Fog) go from the
//      execution model to the renderer;
//   6. draw: drawing is what starts the loads the new state references (an Inline a
//      Switch now shows or a Script set, a texture url, the LOD level chosen at `time`,
//      a QNV prefix); they arrive in later frames.
//
// A new per-frame step goes into WorldView::frame, at its place in this order.
#pragma once

#include "render/scene_renderer.hpp"
#include "scene/camera.hpp"
#include "session/streaming_session.hpp"
#include "session/world_runtime.hpp"
#include "vrml/scene.hpp"

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

namespace gs::session {

class WorldView;

/// What the WorldViews of one session share: the StreamingSession, the WorldRuntimes
/// (attached once the worlds should run), and how often a pump changed a scene.
class ViewGroup {
 public:
  explicit ViewGroup(StreamingSession& session) : session_(session) {}
  ViewGroup(const ViewGroup&) = delete;
  ViewGroup& operator=(const ViewGroup&) = delete;

  StreamingSession& session() { return session_; }
  /// The execution models; null until attachRuntimes().
  WorldRuntimes* runtimes() { return runtimes_; }
  /// From now on frames run `runtimes` (which outlives the group's views): each view's
  /// world gets its execution model (made at `time` when new), the Inline worlds its
  /// renderer loaded join it, and its renderer reads the media clock (`waitForMedia`:
  /// draw() waits for a movie's frame, SceneRenderer::setMediaClock).
  void attachRuntimes(WorldRuntimes& runtimes, double time, bool waitForMedia);
  /// Step 1 of a frame: moves arrived bytes into the scenes (StreamingSession::pump);
  /// when a scene changed, every view's renderer and every execution model are told.
  /// Returns whether something changed.
  bool pump();
  /// Counts the pumps that changed something.
  std::uint64_t generation() const { return generation_; }
  /// Step 3 of a frame: every view's viewer pose goes to its world (in the order the views
  /// were made, `last` last: its pose wins for a world two views show), and every world
  /// advances to `time`. The poses are set once per time, so a frame repeated at the same
  /// time (--snapshot settling) does not move the sensors.
  void advanceTo(double time, const WorldView* last = nullptr);
  /// Whether nothing is arriving and nothing more was asked for.
  bool settled() const { return session_.settled(); }

 private:
  friend class WorldView;
  StreamingSession& session_;
  WorldRuntimes* runtimes_ = nullptr;
  bool waitForMedia_ = false;
  std::uint64_t generation_ = 0;
  std::optional<double> posesAt_;  // the time the viewer poses were last set for
  std::vector<WorldView*> views_;  // in the order made
};

/// The camera a view draws with and its world's sensors see, given the renderer (its
/// bound Viewpoint, bounds) and the aspect (width / height) of the view's rectangle.
using CameraSource = std::function<scene::Camera(render::SceneRenderer& renderer, float aspect)>;

/// One viewport of one world.
class WorldView {
 public:
  /// A view of `scene` (opened in group.session()) drawn with `options`, wired to the
  /// session's loaders. Draws with the renderer's bound Viewpoint until setCamera().
  WorldView(ViewGroup& group, std::shared_ptr<const vrml::Scene> scene,
            const render::SceneRendererOptions& options);
  ~WorldView();
  WorldView(const WorldView&) = delete;
  WorldView& operator=(const WorldView&) = delete;

  const std::shared_ptr<const vrml::Scene>& scene() const { return scene_; }
  render::SceneRenderer& renderer() { return *renderer_; }
  const render::SceneRenderer& renderer() const { return *renderer_; }
  ViewGroup& group() { return group_; }

  void setCamera(CameraSource camera) { camera_ = std::move(camera); }
  /// The camera of the view's current rectangle.
  scene::Camera camera();
  /// Where the view draws (pixels of the current framebuffer, lower-left origin).
  void setRect(int x, int y, int width, int height);
  float aspect() const;

  /// Steps 1-5 of a frame (see the top of this header). `last`: as ViewGroup::advanceTo.
  /// Returns whether the scene changed since this view's last update (a pump by any view
  /// of the group brought something).
  bool update(double time, const WorldView* last = nullptr);
  /// Step 6: draws into the view's rectangle with camera().
  void draw();
  /// update(time) then draw(): one frame. Returns what update() returned.
  bool frame(double time);

 private:
  friend class ViewGroup;
  ViewGroup& group_;
  std::shared_ptr<const vrml::Scene> scene_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  CameraSource camera_;
  int x_ = 0, y_ = 0, width_ = 1, height_ = 1;
  std::uint64_t generationSeen_ = 0;
};

}  // namespace gs::session
