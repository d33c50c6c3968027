// The window's keyboard for the key device sensors (X3D 4.0 clause 21): GLFW callbacks
// to runtime::Key, then to the active viewport's world.
#include "app/window_keys.hpp"

#include "app/window_state.hpp"

// GLFW without its OpenGL header: glad provides GL elsewhere (and must come first in a
// unity build's translation unit).
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

namespace gs::app {

std::optional<runtime::Key> keyOfGlfw(int glfwKey) {
  using runtime::ActionKey;
  using runtime::Key;
  if (glfwKey >= GLFW_KEY_F1 && glfwKey <= GLFW_KEY_F12)
    return Key::of(static_cast<ActionKey>(glfwKey - GLFW_KEY_F1 + 1));
  switch (glfwKey) {
    case GLFW_KEY_HOME:
      return Key::of(ActionKey::home);
    case GLFW_KEY_END:
      return Key::of(ActionKey::end);
    case GLFW_KEY_PAGE_UP:
      return Key::of(ActionKey::pageUp);
    case GLFW_KEY_PAGE_DOWN:
      return Key::of(ActionKey::pageDown);
    case GLFW_KEY_UP:
      return Key::of(ActionKey::up);
    case GLFW_KEY_DOWN:
      return Key::of(ActionKey::down);
    case GLFW_KEY_LEFT:
      return Key::of(ActionKey::left);
    case GLFW_KEY_RIGHT:
      return Key::of(ActionKey::right);
    case GLFW_KEY_LEFT_SHIFT:
    case GLFW_KEY_RIGHT_SHIFT:
      return Key::of(ActionKey::shift);
    case GLFW_KEY_LEFT_CONTROL:
    case GLFW_KEY_RIGHT_CONTROL:
      return Key::of(ActionKey::control);
    case GLFW_KEY_LEFT_ALT:
    case GLFW_KEY_RIGHT_ALT:
      return Key::of(ActionKey::alt);
    case GLFW_KEY_ENTER:
    case GLFW_KEY_KP_ENTER:
      return Key::of(runtime::kKeyEnter);
    case GLFW_KEY_BACKSPACE:
      return Key::of(runtime::kKeyBackspace);
    case GLFW_KEY_TAB:
      return Key::of(U'\t');
    case GLFW_KEY_ESCAPE:
      return Key::of(U'\x1B');
    case GLFW_KEY_DELETE:
      return Key::of(U'\x7F');
    default:
      return std::nullopt;
  }
}

void KeyboardQueue::key(int glfwKey, int action) {
  const bool press = action == GLFW_PRESS || action == GLFW_REPEAT;
  if (const auto k = keyOfGlfw(glfwKey)) {
    lastPressed_ = -1;
    if (k->isModifier()) {  // both Shift keys are one shiftKey
      int& down = mods_[k->action];
      if (action == GLFW_PRESS && down++ > 0) return;
      if (action == GLFW_REPEAT) return;
      if (action == GLFW_RELEASE && (down == 0 || --down > 0)) return;
    }
    queued_.push_back({*k, press});
    return;
  }
  if (press) {
    lastPressed_ = glfwKey;  // its character arrives through character()
    return;
  }
  if (glfwKey == lastPressed_) lastPressed_ = -1;
  const auto it = typed_.find(glfwKey);
  if (it == typed_.end()) return;
  queued_.push_back({runtime::Key::of(it->second), false});
  typed_.erase(it);
}

void KeyboardQueue::character(unsigned int codePoint) {
  const runtime::Key k = runtime::Key::of(static_cast<char32_t>(codePoint));
  if (!k.valid()) return;
  queued_.push_back({k, true});
  if (lastPressed_ < 0) {  // typed without a key of its own (an input method): up at once
    queued_.push_back({k, false});
    return;
  }
  // A different character from the same key (a repeat after Shift changed): release the
  // old one first so that every press has its release.
  const auto it = typed_.find(lastPressed_);
  if (it != typed_.end() && it->second != k.character)
    queued_.insert(queued_.end() - 1, {runtime::Key::of(it->second), false});
  typed_[lastPressed_] = k.character;
}

std::vector<KeyInput> KeyboardQueue::take() {
  std::vector<KeyInput> out;
  out.swap(queued_);
  return out;
}

void KeyboardQueue::install(GLFWwindow* window, KeyboardQueue& queue) {
  glfwSetWindowUserPointer(window, &queue);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int glfwKey, int, int action, int) {
    if (auto* q = static_cast<KeyboardQueue*>(glfwGetWindowUserPointer(w))) q->key(glfwKey, action);
  });
  glfwSetCharCallback(window, [](GLFWwindow* w, unsigned int c) {
    if (auto* q = static_cast<KeyboardQueue*>(glfwGetWindowUserPointer(w))) q->character(c);
  });
}

void WindowState::keyInput(const runtime::Key& key, bool press) {
  if (!runtimes || viewports.empty()) return;
  const Viewport& v = view();
  if (!v.renderer() || v.world >= worlds.size()) return;
  runtime::ExecutionModel& model = runtimes->of(worlds[v.world].scene, worldTime());
  // At the world's time of this frame: the window's clock moves the worlds in its steps.
  if (press)
    model.keyPress(key, model.now());
  else
    model.keyRelease(key, model.now());
}

bool WindowState::worldWantsKeys() const {
  if (!runtimes || viewports.empty()) return false;
  const Viewport& v = view();
  if (!v.renderer() || v.world >= worlds.size()) return false;
  return runtimes->of(worlds[v.world].scene, worldTime()).wantsKeys();
}

}  // namespace gs::app
