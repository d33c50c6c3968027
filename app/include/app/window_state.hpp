// State of the window application: the worlds opened, the one shown, its renderer and
// navigator, the log of diagnostics. The ImGui panels read and change it.
#pragma once

#include "app/streaming_session.hpp"
#include "app/world.hpp"
#include "render/camera.hpp"
#include "render/scene_renderer.hpp"

#include <memory>
#include <string>
#include <vector>

namespace gs::app {

/// One line of the log panel.
struct LogLine {
  bool error = false;
  std::string text;
};

struct WindowState {
  std::vector<LoadedWorld> worlds;                  // every world opened, in order
  std::size_t current = 0;                          // index into worlds of the one shown
  std::unique_ptr<render::SceneRenderer> renderer;  // for worlds[current]; null if none
  render::ExamineNavigator navigator;
  std::vector<LogLine> log;
  std::vector<std::string> recent;  // paths opened, most recent first
  bool showLog = false;
  bool showOpenDialog = false;
  bool quitRequested = false;
  char openPath[1024] = {};
  float lastAspect = 1.0f;
  std::size_t renderDiagnosticsLogged = 0;  // renderer diagnostics already in the log
  /// How worlds are drawn: splat loader, level of detail (--lod), mode (--mode).
  render::SceneRendererOptions rendererOptions;
  /// Streams every world opened (files and URLs) while the window keeps drawing.
  std::unique_ptr<StreamingSession> session = std::make_unique<StreamingSession>();
  /// False once the user moved the camera: until then the view is framed again as the
  /// world arrives.
  bool autoFrame = true;
  bool showStreams = false;

  /// Starts loading `path` (a file or an http(s) URL) and shows it as it arrives; a
  /// failure is logged (and the log shown), never thrown.
  void open(const std::string& path);
  /// Once per frame: moves arrived bytes into the worlds and streams, redraws what grew,
  /// logs messages.
  void update();
  /// Shows worlds[index]: new renderer, navigator at its bound Viewpoint.
  void show(std::size_t index);
  /// Returns the navigator to the bound Viewpoint of the current world.
  void resetView();
  /// Frames the whole scene keeping the view direction.
  void fitToScene();
  /// Draws every world in `mode` (a new renderer for the current world; the view stays).
  void setMode(render::RenderMode mode);
  /// Sets the level of detail (fraction of every QNV stream drawn, 0..1).
  void setLod(double lod);
  /// Jumps to Viewpoint `index` of the current world.
  void jumpToViewpoint(std::size_t index);
  /// Renders the current world (or only the clear colour) into the viewport rectangle
  /// (pixels, origin bottom left) of the current framebuffer.
  void drawScene(int x, int y, int width, int height);
};

/// Draws the main menu bar (File, View, Viewpoints, Help) and acts on it; returns its
/// height in pixels. `aspect` is the scene viewport's width / height.
int drawMenuBar(WindowState& state, float aspect);
/// Draws the open-file dialog, the stream panel and the log panel when they are shown.
void drawPanels(WindowState& state);

}  // namespace gs::app
