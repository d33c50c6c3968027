#include "app/window_script.hpp"

#include <charconv>
#include <chrono>
#include <fstream>
#include <sstream>

#include "render/image.hpp"

#include <algorithm>
#include <optional>
#include <string_view>
#include <vector>

namespace gs::app {

namespace {

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool parseNumber(const std::string& text, double& value) {
  auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && p == text.data() + text.size();
}

/// The numbers of `text` separated by spaces; false when one is not a number.
bool parseNumbers(const std::string& text, std::vector<double>& out) {
  std::istringstream words(text);
  std::string word;
  out.clear();
  while (words >> word) {
    double v = 0.0;
    if (!parseNumber(word, v)) return false;
    out.push_back(v);
  }
  return true;
}

/// `text` as one number; 0 when it is not one (load() checked it).
double numberIn(const std::string& text) {
  double value = 0.0;
  parseNumber(text, value);
  return value;
}

/// Whether `text` is one number within [lo, hi].
bool numberWithin(const std::string& text, double lo, double hi) {
  double value = 0.0;
  return parseNumber(text, value) && value >= lo && value <= hi;
}

/// "" when `ok`, else `expected`: a Verb's check.
std::string unless(bool ok, std::string expected) {
  return ok ? std::string() : std::move(expected);
}

/// The check of `key K`, `key-down K`, `key-up K`: K as runtime::keyNamed reads it.
std::string checkKeyName(const std::string& argument) {
  return unless(runtime::keyNamed(argument).has_value(),
                "key K with K one character, F1..F12, Home, End, PgUp, PgDn, Up, Down, Left, "
                "Right, Shift, Control, Alt, Enter, Backspace, Tab, Escape, Space or U+XXXX");
}

/// The characters of UTF-8 `text` as keys; empty when it is not valid UTF-8.
std::optional<std::vector<runtime::Key>> scriptCharacters(const std::string& text) {
  std::vector<runtime::Key> keys;
  for (std::size_t i = 0; i < text.size();) {
    const auto lead = static_cast<unsigned char>(text[i]);
    const std::size_t n = lead < 0x80             ? 1
                          : (lead & 0xE0) == 0xC0 ? 2
                          : (lead & 0xF0) == 0xE0 ? 3
                                                  : 4;
    const auto k = runtime::keyNamed(std::string_view(text).substr(i, n));
    if (!k || !k->isCharacter()) return std::nullopt;
    keys.push_back(*k);
    i += n;
  }
  return keys;
}

void writeScreenshot(WindowState& state, const std::string& path, const ViewportRect& r) {
  try {
    render::writePng(path, render::readPixels(r.x, r.y, r.width, r.height));
    state.log.push_back({false, "screenshot " + path});
  } catch (const std::exception& e) {
    state.log.push_back({true, std::string("screenshot: ") + e.what()});
  }
}

/// The status command: one line per viewport, then one per QNV tileset.
void writeStatus(WindowState& state, const std::string& path) {
  std::ofstream out(path);
  for (std::size_t i = 0; i < state.viewports.size(); ++i) {
    const Viewport& v = state.viewports[i];
    const char* navs[] = {"EXAMINE", "WALK", "FLY"};
    out << i << " " << (v.world < state.worlds.size() ? state.worlds[v.world].scene->url : "-")
        << " " << v.options.lod << " " << scene::renderModeName(v.options.traversal.mode) << " "
        << navs[static_cast<int>(v.navigator.mode())] << " "
        << (v.renderer() ? v.renderer()->statistics().splats : 0) << "\n";
  }
  for (const session::TilesetStream* t : state.session->tilesets()) {
    const session::TilesetStatistics& s = t->statistics();
    out << "tileset " << t->url() << " resident " << s.residentVectors << " peak "
        << s.peakResidentVectors << " evicted " << s.evictedBricks << " requests " << s.requests
        << " bytes " << s.brickBytes << " chosen " << s.chosenVectors << "\n";
  }
  if (!out) state.log.push_back({true, "status: cannot write " + path});
}

}  // namespace

const std::vector<WindowScript::Verb>& WindowScript::verbs() {
  using N = std::vector<double>;
  static const std::vector<Verb> table = [] {
    // The check of a verb that ignores its argument.
    std::string (*const anyArgument)(const Command&) = [](const Command&) { return std::string(); };
    std::vector<Verb> rows = {
        {"layout",
         [](const Command& c) {
           return unless(layoutFromName(c.argument).has_value(), "layout 1x1, 2x1 or 2x2");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.setLayout(*layoutFromName(c.argument));
           return Next::go;
         }},
        {"open",
         [](const Command& c) { return unless(!c.argument.empty(), "open followed by a path"); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.open(c.argument);
           return Next::go;
         }},
        {"viewport",
         [](const Command& c) { return unless(numberWithin(c.argument, 0, 3), "viewport 0..3"); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           const auto index = static_cast<std::size_t>(numberIn(c.argument));
           if (index < state.viewports.size()) state.active = index;
           return Next::go;
         }},
        {"viewpoint",
         [](const Command& c) {
           return unless(numberWithin(c.argument, 0, 1e6),
                         "viewpoint N (index in the Viewpoints menu, from 0)");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.jumpToViewpoint(static_cast<std::size_t>(numberIn(c.argument)));
           return Next::go;
         }},
        {"lod",
         [](const Command& c) {
           double f = 0.0;
           return unless(parseNumber(c.argument, f) && f > 0.0 && f <= 1.0,
                         "lod F with 0 < F <= 1");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.setLod(numberIn(c.argument));
           return Next::go;
         }},
        {"mode",
         [](const Command& c) {
           return unless(scene::renderModeFromName(c.argument).has_value(),
                         "mode polygons, splats or outlines");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.setMode(*scene::renderModeFromName(c.argument));
           return Next::go;
         }},
        {"shading",
         [](const Command& c) {
           render::ShadingOption parsed;
           return unless(render::parseShadingOption(c.argument, parsed),
                         "shading phong, gouraud, flat, wireframe or point");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           render::ShadingOption shading = render::ShadingOption::phong;
           render::parseShadingOption(c.argument, shading);
           if (!state.setShading(shading))
             state.log.push_back({true, "shading: no world runs in the active viewport"});
           return Next::go;
         }},
        {"wait-loaded", anyArgument,
         [](WindowScript& s, WindowState& state, const Command& c, int, int) {
           // Settled for two frames running: the frame after a change has drawn (and so
           // asked for what its level of detail needs) and nothing new started.
           if (s.waitStart_ < 0.0) s.waitStart_ = now();
           s.settledFrames_ = state.session->settled() ? s.settledFrames_ + 1 : 0;
           if (s.settledFrames_ < 3 && now() - s.waitStart_ < 60.0) return Next::wait;
           if (s.settledFrames_ < 3)
             state.log.push_back(
                 {true, "script line " + std::to_string(c.line) + ": still loading after 60 s"});
           s.waitStart_ = -1.0;
           s.settledFrames_ = 0;
           return Next::go;
         }},
        {"wait-viewports",
         [](const Command& c) {
           return unless(numberWithin(c.argument, 1, 4), "wait-viewports N with 1 <= N <= 4");
         },
         [](WindowScript& s, WindowState& state, const Command& c, int, int) {
           if (s.waitStart_ < 0.0) s.waitStart_ = now();
           std::size_t shown = 0;
           for (const Viewport& v : state.viewports) shown += v.world != Viewport::kNone ? 1 : 0;
           const auto wanted = static_cast<std::size_t>(numberIn(c.argument));
           if (shown < wanted && now() - s.waitStart_ < 60.0) return Next::wait;
           if (shown < wanted)
             state.log.push_back({true, "script line " + std::to_string(c.line) +
                                            ": fewer viewports than asked after 60 s"});
           s.waitStart_ = -1.0;
           return Next::go;
         }},
        {"frames",
         [](const Command& c) {
           return unless(numberWithin(c.argument, 1, 1e6), "frames N with N >= 1");
         },
         [](WindowScript& s, WindowState&, const Command& c, int, int) {
           s.framesLeft_ = static_cast<int>(numberIn(c.argument));
           return Next::frame;
         }},
        {"screenshot",
         [](const Command& c) {
           return unless(!c.argument.empty(), "screenshot followed by a path");
         },
         [](WindowScript&, WindowState& state, const Command& c, int width, int height) {
           writeScreenshot(state, c.argument, ViewportRect{0, 0, width, height});
           return Next::go;
         }},
        {"screenshot-viewport",
         [](const Command& c) {
           return unless(!c.argument.empty(), "screenshot-viewport followed by a path");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           writeScreenshot(state, c.argument, state.view().rect);
           return Next::go;
         }},
        {"auto-lod",
         [](const Command& c) {
           return unless(c.argument == "on" || c.argument == "off", "auto-lod on or off");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.view().autoLod = c.argument == "on";
           return Next::go;
         }},
        {"budget",
         [](const Command& c) {
           return unless(numberWithin(c.argument, 0, 1e12),
                         "budget N (vectors per frame, 0: none)");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.setVectorBudget(static_cast<std::uint64_t>(numberIn(c.argument)));
           return Next::go;
         }},
        {"frame-target",
         [](const Command& c) {
           double ms = 0.0;
           return unless(parseNumber(c.argument, ms) && ms > 0.0 && ms <= 10000,
                         "frame-target MS with 0 < MS <= 10000");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.frameTarget = numberIn(c.argument) / 1000.0;
           return Next::go;
         }},
        {"frame-stats",
         [](const Command& c) {
           return unless(!c.argument.empty(), "frame-stats followed by a path");
         },
         [](WindowScript& s, WindowState& state, const Command& c, int, int) {
           s.writeFrameStats(state, c.argument);
           return Next::go;
         }},
        {"status",
         [](const Command& c) { return unless(!c.argument.empty(), "status followed by a path"); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           writeStatus(state, c.argument);
           return Next::go;
         }},
        // Interaction: each is drawn once before the next command, so screenshots show it.
        {"time",
         [](const Command& c) {
           N n;
           return unless(
               parseNumbers(c.argument, n) && n.size() == 1 && n[0] >= 0.0 && n[0] <= 1e12,
               "time S with S >= 0 seconds");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           N n;
           parseNumbers(c.argument, n);
           state.setWorldTime(n[0]);
           return Next::frame;
         }},
        {"advance",
         [](const Command& c) {
           N n;
           return unless(
               parseNumbers(c.argument, n) && n.size() == 1 && n[0] >= 0.0 && n[0] <= 1e12,
               "advance S with S >= 0 seconds");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           N n;
           parseNumbers(c.argument, n);
           state.setWorldTime(state.worldTime() + n[0]);
           return Next::frame;
         }},
        {"pointer",
         [](const Command& c) {
           N n;
           return unless(parseNumbers(c.argument, n) && n.size() == 2, "pointer X Y (pixels)");
         },
         [](WindowScript& s, WindowState& state, const Command& c, int, int height) {
           N n;
           parseNumbers(c.argument, n);
           s.movePointer(state, n[0], n[1], height);
           return Next::frame;
         }},
        {"press",
         [](const Command& c) { return unless(c.argument.empty(), "press without arguments"); },
         [](WindowScript& s, WindowState& state, const Command&, int, int height) {
           s.setButton(state, true, height);
           return Next::frame;
         }},
        {"release",
         [](const Command& c) { return unless(c.argument.empty(), "release without arguments"); },
         [](WindowScript& s, WindowState& state, const Command&, int, int height) {
           s.setButton(state, false, height);
           return Next::frame;
         }},
        {"click",
         [](const Command& c) {
           N n;
           return unless(parseNumbers(c.argument, n) && n.size() == 2, "click X Y (pixels)");
         },
         [](WindowScript& s, WindowState& state, const Command& c, int, int height) {
           N n;
           parseNumbers(c.argument, n);
           s.movePointer(state, n[0], n[1], height);
           s.setButton(state, true, height);
           s.setButton(state, false, height);
           return Next::frame;
         }},
        {"drag",
         [](const Command& c) {
           N n;
           return unless(parseNumbers(c.argument, n) && (n.size() == 4 || n.size() == 5) &&
                             (n.size() == 4 || (n[4] >= 1 && n[4] <= 10000)),
                         "drag X1 Y1 X2 Y2 [STEPS] with 1 <= STEPS <= 10000");
         },
         [](WindowScript& s, WindowState& state, const Command& c, int, int height) {
           N n;
           parseNumbers(c.argument, n);
           const int steps = n.size() == 5 ? static_cast<int>(n[4]) : 10;
           s.movePointer(state, n[0], n[1], height);
           s.setButton(state, true, height);
           const bool held = state.pointerHeld;
           for (int i = 1; i <= steps; ++i) {
             const double f = static_cast<double>(i) / steps;
             const float x0 = s.pointerX_, y0 = s.pointerY_;
             s.movePointer(state, n[0] + (n[2] - n[0]) * f, n[1] + (n[3] - n[1]) * f, height);
             if (!held && state.view().renderer()) {  // no sensor holds it: the drag navigates
               Viewport& v = state.view();
               const int h = std::max(1, v.rect.height);
               if (v.navigator.mode() == scene::NavigationMode::examine)
                 v.navigator.orbit(s.pointerX_ - x0, s.pointerY_ - y0, h);
               else
                 v.navigator.look(s.pointerX_ - x0, s.pointerY_ - y0, h);
               v.autoFrame = false;
             }
           }
           s.setButton(state, false, height);
           return Next::frame;
         }},
        {"key", [](const Command& c) { return checkKeyName(c.argument); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           const runtime::Key k = *runtime::keyNamed(c.argument);
           state.keyInput(k, true);
           state.keyInput(k, false);
           return Next::frame;
         }},
        {"key-down", [](const Command& c) { return checkKeyName(c.argument); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.keyInput(*runtime::keyNamed(c.argument), true);
           return Next::frame;
         }},
        {"key-up", [](const Command& c) { return checkKeyName(c.argument); },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           state.keyInput(*runtime::keyNamed(c.argument), false);
           return Next::frame;
         }},
        {"type",
         [](const Command& c) {
           return unless(!c.argument.empty() && scriptCharacters(c.argument).has_value(),
                         "type TEXT (UTF-8)");
         },
         [](WindowScript&, WindowState& state, const Command& c, int, int) {
           const auto keys = scriptCharacters(c.argument);  // load() checked it
           for (const runtime::Key& k : *keys) {
             state.keyInput(k, true);
             state.keyInput(k, false);
           }
           return Next::frame;
         }},
        {"quit", anyArgument,
         [](WindowScript&, WindowState&, const Command&, int, int) { return Next::quit; }},
    };
    for (const Verb& n : navigationVerbs()) rows.push_back(n);
    return rows;
  }();
  return table;
}

