#include "session/world_view.hpp"

#include <algorithm>

namespace gs::session {

void ViewGroup::attachRuntimes(WorldRuntimes& runtimes, double time, bool waitForMedia) {
  runtimes_ = &runtimes;
  waitForMedia_ = waitForMedia;
  // LoadSensors watching an Inline hear of its end once its stream is done.
  runtimes.setWorldLoadState(
      [s = &session_](const vrml::Scene& scene) { return s->worldLoadState(scene); });
  // A world a Script replaced adds no more of its file's nodes.
  runtimes.setWorldStop([s = &session_](const vrml::Scene& scene) {
    s->abandonWorld(scene, "Browser.replaceWorld replaced the world while it arrived");
  });
  for (WorldView* v : views_) {
    runtimes.of(v->scene_, time);
    runtimes.addInlines(v->scene_.get(), v->renderer_->traversal());
    // MovieTextures show the frame of their media time (docs/media.md).
    v->renderer_->setMediaClock(runtimes.mediaClock(v->scene_.get()), waitForMedia);
    v->renderer_->traversal().setParticleSource(runtimes.particleSource(v->scene_.get()));
    runtimes.setMediaDurations(v->scene_.get(), v->renderer_->takeMediaDurations());
    runtimes.setUrlObjectLoads(v->scene_.get(), v->renderer_->takeUrlObjectLoads());
  }
}

bool ViewGroup::pump() {
  if (!session_.pump()) return false;
  ++generation_;
  for (WorldView* v : views_) v->renderer_->sceneChanged();
  if (runtimes_ != nullptr) runtimes_->scenesGrew();
  return true;
}

void ViewGroup::advanceTo(double time, const WorldView* last) {
  if (runtimes_ == nullptr) return;
  if (!posesAt_ || *posesAt_ != time) {
    posesAt_ = time;
    // The sensors see each world from its views' cameras, `last` last.
    for (WorldView* v : views_)
      if (v != last) runtimes_->setViewer(v->scene_.get(), viewerPose(v->camera(), v->aspect()));
    if (last != nullptr)
      runtimes_->setViewer(last->scene_.get(),
                           viewerPose(const_cast<WorldView*>(last)->camera(), last->aspect()));
  }
  // A no-op for worlds already at `time`.
  runtimes_->advanceTo(time);
}

WorldView::WorldView(ViewGroup& group, std::shared_ptr<const vrml::Scene> scene,
                     const render::SceneRendererOptions& options)
    : group_(group),
      scene_(std::move(scene)),
      renderer_(std::make_unique<render::SceneRenderer>(scene_,
                                                        group.session().rendererOptions(options))),
      generationSeen_(group.generation()) {
  group_.views_.push_back(this);
  if (WorldRuntimes* runtimes = group_.runtimes()) {
    renderer_->setMediaClock(runtimes->mediaClock(scene_.get()), group_.waitForMedia_);
    renderer_->traversal().setParticleSource(runtimes->particleSource(scene_.get()));
  }
}

WorldView::~WorldView() {
  auto& views = group_.views_;
  views.erase(std::remove(views.begin(), views.end(), this), views.end());
}

scene::Camera WorldView::camera() {
  if (camera_) return camera_(*renderer_, aspect());
  return renderer_->boundViewpointCamera();
}

void WorldView::setRect(int x, int y, int width, int height) {
  x_ = x;
  y_ = y;
  width_ = std::max(width, 1);
  height_ = std::max(height, 1);
}

float WorldView::aspect() const {
  return static_cast<float>(width_) / static_cast<float>(height_);
}

bool WorldView::update(double time, const WorldView* last) {
  // 1. Transfers: what arrived joins the scenes (by this view's pump or another's).
  group_.pump();
  const bool changed = group_.generation() != generationSeen_;
  generationSeen_ = group_.generation();
  if (WorldRuntimes* runtimes = group_.runtimes()) {
    // 2. The Inline worlds loaded so far run with the world (made at `time` when new).
    runtimes->of(scene_, time);
    runtimes->addInlines(scene_.get(), renderer_->traversal());
    // 3. Every world to `time`; the new worlds' Scripts and sensors start there.
    group_.advanceTo(time, last);
    // 4. MovieTexture durations found by the decoders (docs/media.md).
    runtimes->setMediaDurations(scene_.get(), renderer_->takeMediaDurations());
    //    The textures whose loading ended, for LoadSensors.
    runtimes->setUrlObjectLoads(scene_.get(), renderer_->takeUrlObjectLoads());
    //    What the last drawing computed: LOD levels, a GeoLOD's children.
    runtimes->sendDrawnOutputs(scene_.get(), renderer_->takeDrawnOutputs());
    // 5. Bound nodes from the execution model to the renderer.
    renderer_->traversal().setBoundNodes(runtimes->bound(scene_.get()));
  }
  return changed;
}

void WorldView::draw() {
  // 6. Drawing asks for what the state references (Inlines, textures, LOD levels, QNV
  // prefixes); it arrives through later pumps.
  // The browser option Shading as the world's Scripts left it (WorldRuntimes::shading).
  if (WorldRuntimes* runtimes = group_.runtimes())
    renderer_->setShading(runtimes->shading(scene_.get()));
  renderer_->draw(camera(), x_, y_, width_, height_);
}

bool WorldView::frame(double time) {
  const bool changed = update(time);
  draw();
  return changed;
}

}  // namespace gs::session
