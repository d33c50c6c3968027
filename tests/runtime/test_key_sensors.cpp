// The X3D Key device sensor component (X3D 4.0 clause 21) in the execution model:
// KeySensor and StringSensor fed by ExecutionModel::keyPress / keyRelease.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::ActionKey;
using gs::runtime::Key;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;
using Events = std::vector<std::string>;

namespace {

constexpr Key kShift = Key::of(ActionKey::shift);

/// Presses and releases `text`'s characters (ASCII) one after the other at `time`.
void typeKeys(RunningWorld& w, const std::string& text, double time) {
  for (char c : text) {
    w.model->keyPress(Key::of(static_cast<char32_t>(c)), time);
    w.model->keyRelease(Key::of(static_cast<char32_t>(c)), time);
  }
}

}  // namespace

TEST_CASE("key sensors: KeySensor sends keyPress, keyRelease and isActive for a character",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K KeySensor {}
DEF B BooleanToggle {}
ROUTE K.isActive TO B.set_boolean
)"));
  w.model->keyPress(Key::of(U'a'), 1.0);
  CHECK(w.take() == Events{"K.isActive=TRUE", "K.keyPress=\"a\"", "B.toggle_changed=TRUE"});
  CHECK(w.model->now() == 1.0);
  CHECK(w.node("K").field("keyPress")->get<FieldType::SFString>() == "a");
  w.model->keyRelease(Key::of(U'a'), 1.5);
  CHECK(w.take() == Events{"K.keyRelease=\"a\"", "K.isActive=FALSE"});
  CHECK(w.model->now() == 1.5);
  CHECK_FALSE(w.node("K").field("isActive")->get<FieldType::SFBool>());
}

TEST_CASE("key sensors: KeySensor's characters are UTF-8, a second key keeps it active",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld("DEF K KeySensor {}\n"));
  w.model->keyPress(Key::of(U'\u00E9'), 0.0);  // é
  CHECK(w.take() == Events{"K.isActive=TRUE", "K.keyPress=\"\xC3\xA9\""});
  w.model->keyPress(Key::of(U'\u20AC'), 0.0);  // € while é is down: no second isActive
  CHECK(w.take() == Events{"K.keyPress=\"\xE2\x82\xAC\""});
  w.model->keyRelease(Key::of(U'\u00E9'), 0.0);
  CHECK(w.take() == Events{"K.keyRelease=\"\xC3\xA9\""});
  w.model->keyRelease(Key::of(U'\u20AC'), 0.0);
  CHECK(w.take() == Events{"K.keyRelease=\"\xE2\x82\xAC\"", "K.isActive=FALSE"});
}

TEST_CASE("key sensors: auto-repeat sends keyPress again without isActive",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld("DEF K KeySensor {}\n"));
  w.model->keyPress(Key::of(U'x'), 0.0);
  w.take();
  w.model->keyPress(Key::of(U'x'), 0.1);
  w.model->keyPress(Key::of(ActionKey::shift), 0.2);
  w.model->keyPress(Key::of(ActionKey::shift), 0.3);  // a repeated modifier: nothing
  CHECK(w.take() == Events{"K.keyPress=\"x\"", "K.shiftKey=TRUE"});
  w.model->keyRelease(Key::of(U'x'), 0.4);
  CHECK(w.take() == Events{"K.keyRelease=\"x\""});  // shift is still down
  w.model->keyRelease(kShift, 0.5);
  CHECK(w.take() == Events{"K.shiftKey=FALSE", "K.isActive=FALSE"});
}

