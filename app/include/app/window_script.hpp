// Scripted input for the window (--script FILE), for tests and demonstrations: the same
// actions the menus perform, one per line, run between frames.
//
//   # comment
//   layout 2x1              View > Layout
//   open PATH_OR_URL        File > Open (into the active viewport)
//   viewport I              click viewport I (0-based: left to right, top to bottom)
//   lod F                   the active viewport's level of detail slider (0 < F <= 1)
//   mode polygons|splats|outlines
//   shading phong|gouraud|flat|wireframe|point   View > Shading: the browser option Shading
//                           of the active viewport's world
//   viewpoint N             Viewpoints > N (from 0): binds that Viewpoint (4.6.10)
//   wait-loaded             until nothing is arriving (at most 60 s, then logged)
//   wait-viewports N        until N viewports show a world (e.g. sent by another launch;
//                           at most 60 s)
//   frames N                draw N frames
//   screenshot OUT.png      the whole scene area (without the menus) as PNG
//   screenshot-viewport OUT.png   the active viewport only
//   auto-lod on|off         the active viewport's automatic level of detail
//   budget N                the active viewport's vector budget (vectors per frame; 0: none)
//   frame-target MS         the frame time automatic levels of detail aim at
//   status OUT.txt          one line per viewport: index, world URL, level of detail,
//                           mode, navigation, splats drawn (for tests); then one line per
//                           QNV tileset: "tileset URL resident R peak P evicted E requests Q
//                           bytes B chosen C" (session::TilesetStatistics; R, P, C vectors)
//   time T                  the worlds' clock to SFTime T (seconds); from then on the
//                           clock is virtual (no longer the wall clock)
//   advance S               the virtual clock S seconds on (cascades at --time-step)
//   pointer X Y             the mouse to pixel X Y (from the top left of the scene area)
//   press / release         the left button down / up where the mouse is
//   click X Y               pointer X Y, press, release
//   drag X1 Y1 X2 Y2 [N]    press at X1 Y1, N moves (default 10) to X2 Y2, release; a drag
//                           that no sensor holds navigates
//   key K                   key K down and up for the active viewport's world (X3D
//                           KeySensor, StringSensor): K one UTF-8 character or a name,
//                           F1..F12, Home, End, PgUp, PgDn, Up, Down, Left, Right, Shift,
//                           Control, Alt, Enter, Backspace, Tab, Escape, Space, U+XXXX
//   key-down K / key-up K   key K down / up only (e.g. Shift held over other keys)
//   type TEXT               each character of TEXT (UTF-8, spaces kept) down and up
//   navigation EXAMINE|WALK|FLY   the active viewport's navigation type (View menu)
//   walk F R U [N]          WALK and FLY: the active viewport's camera F metres forward, R
//                           right, U up in N steps (default 1) as the keys move it: stopped
//                           by walls (collideTime sent), WALK on the ground at once
//   back / forward          Back / Forward (Alt+Left / Alt+Right) in the active viewport
//   camera OUT.txt          the active viewport's camera position "X Y Z" (metres)
//   frame-stats OUT.txt     the frames drawn since the last frame-stats (or the start):
//                           "frames N mean_ms M median_ms M p95_ms M max_ms M", then per
//                           viewport "viewport I movie_frames K" (MovieTexture frames
//                           copied into textures since its renderer was made)
//   Each of these commands is followed by one frame drawn before the next command.
//   quit
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/window_state.hpp"

namespace gs::app {

class WindowScript {
 public:
  /// Reads and checks the whole script. Returns false with `error` set to
  /// "FILE:LINE: expected ..., got ..." (or why the file cannot be read).
  bool load(const std::string& path, std::string& error);

  /// Runs commands after a frame's scene was drawn into the scene area (width x height
  /// pixels at the bottom left of the current framebuffer, before the menus are drawn),
  /// until one waits for more frames. Returns false once the script asked to quit or
  /// ended with `quit`. Failures (a screenshot that cannot be written) go to the log.
  bool step(WindowState& state, int width, int height);

  bool empty() const { return commands_.empty(); }

 private:
  struct Command;
  /// What step() does once a command ran: the next command at once, a frame first, the
  /// same command again next frame (waiting), or stop.
  enum class Next { go, frame, wait, quit };
  /// One command of the language: the verb, what load() checks of its argument (what the
  /// line should have been, "" when it is right) and what step() runs. One table,
  /// verbs(), serves both.
  struct Verb {
    const char* name;
    std::string (*check)(const Command& c);
    Next (*run)(WindowScript& script, WindowState& state, const Command& c, int width, int height);
  };
  struct Command {
    std::string verb;
    std::string argument;
    int line = 0;
    const Verb* handler = nullptr;  // in verbs()
  };
  /// Every verb: window_script.cpp's and the navigation verbs (navigation, walk, back,
  /// forward, camera) of window_script_navigation.cpp.
  static const std::vector<Verb>& verbs();
  static std::vector<Verb> navigationVerbs();
  std::vector<Command> commands_;
  std::size_t next_ = 0;
  int framesLeft_ = 0;
  int settledFrames_ = 0;
  int waitedFrames_ = 0;
  double waitStart_ = -1.0;
  float pointerX_ = 0.0f, pointerY_ = 0.0f;  // the scripted mouse
  bool buttonDown_ = false;
  /// The scripted mouse to (x, y) / its button down or up, told to the window's sensors.
  void movePointer(WindowState& state, double x, double y, int height);
  void setButton(WindowState& state, bool down, int height);
  /// frame-stats (window_script_stats.cpp); the steady-clock seconds of each step().
  void writeFrameStats(WindowState& state, const std::string& path);
  std::vector<double> frameStamps_;
};

}  // namespace gs::app
