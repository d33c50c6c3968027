// The X3D Key device sensor component (X3D 4.0 clause 21): KeySensor (21.4.1) and
// StringSensor (21.4.2), fed by ExecutionModel::keyPress / keyRelease. Every enabled key
// device sensor of the world receives every key (the browser has one keyboard; there is
// no focus between sensors), in the order the execution model met them. Each key is one
// timestamp at the clock's now().
#include "execution_state.hpp"

#include <algorithm>
#include <string_view>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

FieldValue keyBool(bool b) {
  return FieldValue::make<FieldType::SFBool>(b);
}

FieldValue keyString(std::string s) {
  return FieldValue::make<FieldType::SFString>(std::move(s));
}

/// The outputOnly field of a KeySensor that a modifier drives (shiftKey ...), -1 for other
/// keys.
int modifierField(const KeySensorState& k, const Key& key) {
  switch (key.action) {
    case ActionKey::shift:
      return k.shiftKey;
    case ActionKey::control:
      return k.controlKey;
    case ActionKey::alt:
      return k.altKey;
    default:
      return -1;
  }
}

/// Whether StringSensor text takes `c` (printable: not a C0 control, not DEL).
bool typesText(char32_t c) {
  return c >= 0x20 && c != 0x7F;
}

/// `text` without its last UTF-8 character (continuation bytes and their lead byte).
void dropLastCharacter(std::string& text) {
  while (!text.empty() && (static_cast<unsigned char>(text.back()) & 0xC0) == 0x80) text.pop_back();
  if (!text.empty()) text.pop_back();
}

bool sensorEnabled(const NodeState& ns) {
  const KeySensorState& k = *ns.keys;
  if (k.enabled < 0) return true;
  const FieldValue& f = ns.node->fieldAt(static_cast<std::size_t>(k.enabled));
  return f.type() != FieldType::SFBool || f.get<FieldType::SFBool>();
}

}  // namespace

bool Key::valid() const {
  if (action == ActionKey::none)
    return character >= 1 && character <= 0x10FFFF && !(character >= 0xD800 && character <= 0xDFFF);
  if (character != 0) return false;
  const auto a = static_cast<std::int32_t>(action);
  return (a >= 1 && a <= 20) || isModifier();
}

std::string utf8Of(char32_t c) {
  std::string out;
  if (c == 0 || c > 0x10FFFF || (c >= 0xD800 && c <= 0xDFFF)) return out;
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (c >> 18));
    out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
  return out;
}

namespace {

/// The one code point `s` encodes in UTF-8 (shortest form), or nothing.
std::optional<char32_t> singleCodePoint(std::string_view s) {
  if (s.empty()) return std::nullopt;
  const auto b0 = static_cast<unsigned char>(s[0]);
  std::size_t n = 0;
  char32_t c = 0;
  if (b0 < 0x80) {
    n = 1;
    c = b0;
  } else if ((b0 & 0xE0) == 0xC0) {
    n = 2;
    c = b0 & 0x1F;
  } else if ((b0 & 0xF0) == 0xE0) {
    n = 3;
    c = b0 & 0x0F;
  } else if ((b0 & 0xF8) == 0xF0) {
    n = 4;
    c = b0 & 0x07;
  } else {
    return std::nullopt;
  }
  if (s.size() != n) return std::nullopt;
  for (std::size_t i = 1; i < n; ++i) {
    const auto b = static_cast<unsigned char>(s[i]);
    if ((b & 0xC0) != 0x80) return std::nullopt;
    c = (c << 6) | (b & 0x3F);
  }
  if (utf8Of(c) != s) return std::nullopt;  // overlong, surrogate or out of range
  return c;
}

std::string lowerAscii(std::string_view s) {
  std::string out(s);
  for (char& ch : out)
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  return out;
}

}  // namespace

