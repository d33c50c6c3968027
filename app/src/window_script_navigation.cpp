// Window script commands for navigation (app/window_script.hpp): the navigation type,
// walking against the world, Back / Forward, the camera's position.
#include "app/window_script.hpp"
#include "scene/collision.hpp"

#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace gs::app {

namespace {

std::optional<scene::NavigationMode> modeNamed(const std::string& name) {
  if (name == "EXAMINE") return scene::NavigationMode::examine;
  if (name == "WALK") return scene::NavigationMode::walk;
  if (name == "FLY") return scene::NavigationMode::fly;
  return std::nullopt;
}

/// The numbers of `text`; false when a word is not one.
bool numbers(const std::string& text, std::vector<double>& out) {
  std::istringstream words(text);
  std::string word;
  while (words >> word) {
    std::istringstream in(word);
    double v = 0.0;
    if (!(in >> v) || !in.eof()) return false;
    out.push_back(v);
  }
  return true;
}

}  // namespace

std::vector<WindowScript::Verb> WindowScript::navigationVerbs() {
  return {
      {"navigation",
       [](const Command& c) {
         return modeNamed(c.argument) ? std::string() : "navigation EXAMINE, WALK or FLY";
       },
       [](WindowScript&, WindowState& state, const Command& c, int, int) {
         state.setNavigation(*modeNamed(c.argument));
         return Next::frame;
       }},
      {"walk",
       [](const Command& c) {
         std::vector<double> n;
         if (!numbers(c.argument, n) || (n.size() != 3 && n.size() != 4) ||
             (n.size() == 4 && (n[3] < 1 || n[3] > 10000)))
           return std::string("walk F R U [STEPS] (metres) with 1 <= STEPS <= 10000");
         return std::string();
       },
       [](WindowScript&, WindowState& state, const Command& c, int, int) {
         std::vector<double> n;
         numbers(c.argument, n);
         const int steps = n.size() == 4 ? static_cast<int>(n[3]) : 1;
         for (int i = 0; i < steps; ++i)
           state.moveViewer(static_cast<float>(n[0] / steps), static_cast<float>(n[1] / steps),
                            static_cast<float>(n[2] / steps),
                            std::numeric_limits<float>::infinity());
         return Next::frame;
       }},
      {"back",
       [](const Command& c) {
         return c.argument.empty() ? std::string() : "back without arguments";
       },
       [](WindowScript&, WindowState& state, const Command& c, int, int) {
         if (!state.goBack())
           state.log.push_back(
               {false, "script line " + std::to_string(c.line) + ": no world to go back to"});
         return Next::frame;
       }},
      {"forward",
       [](const Command& c) {
         return c.argument.empty() ? std::string() : "forward without arguments";
       },
       [](WindowScript&, WindowState& state, const Command& c, int, int) {
         if (!state.goForward())
           state.log.push_back(
               {false, "script line " + std::to_string(c.line) + ": no world to go forward to"});
         return Next::frame;
       }},
      {"camera",
       [](const Command& c) {
         return c.argument.empty() ? "camera followed by a path" : std::string();
       },
       [](WindowScript&, WindowState& state, const Command& c, int, int) {
         const glm::vec3 p = state.view().navigator.camera().position;
         std::ofstream out(c.argument);
         out << p.x << " " << p.y << " " << p.z << "\n";
         if (!out) state.log.push_back({true, "camera: cannot write " + c.argument});
         return Next::frame;
       }},
  };
}

}  // namespace gs::app
