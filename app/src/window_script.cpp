#include "app/window_script.hpp"

#include <charconv>
#include <chrono>
#include <fstream>
#include <sstream>

#include "render/image.hpp"

#include <algorithm>
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

bool isInteraction(const std::string& verb) {
  return verb == "time" || verb == "advance" || verb == "pointer" || verb == "press" ||
         verb == "release" || verb == "click" || verb == "drag" || verb == "key";
}

}  // namespace

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
    double number = 0.0;
    if (c.verb == "layout") {
      if (!layoutFromName(c.argument)) return fail("layout 1x1, 2x1 or 2x2");
    } else if (c.verb == "viewport") {
      if (!parseNumber(c.argument, number) || number < 0 || number > 3)
        return fail("viewport 0..3");
    } else if (c.verb == "viewpoint") {
      if (!parseNumber(c.argument, number) || number < 0 || number > 1e6)
        return fail("viewpoint N (index in the Viewpoints menu, from 0)");
    } else if (c.verb == "lod") {
      if (!parseNumber(c.argument, number) || !(number > 0.0) || number > 1.0)
        return fail("lod F with 0 < F <= 1");
    } else if (c.verb == "mode") {
      if (!render::renderModeFromName(c.argument)) return fail("mode polygons, splats or outlines");
    } else if (c.verb == "frames") {
      if (!parseNumber(c.argument, number) || number < 1 || number > 1e6)
        return fail("frames N with N >= 1");
    } else if (c.verb == "wait-viewports") {
      if (!parseNumber(c.argument, number) || number < 1 || number > 4)
        return fail("wait-viewports N with 1 <= N <= 4");
    } else if (c.verb == "auto-lod") {
      if (c.argument != "on" && c.argument != "off") return fail("auto-lod on or off");
    } else if (c.verb == "budget") {
      if (!parseNumber(c.argument, number) || number < 0 || number > 1e12)
        return fail("budget N (vectors per frame, 0: none)");
    } else if (c.verb == "frame-target") {
      if (!parseNumber(c.argument, number) || !(number > 0.0) || number > 10000)
        return fail("frame-target MS with 0 < MS <= 10000");
    } else if (c.verb == "open" || c.verb == "screenshot" || c.verb == "screenshot-viewport" ||
               c.verb == "status" || c.verb == "frame-stats") {
      if (c.argument.empty()) return fail(c.verb + " followed by a path");
    } else if (isInteraction(c.verb)) {
      std::vector<double> n;
      const bool numbers = parseNumbers(c.argument, n);
      if ((c.verb == "time" || c.verb == "advance") &&
          (!numbers || n.size() != 1 || n[0] < 0.0 || n[0] > 1e12))
        return fail(c.verb + " S with S >= 0 seconds");
      if ((c.verb == "pointer" || c.verb == "click") && (!numbers || n.size() != 2))
        return fail(c.verb + " X Y (pixels)");
      if (c.verb == "drag" && (!numbers || (n.size() != 4 && n.size() != 5) ||
                               (n.size() == 5 && (n[4] < 1 || n[4] > 10000))))
        return fail("drag X1 Y1 X2 Y2 [STEPS] with 1 <= STEPS <= 10000");
      if ((c.verb == "press" || c.verb == "release") && !c.argument.empty())
        return fail(c.verb + " without arguments");
      if (c.verb == "key" && c.argument.empty()) return fail("key K");
    } else if (isNavigation(c.verb)) {
      if (const std::string expected = checkNavigation(c); !expected.empty()) return fail(expected);
    } else if (c.verb != "wait-loaded" && c.verb != "quit") {
      return fail(
          "a command (layout, open, viewport, lod, mode, wait-loaded, frames, "
          "screenshot, screenshot-viewport, time, advance, pointer, press, release, click, "
          "drag, key, navigation, walk, back, forward, camera, frame-stats, quit)");
    }
    commands_.push_back(std::move(c));
  }
  return true;
}