std::optional<Key> keyNamed(std::string_view name) {
  if (const auto c = singleCodePoint(name)) return Key::of(*c);
  const std::string lower = lowerAscii(name);
  if (lower.size() >= 3 && lower.starts_with("u+")) {
    char32_t c = 0;
    for (std::size_t i = 2; i < lower.size(); ++i) {
      const char h = lower[i];
      if (i >= 8) return std::nullopt;
      if (h >= '0' && h <= '9')
        c = c * 16 + static_cast<char32_t>(h - '0');
      else if (h >= 'a' && h <= 'f')
        c = c * 16 + static_cast<char32_t>(h - 'a' + 10);
      else
        return std::nullopt;
    }
    const Key k = Key::of(c);
    return k.valid() ? std::optional<Key>(k) : std::nullopt;
  }
  if (lower.size() >= 2 && lower[0] == 'f') {
    int n = 0;
    for (std::size_t i = 1; i < lower.size(); ++i) {
      if (lower[i] < '0' || lower[i] > '9' || i > 2) return std::nullopt;
      n = n * 10 + (lower[i] - '0');
    }
    if (n >= 1 && n <= 12) return Key::of(static_cast<ActionKey>(n));
    return std::nullopt;
  }
  struct Named {
    std::string_view name;
    Key key;
  };
  static constexpr Named kNamed[] = {
      {"home", Key::of(ActionKey::home)},
      {"end", Key::of(ActionKey::end)},
      {"pgup", Key::of(ActionKey::pageUp)},
      {"pageup", Key::of(ActionKey::pageUp)},
      {"pgdn", Key::of(ActionKey::pageDown)},
      {"pagedown", Key::of(ActionKey::pageDown)},
      {"up", Key::of(ActionKey::up)},
      {"down", Key::of(ActionKey::down)},
      {"left", Key::of(ActionKey::left)},
      {"right", Key::of(ActionKey::right)},
      {"shift", Key::of(ActionKey::shift)},
      {"control", Key::of(ActionKey::control)},
      {"ctrl", Key::of(ActionKey::control)},
      {"alt", Key::of(ActionKey::alt)},
      {"enter", Key::of(kKeyEnter)},
      {"return", Key::of(kKeyEnter)},
      {"backspace", Key::of(kKeyBackspace)},
      {"tab", Key::of(U'\t')},
      {"escape", Key::of(U'\x1B')},
      {"esc", Key::of(U'\x1B')},
      {"space", Key::of(U' ')},
  };
  for (const Named& n : kNamed)
    if (n.name == lower) return n.key;
  return std::nullopt;
}

bool ExecutionModel::State::classifyKeySensor(NodeState& ns) {
  const vrml::NodeTypeId id = ns.node->typeId();
  if (id != vrml::NodeTypeId::KeySensor && id != vrml::NodeTypeId::StringSensor) return false;
  ns.role = NodeRole::keySensor;
  ns.keys = std::make_unique<KeySensorState>();
  KeySensorState& k = *ns.keys;
  const vrml::NodeType& type = ns.node->type();
  auto idx = [&](std::string_view name) { return type.findExact(name); };
  k.string = id == vrml::NodeTypeId::StringSensor;
  k.enabled = idx("enabled");
  k.isActive = idx("isActive");
  if (k.string) {
    k.deletionAllowed = idx("deletionAllowed");
    k.enteredText = idx("enteredText");
    k.finalText = idx("finalText");
  } else {
    k.keyPress = idx("keyPress");
    k.keyRelease = idx("keyRelease");
    k.actionKeyPress = idx("actionKeyPress");
    k.actionKeyRelease = idx("actionKeyRelease");
    k.shiftKey = idx("shiftKey");
    k.controlKey = idx("controlKey");
    k.altKey = idx("altKey");
  }
  keySensors.push_back(&ns);
  return true;
}

void ExecutionModel::State::deliverKeySensor(NodeState& ns, int field, FieldValue value) {
  const bool on = value.get<FieldType::SFBool>();
  emitOwn(ns, field, std::move(value));
  KeySensorState& k = *ns.keys;
  if (on || !k.active) return;
  k.active = false;
  k.held.clear();
  emitOwn(ns, k.isActive, keyBool(false));
  if (k.string && !k.text.empty()) {
    k.text.clear();
    emitOwn(ns, k.enteredText, keyString(std::string()));
  }
}

