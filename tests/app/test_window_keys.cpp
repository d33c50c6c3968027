// The window's keyboard for X3D's key device sensors (X3D 4.0 clause 21) under Xvfb: a
// window script's keys reach the active viewport's KeySensor and StringSensor.
#include "app/window_keys.hpp"
#include "process.hpp"
#include "test_support.hpp"
#include "xvfb.hpp"

#include <GLFW/glfw3.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

namespace fs = std::filesystem;

std::string windowKeysText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("GLFW keys: action keys, modifiers, Enter and Backspace map to runtime keys",
          "[app][keys]") {
  using gs::runtime::ActionKey;
  using gs::runtime::Key;
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_F1) == Key::of(ActionKey::f1));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_F12) == Key::of(ActionKey::f12));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_PAGE_DOWN) == Key::of(ActionKey::pageDown));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_RIGHT) == Key::of(ActionKey::right));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_RIGHT_SHIFT) == Key::of(ActionKey::shift));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_LEFT_CONTROL) == Key::of(ActionKey::control));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_KP_ENTER) == Key::of(gs::runtime::kKeyEnter));
  CHECK(gs::app::keyOfGlfw(GLFW_KEY_BACKSPACE) == Key::of(gs::runtime::kKeyBackspace));
  CHECK_FALSE(gs::app::keyOfGlfw(GLFW_KEY_A));  // typed through the char callback
  CHECK_FALSE(gs::app::keyOfGlfw(GLFW_KEY_F13));
}

TEST_CASE("GLFW keys: a character's release repeats what its press typed", "[app][keys]") {
  using gs::app::KeyInput;
  using gs::runtime::ActionKey;
  using gs::runtime::Key;
  gs::app::KeyboardQueue q;
  q.key(GLFW_KEY_LEFT_SHIFT, GLFW_PRESS);
  q.key(GLFW_KEY_A, GLFW_PRESS);
  q.character(U'A');
  q.key(GLFW_KEY_RIGHT_SHIFT, GLFW_PRESS);    // a second Shift: no second shiftKey
  q.key(GLFW_KEY_LEFT_SHIFT, GLFW_RELEASE);   // one Shift is still down
  q.key(GLFW_KEY_RIGHT_SHIFT, GLFW_RELEASE);  // the last one
  q.key(GLFW_KEY_A, GLFW_RELEASE);            // releases "A", not "a"
  q.character(0x263A);                        // an input method's character: down and up
  q.key(GLFW_KEY_F2, GLFW_PRESS);
  q.key(GLFW_KEY_F2, GLFW_REPEAT);
  q.key(GLFW_KEY_F2, GLFW_RELEASE);
  q.key(GLFW_KEY_B, GLFW_RELEASE);  // never typed: nothing
  const std::vector<KeyInput> expected{
      {Key::of(ActionKey::shift), true},  {Key::of(U'A'), true},
      {Key::of(ActionKey::shift), false}, {Key::of(U'A'), false},
      {Key::of(U'\u263A'), true},         {Key::of(U'\u263A'), false},
      {Key::of(ActionKey::f2), true},     {Key::of(ActionKey::f2), true},
      {Key::of(ActionKey::f2), false}};
  CHECK(q.take() == expected);
  CHECK(q.take().empty());
}

TEST_CASE("a window script's keys reach the world's KeySensor and StringSensor",
          "[app][window][keys]") {
  gs::test::Xvfb x;
  if (gs::test::skipWithoutXvfb(x)) return;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-keys";
  fs::create_directories(dir);
  const fs::path world = dir / "keys.x3dv", script = dir / "keys.script",
                 trace = dir / "keys.jsonl";
  std::ofstream(world) << R"(#X3D V4.0 utf8
PROFILE Interchange
COMPONENT KeyDeviceSensor:2
Shape { geometry Box {} }
DEF K KeySensor {}
DEF S StringSensor {}
)";
  std::ofstream(script) << "wait-loaded\ntime 5\nkey F3\nkey-down Shift\ntype Hi there\n"
                        << "key-up Shift\nkey Backspace\nkey Enter\nquit\n";
  auto r = gs::test::runGhostspace(
      {"--size", "320x240", "--new-instance", "--time", "1", "--trace-events", trace.string(),
       "--script", script.string(), world.string()},
      {"DISPLAY=" + x.display()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const std::string events = windowKeysText(trace);
  INFO(events);
  const auto has = [&](const std::string& line) { return events.find(line) != std::string::npos; };
  CHECK(has(R"({"time":5.000,"node":"K","field":"actionKeyPress","value":"3"})"));
  CHECK(has(R"({"time":5.000,"node":"K","field":"actionKeyRelease","value":"3"})"));
  CHECK(has(R"({"time":5.000,"node":"K","field":"shiftKey","value":"TRUE"})"));
  CHECK(has(R"({"time":5.000,"node":"K","field":"keyPress","value":"\"H\""})"));
  CHECK(has(R"({"time":5.000,"node":"K","field":"keyRelease","value":"\" \""})"));
  CHECK(has(R"({"time":5.000,"node":"K","field":"shiftKey","value":"FALSE"})"));
  CHECK(has(R"({"time":5.000,"node":"S","field":"enteredText","value":"\"Hi there\""})"));
  CHECK(has(R"({"time":5.000,"node":"S","field":"enteredText","value":"\"Hi ther\""})"));
  CHECK(has(R"({"time":5.000,"node":"S","field":"finalText","value":"\"Hi ther\""})"));
}

TEST_CASE("a window script names its keys or fails at load", "[app][window][keys]") {
  gs::test::Xvfb x;  // the window opens before the script is read
  if (gs::test::skipWithoutXvfb(x)) return;
  const fs::path dir = fs::path(GS_BINARY_DIR) / "window-keys";
  fs::create_directories(dir);
  const fs::path script = dir / "bad-key.script";
  std::ofstream(script) << "key F13\nquit\n";
  auto r =
      gs::test::runGhostspace({"--size", "320x240", "--new-instance", "--script", script.string()},
                              {"DISPLAY=" + x.display()});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("bad-key.script:1: expected key K") != std::string::npos);
}