TEST_CASE("key sensors: action keys send the values of table 21.2", "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K KeySensor {}
DEF S Switch { whichChoice -1 }
ROUTE K.actionKeyPress TO S.whichChoice
)"));
  const std::pair<ActionKey, int> expected[] = {{ActionKey::f1, 1},      {ActionKey::f12, 12},
                                                {ActionKey::home, 13},   {ActionKey::end, 14},
                                                {ActionKey::pageUp, 15}, {ActionKey::pageDown, 16},
                                                {ActionKey::up, 17},     {ActionKey::down, 18},
                                                {ActionKey::left, 19},   {ActionKey::right, 20}};
  for (const auto& [key, value] : expected) {
    w.model->keyPress(Key::of(key), 0.0);
    CHECK(w.node("S").field("whichChoice")->get<FieldType::SFInt32>() == value);
    CHECK(w.node("K").field("actionKeyPress")->get<FieldType::SFInt32>() == value);
    w.model->keyRelease(Key::of(key), 0.0);
    CHECK(w.node("K").field("actionKeyRelease")->get<FieldType::SFInt32>() == value);
  }
  w.take();
  w.model->keyPress(Key::of(ActionKey::left), 0.0);
  CHECK(w.take() == Events{"K.isActive=TRUE", "K.actionKeyPress=19", "S.whichChoice_changed=19"});
  w.model->keyRelease(Key::of(ActionKey::left), 0.0);
  CHECK(w.take() == Events{"K.actionKeyRelease=19", "K.isActive=FALSE"});
  // An action key sends no keyPress; a character no actionKeyPress.
  w.model->keyPress(Key::of(U'q'), 0.0);
  CHECK(w.take() == Events{"K.isActive=TRUE", "K.keyPress=\"q\""});
}

TEST_CASE("key sensors: shift, control and alt send shiftKey, controlKey, altKey",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K KeySensor {}
DEF LS DirectionalLight { on FALSE }
DEF LC DirectionalLight { on FALSE }
DEF LA DirectionalLight { on FALSE }
ROUTE K.shiftKey TO LS.on
ROUTE K.controlKey TO LC.on
ROUTE K.altKey TO LA.on
)"));
  const auto on = [&](const char* name) {
    return w.node(name).field("on")->get<FieldType::SFBool>();
  };
  w.model->keyPress(Key::of(ActionKey::control), 0.0);
  CHECK(w.take() == Events{"K.isActive=TRUE", "K.controlKey=TRUE", "LC.on_changed=TRUE"});
  CHECK(on("LC"));
  CHECK_FALSE(on("LS"));
  w.model->keyPress(Key::of(ActionKey::alt), 0.0);
  w.model->keyPress(kShift, 0.0);
  CHECK(on("LA"));
  CHECK(on("LS"));
  w.model->keyRelease(Key::of(ActionKey::control), 0.0);
  w.model->keyRelease(Key::of(ActionKey::alt), 0.0);
  CHECK_FALSE(on("LC"));
  CHECK_FALSE(on("LA"));
  CHECK(on("LS"));
  w.take();
  w.model->keyRelease(kShift, 0.0);
  CHECK(w.take() == Events{"K.shiftKey=FALSE", "K.isActive=FALSE", "LS.on_changed=FALSE"});
}

TEST_CASE("key sensors: enabled FALSE ignores keys; disabling ends the activity",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K KeySensor { enabled FALSE }
DEF S StringSensor { enabled FALSE }
)"));
  CHECK_FALSE(w.model->wantsKeys());
  w.model->keyPress(Key::of(U'a'), 0.0);
  w.model->keyRelease(Key::of(U'a'), 0.0);
  CHECK(w.take() == Events{});
  CHECK(w.node("K").field("keyPress")->get<FieldType::SFString>().empty());

  w.send("K", "enabled", FieldValue::make<FieldType::SFBool>(true));
  w.send("S", "enabled", FieldValue::make<FieldType::SFBool>(true));
  CHECK(w.model->wantsKeys());
  w.take();
  w.model->keyPress(Key::of(U'b'), 0.0);
  CHECK(w.take() ==
        Events{"K.isActive=TRUE", "K.keyPress=\"b\"", "S.isActive=TRUE", "S.enteredText=\"b\""});
  // Disabled while a key is down: isActive FALSE, the text dropped, the release ignored.
  w.send("K", "enabled", FieldValue::make<FieldType::SFBool>(false));
  w.send("S", "enabled", FieldValue::make<FieldType::SFBool>(false));
  CHECK(w.take() == Events{"K.enabled_changed=FALSE", "K.isActive=FALSE", "S.enabled_changed=FALSE",
                           "S.isActive=FALSE", "S.enteredText=\"\""});
  w.model->keyRelease(Key::of(U'b'), 0.0);
  CHECK(w.take() == Events{});
  CHECK_FALSE(w.model->wantsKeys());
}

TEST_CASE("key sensors: a key that went down before the sensor was enabled is not released",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld("DEF K KeySensor { enabled FALSE }\n"));
  w.model->keyPress(Key::of(U'a'), 0.0);
  w.send("K", "enabled", FieldValue::make<FieldType::SFBool>(true));
  w.take();
  w.model->keyRelease(Key::of(U'a'), 0.0);
  CHECK(w.take() == Events{});
}

