// Keyboard input for the execution model (ISO/IEC 19775-1 X3D 4.0 clause 21, "Key device
// sensor component"): a key is a character (a Unicode code point) or an action key of
// table 21.2 or a modifier. The application translates its window system's keys into
// these (app/src/window_keys.cpp for GLFW); see ExecutionModel::keyPress().
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace gs::runtime {

/// The keys that produce no character. F1 .. RIGHT carry the values KeySensor sends as
/// actionKeyPress / actionKeyRelease (X3D 4.0 table 21.2: F1..F12 = 1..12, HOME = 13,
/// END = 14, PGUP = 15, PGDN = 16, UP = 17, DOWN = 18, LEFT = 19, RIGHT = 20); shift,
/// control and alt are the modifiers of shiftKey, controlKey and altKey (their values are
/// never sent).
enum class ActionKey : std::int32_t {
  none = 0,
  f1 = 1,
  f2 = 2,
  f3 = 3,
  f4 = 4,
  f5 = 5,
  f6 = 6,
  f7 = 7,
  f8 = 8,
  f9 = 9,
  f10 = 10,
  f11 = 11,
  f12 = 12,
  home = 13,
  end = 14,
  pageUp = 15,
  pageDown = 16,
  up = 17,
  down = 18,
  left = 19,
  right = 20,
  shift = 100,
  control = 101,
  alt = 102,
};

/// Characters with a meaning of their own: Enter ends a StringSensor's text (finalText),
/// Backspace deletes its last character when deletionAllowed (X3D 4.0 21.4.2). A
/// KeySensor sends them as keyPress / keyRelease like any other character.
inline constexpr char32_t kKeyEnter = U'\r';
inline constexpr char32_t kKeyBackspace = U'\b';

/// One key: a character (`action` none, `character` a Unicode code point, 1 ..
/// 0x10FFFF, surrogates excluded) or an action key / modifier (`character` 0).
struct Key {
  char32_t character = 0;
  ActionKey action = ActionKey::none;

  /// The key that types code point `c`.
  static constexpr Key of(char32_t c) { return Key{c, ActionKey::none}; }
  /// Action key or modifier `a`.
  static constexpr Key of(ActionKey a) { return Key{0, a}; }
  /// Whether it is a character key (else an action key or a modifier).
  constexpr bool isCharacter() const { return action == ActionKey::none; }
  /// Whether it is Shift, Control or Alt.
  constexpr bool isModifier() const {
    return action == ActionKey::shift || action == ActionKey::control || action == ActionKey::alt;
  }
  /// Whether it is a valid key: a character in 1 .. 0x10FFFF outside the surrogates, or
  /// an action key / modifier listed in ActionKey.
  bool valid() const;
  bool operator==(const Key&) const = default;
};

/// Code point `c` as UTF-8 (1 to 4 bytes); "" when it is not a valid code point (0,
/// surrogates, above 0x10FFFF).
std::string utf8Of(char32_t c);

/// A key named as in window scripts (app/window_script.hpp `key K`): one UTF-8 character
/// ("a", "é", "7"), a name (case-insensitive: F1 .. F12, Home, End, PgUp, PgDn, Up, Down,
/// Left, Right, Shift, Control / Ctrl, Alt, Enter / Return, Backspace, Tab, Escape / Esc,
/// Space) or "U+XXXX" (a hexadecimal code point). Empty when `name` is none of these.
std::optional<Key> keyNamed(std::string_view name);

}  // namespace gs::runtime