bool WindowScript::load(const std::string& path, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = "cannot read script '" + path + "'";
    return false;
  }
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    std::istringstream words(text);
    Command c;
    c.line = line;
    if (!(words >> c.verb) || c.verb.starts_with("#")) continue;
    std::getline(words >> std::ws, c.argument);
    auto fail = [&](const std::string& expected) {
      error = path + ":" + std::to_string(line) + ": expected " + expected + ", got '" + text + "'";
      return false;
    };
    for (const Verb& v : verbs())
      if (c.verb == v.name) c.handler = &v;
    if (!c.handler) {
      std::string names;
      for (const Verb& v : verbs()) names += (names.empty() ? "" : ", ") + std::string(v.name);
      return fail("a command (" + names + ")");
    }
    if (const std::string expected = c.handler->check(c); !expected.empty()) return fail(expected);
    commands_.push_back(std::move(c));
  }
  return true;
}

bool WindowScript::step(WindowState& state, int width, int height) {
  frameStamps_.push_back(now());  // one call per frame drawn: frame-stats
  if (framesLeft_ > 0 && --framesLeft_ > 0) return true;
  while (next_ < commands_.size()) {
    const Command& c = commands_[next_];
    const Next after = c.handler->run(*this, state, c, width, height);
    if (after == Next::wait) return true;
    ++next_;
    if (after == Next::frame) return true;
    if (after == Next::quit) return false;
  }
  return true;
}

void WindowScript::movePointer(WindowState& state, double x, double y, int height) {
  pointerX_ = static_cast<float>(x);
  pointerY_ = static_cast<float>(y);
  state.pointerInput(pointerX_, pointerY_, buttonDown_, height);
}

void WindowScript::setButton(WindowState& state, bool down, int height) {
  buttonDown_ = down;
  state.pointerInput(pointerX_, pointerY_, buttonDown_, height);
}

}  // namespace gs::app