bool WindowScript::step(WindowState& state, int width, int height) {
  frameStamps_.push_back(now());  // one call per frame drawn: frame-stats
  if (framesLeft_ > 0 && --framesLeft_ > 0) return true;
  while (next_ < commands_.size()) {
    const Command& c = commands_[next_];
    double number = 0.0;
    parseNumber(c.argument, number);
    if (isInteraction(c.verb)) {
      interact(state, c, height);
      ++next_;
      return true;  // drawn once before the next command, so screenshots show it
    }
    if (isNavigation(c.verb)) {
      navigate(state, c);
      ++next_;
      return true;
    }
    if (c.verb == "wait-loaded") {
      // Settled for two frames running: the frame after a change has drawn (and so asked
      // for what its level of detail needs) and nothing new started.
      if (waitStart_ < 0.0) waitStart_ = now();
      settledFrames_ = state.session->settled() ? settledFrames_ + 1 : 0;
      if (settledFrames_ < 3 && now() - waitStart_ < 60.0) return true;
      if (settledFrames_ < 3)
        state.log.push_back(
            {true, "script line " + std::to_string(c.line) + ": still loading after 60 s"});
      waitStart_ = -1.0;
      settledFrames_ = 0;
    } else if (c.verb == "wait-viewports") {
      if (waitStart_ < 0.0) waitStart_ = now();
      std::size_t shown = 0;
      for (const Viewport& v : state.viewports) shown += v.world != Viewport::kNone ? 1 : 0;
      if (shown < static_cast<std::size_t>(number) && now() - waitStart_ < 60.0) return true;
      if (shown < static_cast<std::size_t>(number))
        state.log.push_back({true, "script line " + std::to_string(c.line) +
                                       ": fewer viewports than asked after 60 s"});
      waitStart_ = -1.0;
    } else if (c.verb == "frames") {
      framesLeft_ = static_cast<int>(number);
      ++next_;
      return true;
    } else if (c.verb == "layout") {
      state.setLayout(*layoutFromName(c.argument));
    } else if (c.verb == "open") {
      state.open(c.argument);
    } else if (c.verb == "viewport") {
      const auto index = static_cast<std::size_t>(number);
      if (index < state.viewports.size()) state.active = index;
    } else if (c.verb == "viewpoint") {
      state.jumpToViewpoint(static_cast<std::size_t>(number));
    } else if (c.verb == "lod") {
      state.setLod(number);
    } else if (c.verb == "mode") {
      state.setMode(*render::renderModeFromName(c.argument));
    } else if (c.verb == "screenshot" || c.verb == "screenshot-viewport") {
      ViewportRect r{0, 0, width, height};
      if (c.verb == "screenshot-viewport") r = state.view().rect;
      try {
        render::writePng(c.argument, render::readPixels(r.x, r.y, r.width, r.height));
        state.log.push_back({false, "screenshot " + c.argument});
      } catch (const std::exception& e) {
        state.log.push_back({true, std::string("screenshot: ") + e.what()});
      }
    } else if (c.verb == "auto-lod") {
      state.view().autoLod = c.argument == "on";
    } else if (c.verb == "budget") {
      state.setVectorBudget(static_cast<std::uint64_t>(number));
    } else if (c.verb == "frame-target") {
      state.frameTarget = number / 1000.0;
    } else if (c.verb == "frame-stats") {
      writeFrameStats(state, c.argument);
    } else if (c.verb == "status") {
      std::ofstream out(c.argument);
      for (std::size_t i = 0; i < state.viewports.size(); ++i) {
        const Viewport& v = state.viewports[i];
        const char* navs[] = {"EXAMINE", "WALK", "FLY"};
        out << i << " " << (v.world < state.worlds.size() ? state.worlds[v.world].scene->url : "-")
            << " " << v.options.lod << " " << render::renderModeName(v.options.traversal.mode)
            << " " << navs[static_cast<int>(v.navigator.mode())] << " "
            << (v.renderer ? v.renderer->statistics().splats : 0) << "\n";
      }
      for (const session::TilesetStream* t : state.session->tilesets()) {
        const session::TilesetStatistics& s = t->statistics();
        out << "tileset " << t->url() << " resident " << s.residentVectors << " peak "
            << s.peakResidentVectors << " evicted " << s.evictedBricks << " requests " << s.requests
            << " bytes " << s.brickBytes << " chosen " << s.chosenVectors << "\n";
      }
      if (!out) state.log.push_back({true, "status: cannot write " + c.argument});
    } else if (c.verb == "quit") {
      ++next_;
      return false;
    }
    ++next_;
  }
  return true;
}

bool WindowScript::interact(WindowState& state, const Command& c, int height) {
  std::vector<double> n;
  parseNumbers(c.argument, n);
  auto to = [&](double x, double y) {
    pointerX_ = static_cast<float>(x);
    pointerY_ = static_cast<float>(y);
    state.pointerInput(pointerX_, pointerY_, buttonDown_, height);
  };
  auto button = [&](bool down) {
    buttonDown_ = down;
    state.pointerInput(pointerX_, pointerY_, buttonDown_, height);
  };
  if (c.verb == "time") {
    state.setWorldTime(n[0]);
  } else if (c.verb == "advance") {
    state.setWorldTime(state.worldTime() + n[0]);
  } else if (c.verb == "pointer") {
    to(n[0], n[1]);
  } else if (c.verb == "press") {
    button(true);
  } else if (c.verb == "release") {
    button(false);
  } else if (c.verb == "click") {
    to(n[0], n[1]);
    button(true);
    button(false);
  } else if (c.verb == "drag") {
    const int steps = n.size() == 5 ? static_cast<int>(n[4]) : 10;
    to(n[0], n[1]);
    button(true);
    const bool held = state.pointerHeld;
    for (int i = 1; i <= steps; ++i) {
      const double f = static_cast<double>(i) / steps;
      const float x0 = pointerX_, y0 = pointerY_;
      to(n[0] + (n[2] - n[0]) * f, n[1] + (n[3] - n[1]) * f);
      if (!held && state.view().renderer) {  // no sensor holds it: the drag navigates
        Viewport& v = state.view();
        const int h = std::max(1, v.rect.height);
        if (v.navigator.mode() == render::NavigationMode::examine)
          v.navigator.orbit(pointerX_ - x0, pointerY_ - y0, h);
        else
          v.navigator.look(pointerX_ - x0, pointerY_ - y0, h);
        v.autoFrame = false;
      }
    }
    button(false);
  } else if (c.verb == "key") {
    state.log.push_back({false, "key " + c.argument + " (no key sensor in VRML97: ignored)"});
  } else {
    return false;
  }
  return true;
}

}  // namespace gs::app