TEST_CASE("key sensors: every enabled KeySensor receives the key", "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K1 KeySensor {}
Transform { children DEF K2 KeySensor {} }
DEF K3 KeySensor { enabled FALSE }
)"));
  w.model->keyPress(Key::of(ActionKey::home), 0.0);
  CHECK(w.take() == Events{"K1.isActive=TRUE", "K1.actionKeyPress=13", "K2.isActive=TRUE",
                           "K2.actionKeyPress=13"});
}

TEST_CASE("key sensors: StringSensor builds enteredText and sends finalText on Enter",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF S StringSensor {}
)"));
  w.model->keyPress(Key::of(U'h'), 1.0);
  CHECK(w.take() == Events{"S.isActive=TRUE", "S.enteredText=\"h\""});
  // Releases and keys that type nothing change nothing.
  w.model->keyRelease(Key::of(U'h'), 1.0);
  w.model->keyPress(Key::of(ActionKey::f5), 1.0);
  w.model->keyPress(kShift, 1.0);
  w.model->keyPress(Key::of(U'\t'), 1.0);
  CHECK(w.take() == Events{});
  typeKeys(w, "i!", 2.0);
  CHECK(w.take() == Events{"S.enteredText=\"hi\"", "S.enteredText=\"hi!\""});
  CHECK(w.node("S").field("enteredText")->get<FieldType::SFString>() == "hi!");
  w.model->keyPress(Key::of(gs::runtime::kKeyEnter), 3.0);
  CHECK(w.take() == Events{"S.finalText=\"hi!\"", "S.enteredText=\"\"", "S.isActive=FALSE"});
  CHECK(w.node("S").field("finalText")->get<FieldType::SFString>() == "hi!");
  // Enter while inactive: nothing; the next character starts a new text.
  w.model->keyPress(Key::of(gs::runtime::kKeyEnter), 3.0);
  CHECK(w.take() == Events{});
  typeKeys(w, "ok", 4.0);
  CHECK(w.take() == Events{"S.isActive=TRUE", "S.enteredText=\"o\"", "S.enteredText=\"ok\""});
}

TEST_CASE("key sensors: Backspace deletes the last character when deletionAllowed",
          "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF S StringSensor {}
DEF N StringSensor { deletionAllowed FALSE }
)"));
  const Key backspace = Key::of(gs::runtime::kKeyBackspace);
  w.model->keyPress(backspace, 0.0);  // nothing typed yet
  CHECK(w.take() == Events{});
  typeKeys(w, "ab", 0.0);
  w.model->keyPress(Key::of(U'\u00E9'), 0.0);  // two UTF-8 bytes, one character
  w.take();
  w.model->keyPress(backspace, 0.0);
  CHECK(w.take() == Events{"S.enteredText=\"ab\""});
  CHECK(w.node("N").field("enteredText")->get<FieldType::SFString>() == "ab\xC3\xA9");
  w.model->keyPress(backspace, 0.0);
  w.model->keyPress(backspace, 0.0);
  CHECK(w.take() == Events{"S.enteredText=\"a\"", "S.enteredText=\"\""});
  w.model->keyPress(backspace, 0.0);  // empty: nothing to delete, still active
  CHECK(w.take() == Events{});
  CHECK(w.node("S").field("isActive")->get<FieldType::SFBool>());
  w.model->keyPress(Key::of(gs::runtime::kKeyEnter), 0.0);
  CHECK(w.take() == Events{"S.finalText=\"\"", "S.enteredText=\"\"", "S.isActive=FALSE",
                           "N.finalText=\"ab\xC3\xA9\"", "N.enteredText=\"\"", "N.isActive=FALSE"});
}

TEST_CASE("key sensors: a key at a later time moves the clock first", "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld(R"(
DEF K KeySensor {}
DEF C TimeSensor { cycleInterval 10 loop TRUE }
DEF TT TimeTrigger {}
ROUTE K.isActive TO TT.set_boolean
)"));
  w.model->keyPress(Key::of(U'z'), 2.5);
  CHECK(w.model->now() == 2.5);
  CHECK(w.node("TT").field("triggerTime")->get<FieldType::SFTime>() == 2.5);
  CHECK(w.node("C").field("fraction_changed")->get<FieldType::SFFloat>() == Approx(0.25));
  // An earlier time counts as now.
  w.model->keyRelease(Key::of(U'z'), 1.0);
  CHECK(w.model->now() == 2.5);
  CHECK_FALSE(w.node("K").field("isActive")->get<FieldType::SFBool>());
}

