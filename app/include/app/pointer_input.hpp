// The pointing device between the renderer's picking and the execution model's sensors
// (docs/runtime.md): a scene::PickHit as a runtime::PickResult, and what the browser
// does with a link (Anchor, Browser.loadURL) that is not a `#Name` Viewpoint.
#pragma once

#include "runtime/pointer.hpp"
#include "scene/camera.hpp"
#include "scene/picking.hpp"

#include <string>
#include <vector>

namespace gs::app {

/// The runtime's view of a pick (the nodes are the scene's; render/ holds them const).
runtime::PickResult toPickResult(const scene::PickHit& hit);

/// The pointer event for the point (x, y) of a viewport width x height pixels (from its
/// top left) seen by `camera`, picking on what `traversal` draws for that camera.
runtime::PointerEvent pointerEventAt(scene::SceneTraversal& traversal, const scene::Camera& camera,
                                     int width, int height, float x, float y, bool buttonDown);

/// What a link asks of the browser (ISO/IEC 14772-1 6.2; issue 11 point 7).
enum class LinkAction {
  openWorld,               // replace the world in the viewport the link was followed in
  openWorldInNewViewport,  // parameter "target=NAME" (not _self)
  external,                // a web page, a PDF ...: the desktop's opener (xdg-open)
  refused,                 // nothing usable, or not allowed for this world
};

struct LinkDecision {
  LinkAction action = LinkAction::refused;
  std::string url;     // resolved against the world's url
  std::string reason;  // why it was refused
};

/// Decides what to do with the url list of a link in the world at `worldUrl` (the first
/// usable url wins). The rules keep content from the network away from the machine: a
/// world read over http(s) may only open http(s) worlds and hand http(s) pages to the
/// opener, never local files, other schemes or programs; a local world may also open
/// local worlds and hand local documents of a few passive types (pdf, html, txt, images)
/// to the opener. `#Name` urls are the runtime's (Viewpoints) and are skipped here.
LinkDecision decideLink(const std::string& worldUrl, const std::vector<std::string>& url,
                        const std::vector<std::string>& parameter);

/// Hands `url` to `xdg-open` as one argument (no shell), in the background. False with
/// `error` set when it cannot start.
bool openExternally(const std::string& url, std::string& error);

}  // namespace gs::app