void ExecutionModel::State::keyEvent(const Key& key, bool press) {
  for (NodeState* ns : keySensors) {
    if (!sensorEnabled(*ns)) continue;
    KeySensorState& k = *ns->keys;
    if (k.string) {
      // 21.4.2: characters build enteredText; Backspace deletes; Enter terminates.
      if (!press || !key.isCharacter()) continue;
      if (key.character == kKeyEnter) {
        if (!k.active) continue;
        std::string text;
        text.swap(k.text);
        emitOwn(*ns, k.finalText, keyString(std::move(text)));
        emitOwn(*ns, k.enteredText, keyString(std::string()));
        k.active = false;
        emitOwn(*ns, k.isActive, keyBool(false));
      } else if (key.character == kKeyBackspace) {
        const bool allowed =
            k.deletionAllowed < 0 ||
            ns->node->fieldAt(static_cast<std::size_t>(k.deletionAllowed)).get<FieldType::SFBool>();
        if (!k.active || !allowed || k.text.empty()) continue;
        dropLastCharacter(k.text);
        emitOwn(*ns, k.enteredText, keyString(k.text));
      } else if (typesText(key.character)) {
        if (!k.active) {
          k.active = true;
          emitOwn(*ns, k.isActive, keyBool(true));
        }
        k.text += utf8Of(key.character);
        emitOwn(*ns, k.enteredText, keyString(k.text));
      }
      continue;
    }
    // 21.4.1: KeySensor.
    const auto held = std::find(k.held.begin(), k.held.end(), key);
    if (press) {
      const bool repeat = held != k.held.end();
      if (repeat && key.isModifier()) continue;
      if (!repeat) k.held.push_back(key);
      if (!k.active) {
        k.active = true;
        emitOwn(*ns, k.isActive, keyBool(true));
      }
      if (key.isModifier())
        emitOwn(*ns, modifierField(k, key), keyBool(true));
      else if (key.isCharacter())
        emitOwn(*ns, k.keyPress, keyString(utf8Of(key.character)));
      else
        emitOwn(*ns, k.actionKeyPress,
                FieldValue::make<FieldType::SFInt32>(static_cast<std::int32_t>(key.action)));
    } else {
      if (held == k.held.end()) continue;  // went down before the sensor was enabled
      k.held.erase(held);
      if (key.isModifier())
        emitOwn(*ns, modifierField(k, key), keyBool(false));
      else if (key.isCharacter())
        emitOwn(*ns, k.keyRelease, keyString(utf8Of(key.character)));
      else
        emitOwn(*ns, k.actionKeyRelease,
                FieldValue::make<FieldType::SFInt32>(static_cast<std::int32_t>(key.action)));
      if (k.held.empty() && k.active) {
        k.active = false;
        emitOwn(*ns, k.isActive, keyBool(false));
      }
    }
  }
}

namespace {

void runKeyEvent(ExecutionModel& model, ExecutionModel::State& s, ExecutionStatistics& stats,
                 const Key& key, bool press, double time) {
  if (!key.valid()) return;
  if (time > model.now()) model.advanceTo(time);
  ++s.stamp;
  ++stats.cascades;
  s.eventsThisCascade = 0;
  s.cascadeOverflow = false;
  s.keyEvent(key, press);
  s.runCascade();
  s.initializeScripts();
}

}  // namespace

void ExecutionModel::keyPress(const Key& key, double time) {
  runKeyEvent(*this, *s_, stats_, key, true, time);
}

void ExecutionModel::keyRelease(const Key& key, double time) {
  runKeyEvent(*this, *s_, stats_, key, false, time);
}

bool ExecutionModel::wantsKeys() const {
  return std::any_of(s_->keySensors.begin(), s_->keySensors.end(),
                     [](const NodeState* ns) { return sensorEnabled(*ns); });
}

}  // namespace gs::runtime
