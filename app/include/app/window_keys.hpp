// The window's keyboard for the worlds' key device sensors (X3D 4.0 clause 21): GLFW's
// key callback gives action keys, modifiers, Enter, Backspace, Tab, Escape, Delete and
// every key's release; its char callback gives the characters typed. They are queued
// while GLFW polls and handed to WindowState::keyInput() once a frame.
#pragma once

#include "runtime/keys.hpp"

#include <map>
#include <optional>
#include <vector>

struct GLFWwindow;

namespace gs::app {

/// One key down or up, as the world will get it.
struct KeyInput {
  runtime::Key key;
  bool press = true;
  bool operator==(const KeyInput&) const = default;
};

/// The runtime key of GLFW key code `glfwKey` (GLFW_KEY_*) when it types no character
/// through the char callback: F1..F12, Home, End, Page Up / Down, the arrows, the
/// modifiers (left and right alike), Enter (and keypad Enter) as kKeyEnter, Backspace as
/// kKeyBackspace, Tab, Escape and Delete as their control characters. Empty for the keys
/// that type characters (and keys with no meaning to X3D).
std::optional<runtime::Key> keyOfGlfw(int glfwKey);

/// Turns GLFW's key and char callbacks into KeyInputs (a key's release repeats the
/// character its press typed; with both Shift keys down, shiftKey goes FALSE only when
/// the last is released). Not thread-safe: GLFW calls back on the main thread.
class KeyboardQueue {
 public:
  /// GLFW key callback data: `glfwKey` (GLFW_KEY_*), `action` (GLFW_PRESS, GLFW_REPEAT,
  /// GLFW_RELEASE).
  void key(int glfwKey, int action);
  /// GLFW char callback data: the Unicode code point typed (by the last key pressed).
  void character(unsigned int codePoint);
  /// The inputs queued since the last call, oldest first.
  std::vector<KeyInput> take();

  /// Installs GLFW key and char callbacks on `window` that feed `queue` (stored as the
  /// window's user pointer; `queue` must outlive the callbacks). Call before ImGui
  /// installs its own: ImGui's GLFW backend then calls these first.
  static void install(GLFWwindow* window, KeyboardQueue& queue);

 private:
  std::vector<KeyInput> queued_;
  int lastPressed_ = -1;                    // the GLFW key the next character belongs to
  std::map<int, char32_t> typed_;           // GLFW key -> the character its press typed
  std::map<runtime::ActionKey, int> mods_;  // modifier -> keys of it down
};

}  // namespace gs::app
