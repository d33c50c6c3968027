// The window's viewer against its world (issue 11 points 6 and 7): WALK and FLY stop at
// walls and WALK falls and follows the terrain (scene::walkStep, ISO/IEC 14772-1:1997
// 6.29), Collision nodes met send collideTime (6.8); Back and Forward through the worlds
// Anchor links opened in a viewport.
#include "app/window_state.hpp"
#include "scene/collision.hpp"

#include <algorithm>
#include <limits>

namespace gs::app {

namespace {

constexpr float kGravity = 9.81f;  // metres per second squared

/// Applies a walkStep result to viewport `v` of `state`: the camera, the gravity state,
/// collideTime for the Collision nodes met.
void take(WindowState& state, Viewport& v, const scene::WalkResult& r) {
  v.navigator.setCamera(r.camera);
  v.gravity.settled = r.grounded;
  v.gravity.at = r.camera.position;
  if (r.grounded) v.gravity.speed = 0.0f;
  if (r.collided.empty() || !state.runtimes || v.world >= state.worlds.size()) return;
  std::vector<vrml::Node*> nodes;
  // The scene's nodes are the execution model's to change (pointer_input.cpp does the same).
  for (const vrml::Node* n : r.collided) nodes.push_back(const_cast<vrml::Node*>(n));
  state.runtimes->of(state.worlds[v.world].scene, state.worldTime()).collided(nodes);
}

}  // namespace

void WindowState::moveViewer(float forward, float right, float up, float maxFall) {
  Viewport& v = view();
  v.autoFrame = false;
  if (!v.renderer() || v.navigator.mode() == scene::NavigationMode::examine) {
    v.navigator.move(forward, right, up);
    return;
  }
  scene::WalkOptions options;
  options.mode = v.navigator.mode();
  options.maxFall = maxFall;
  const scene::WalkResult r =
      scene::walkStep(v.renderer()->traversal(), v.navigator.camera(),
                      v.navigator.motion(forward, right, up), v.renderer()->navigation(), options);
  take(*this, v, r);
}

void WindowState::applyGravity(float seconds) {
  seconds = std::clamp(seconds, 0.0f, 0.1f);
  for (Viewport& v : viewports) {
    if (!v.renderer() || v.navigator.mode() != scene::NavigationMode::walk ||
        v.transition.start >= 0.0)
      continue;
    if (v.gravity.settled && v.gravity.at == v.navigator.camera().position) continue;
    v.gravity.speed += kGravity * seconds;
    scene::WalkOptions options;
    options.maxFall = v.gravity.speed * seconds;
    take(*this, v,
         scene::walkStep(v.renderer()->traversal(), v.navigator.camera(), glm::vec3(0.0f),
                         v.renderer()->navigation(), options));
  }
}

void WindowState::showLinked(std::size_t world, std::size_t index) {
  if (world >= worlds.size() || index >= viewports.size()) return;
  Viewport& v = viewports[index];
  if (v.world != Viewport::kNone && v.world != world) v.back.push_back(v.world);
  v.forward.clear();
  show(world, index);
}

bool WindowState::goBack() {
  Viewport& v = view();
  if (v.back.empty()) return false;
  const std::size_t world = v.back.back();
  v.back.pop_back();
  if (v.world != Viewport::kNone) v.forward.push_back(v.world);
  show(world, active);
  return true;
}

bool WindowState::goForward() {
  Viewport& v = view();
  if (v.forward.empty()) return false;
  const std::size_t world = v.forward.back();
  v.forward.pop_back();
  if (v.world != Viewport::kNone) v.back.push_back(v.world);
  show(world, active);
  return true;
}

}  // namespace gs::app
