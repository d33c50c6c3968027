// The window's pointing device and links (issue 11 points 5 and 7): the mouse goes to the
// execution model of the world under it before navigation; Anchor clicks open worlds
// or documents; a script's virtual clock.
#include "app/pointer_input.hpp"
#include "app/window_state.hpp"
#include "runtime/clock.hpp"

namespace gs::app {

double WindowState::worldTime() const {
  return virtualClock ? virtualTime : runtime::wallClockSeconds() + clockOffset;
}

void WindowState::setWorldTime(double t) {
  const double now = worldTime();
  if (t < now) {
    log.push_back({true, "time " + std::to_string(t) + " is before the world's time " +
                             std::to_string(now) + ": the clock stays"});
    t = now;
  }
  virtualClock = true;
  virtualTime = t;
  if (runtimes) runtimes->advanceTo(t);
}

bool WindowState::pointerInput(float x, float y, bool buttonDown, int height) {
  std::size_t index = pointerHeld && pointerViewport < viewports.size() ? pointerViewport
                                                                        : viewportAt(x, y, height);
  if (index != Viewport::kNone &&
      (!viewports[index].renderer() || viewports[index].world >= worlds.size()))
    index = Viewport::kNone;
  if (!runtimes) {
    pointerHint = {};
    return false;
  }
  const double now = worldTime();
  // Leaving a viewport: its world sees the pointer go off its geometry.
  if (pointerViewport != index && pointerViewport < viewports.size()) {
    const Viewport& old = viewports[pointerViewport];
    if (old.renderer() && old.world < worlds.size()) {
      runtime::PointerEvent off;
      off.buttonDown = false;
      runtimes->of(worlds[old.world].scene, now).pointer(off);
    }
  }
  pointerViewport = index;
  if (index == Viewport::kNone) {
    pointerHint = {};
    pointerHeld = false;
    return false;
  }
  Viewport& v = viewports[index];
  runtime::ExecutionModel& model = runtimes->of(worlds[v.world].scene, now);
  if (!model.wantsPointer()) {  // nothing to sense: no picking
    pointerHint = {};
    pointerHeld = false;
    return false;
  }
  // Pixels inside the viewport from its top left (rect has its origin at the bottom left).
  const float vx = x - static_cast<float>(v.rect.x);
  const float vy = y - (static_cast<float>(height) - static_cast<float>(v.rect.y + v.rect.height));
  const runtime::PointerEvent event =
      pointerEventAt(v.renderer()->traversal(), v.navigator.camera(), v.rect.width, v.rect.height,
                     vx, vy, buttonDown);
  pointerHeld = model.pointer(event);
  pointerHint = model.pointerHint();
  return pointerHeld;
}

void WindowState::followLinks() {
  std::vector<LinkRequest> requests;
  requests.swap(links);
  for (const LinkRequest& r : requests) {
    const std::string worldUrl = r.scene != nullptr ? r.scene->url : std::string();
    const LinkDecision d = decideLink(worldUrl, r.url, r.parameter);
    // A world link that is refused or cannot be opened: the asking world's Scripts hear
    // INITIALIZED_ERROR (X_ITE 15's loadURL), and the world stays.
    bool failed = false;
    switch (d.action) {
      case LinkAction::refused:
        log.push_back({true, "link not followed: " + d.reason});
        showLog = true;
        failed = true;
        break;
      case LinkAction::external: {
        std::string error;
        if (openExternally(d.url, error))
          log.push_back({false, "opening " + d.url + " with xdg-open"});
        else
          log.push_back({true, error});
        break;
      }
      case LinkAction::openWorld: {
        const std::size_t world = load(d.url);
        if (world != Viewport::kNone)  // Back returns to the world it replaces
          showLinked(world, r.viewport < viewports.size() ? r.viewport : active);
        failed = world == Viewport::kNone;
        break;
      }
      case LinkAction::openWorldInNewViewport:
        failed = !openInNewViewport(d.url);
        break;
    }
    if (failed && runtimes) runtimes->linkFailed(r.scene);
  }
}

}  // namespace gs::app