TEST_CASE("key sensors: invalid keys are ignored", "[runtime][x3d][keys]") {
  RunningWorld w(x3dWorld("DEF K KeySensor {}\n"));
  w.model->keyPress(Key::of(U'\0'), 0.0);
  w.model->keyPress(Key::of(static_cast<char32_t>(0xD800)), 0.0);
  w.model->keyPress(Key::of(static_cast<char32_t>(0x110000)), 0.0);
  w.model->keyPress(Key::of(static_cast<ActionKey>(21)), 0.0);
  w.model->keyPress(Key{U'a', ActionKey::f1}, 0.0);
  CHECK(w.take() == Events{});
  CHECK_FALSE(Key::of(ActionKey::none).valid());
  CHECK(Key::of(ActionKey::alt).valid());
  CHECK(Key::of(static_cast<char32_t>(0x10FFFF)).valid());
}

TEST_CASE("key sensors: keys named as window scripts name them", "[runtime][keys]") {
  using gs::runtime::keyNamed;
  CHECK(keyNamed("a") == Key::of(U'a'));
  CHECK(keyNamed("\xC3\xA9") == Key::of(U'\u00E9'));
  CHECK(keyNamed("F1") == Key::of(ActionKey::f1));
  CHECK(keyNamed("f12") == Key::of(ActionKey::f12));
  CHECK(keyNamed("Home") == Key::of(ActionKey::home));
  CHECK(keyNamed("PgDn") == Key::of(ActionKey::pageDown));
  CHECK(keyNamed("RIGHT") == Key::of(ActionKey::right));
  CHECK(keyNamed("ctrl") == Key::of(ActionKey::control));
  CHECK(keyNamed("Enter") == Key::of(gs::runtime::kKeyEnter));
  CHECK(keyNamed("Backspace") == Key::of(gs::runtime::kKeyBackspace));
  CHECK(keyNamed("Space") == Key::of(U' '));
  CHECK(keyNamed("U+20AC") == Key::of(U'\u20AC'));
  CHECK_FALSE(keyNamed(""));
  CHECK_FALSE(keyNamed("F13"));
  CHECK_FALSE(keyNamed("F0"));
  CHECK_FALSE(keyNamed("ab"));
  CHECK_FALSE(keyNamed("U+D800"));
  CHECK_FALSE(keyNamed("U+110000"));
  CHECK_FALSE(keyNamed("\xC3"));      // truncated UTF-8
  CHECK_FALSE(keyNamed("\xC0\xAF"));  // overlong
  CHECK(gs::runtime::utf8Of(U'\U0001F600') == "\xF0\x9F\x98\x80");
  CHECK(gs::runtime::utf8Of(0).empty());
}

TEST_CASE("key sensors: castle's key_sensor.x3dv switches on F-keys and lights modifiers",
          "[runtime][x3d][keys][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/sensors_key")) return;
  const auto path = gs::test::corpusDir() / "x3d/castle/sensors_key/key_sensor.x3dv";
  RunningWorld w(gs::test::WorldText{gs::test::readBytes(path), path.string()});
  CHECK(w.model->diagnostics().items.empty());
  CHECK(w.model->wantsKeys());
  const auto choice = [&](const char* name) {
    return w.node(name).field("whichChoice")->get<FieldType::SFInt32>();
  };
  CHECK(choice("SPressed") == -1);
  w.model->keyPress(Key::of(ActionKey::f3), 1.0);
  CHECK(choice("SPressed") == 3);
  CHECK(choice("SReleased") == -1);
  w.model->keyRelease(Key::of(ActionKey::f3), 1.2);
  CHECK(choice("SReleased") == 3);
  w.model->keyPress(Key::of(ActionKey::pageDown), 2.0);
  CHECK(choice("SPressed") == 16);  // "PgDown"
  w.model->keyPress(Key::of(ActionKey::alt), 2.0);
  CHECK(w.node("LightAlt").field("on")->get<FieldType::SFBool>());
  CHECK_FALSE(w.node("LightShift").field("on")->get<FieldType::SFBool>());
  w.model->keyRelease(Key::of(ActionKey::alt), 2.5);
  CHECK_FALSE(w.node("LightAlt").field("on")->get<FieldType::SFBool>());
}
