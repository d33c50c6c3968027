// The X3D Event Utilities component (X3D 4.0 clause 30) in the execution model.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;
using Events = std::vector<std::string>;

namespace {

FieldValue sfBool(bool b) {
  return FieldValue::make<FieldType::SFBool>(b);
}
FieldValue sfFloat(float f) {
  return FieldValue::make<FieldType::SFFloat>(f);
}

}  // namespace

TEST_CASE("event utilities: BooleanFilter splits and negates", "[runtime][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF F BooleanFilter {}
DEF T BooleanToggle {}
ROUTE F.inputNegate TO T.set_toggle
)"));
  w.send("F", "set_boolean", sfBool(true));
  CHECK(w.take() == Events{"F.inputTrue=TRUE", "F.inputNegate=FALSE", "T.toggle_changed=FALSE"});
  w.send("F", "set_boolean", sfBool(false));
  CHECK(w.take() == Events{"F.inputFalse=FALSE", "F.inputNegate=TRUE", "T.toggle_changed=TRUE"});
  CHECK(w.node("T").field("toggle")->get<FieldType::SFBool>());
}

TEST_CASE("event utilities: BooleanToggle negates toggle on TRUE only", "[runtime][x3d]") {
  RunningWorld w(x3dWorld("DEF T BooleanToggle { toggle TRUE }\n"));
  w.send("T", "set_boolean", sfBool(true));
  CHECK(w.take() == Events{"T.toggle_changed=FALSE"});
  CHECK_FALSE(w.node("T").field("toggle")->get<FieldType::SFBool>());
  w.send("T", "set_boolean", sfBool(false));
  CHECK(w.take() == Events{});
  w.send("T", "set_boolean", sfBool(true));
  CHECK(w.take() == Events{"T.toggle_changed=TRUE"});
  CHECK(w.node("T").field("toggle")->get<FieldType::SFBool>());
}

TEST_CASE("event utilities: BooleanTrigger sends triggerTrue TRUE", "[runtime][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF B BooleanTrigger {}
DEF L PointLight { on FALSE }
ROUTE B.triggerTrue TO L.on
)"));
  w.send("B", "set_triggerTime", FieldValue::make<FieldType::SFTime>(3.0));
  CHECK(w.take() == Events{"B.triggerTrue=TRUE", "L.on_changed=TRUE"});
  CHECK(w.node("L").field("on")->get<FieldType::SFBool>());
}

TEST_CASE("event utilities: IntegerTrigger sends integerKey on TRUE", "[runtime][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF I IntegerTrigger { integerKey 2 }
DEF S Switch { whichChoice -1 }
ROUTE I.triggerValue TO S.whichChoice
)"));
  w.send("I", "set_boolean", sfBool(false));
  CHECK(w.take() == Events{});
  w.send("I", "set_boolean", sfBool(true));
  CHECK(w.take() == Events{"I.triggerValue=2", "S.whichChoice_changed=2"});
  CHECK(w.node("S").field("whichChoice")->get<FieldType::SFInt32>() == 2);
  w.send("I", "integerKey", FieldValue::make<FieldType::SFInt32>(5));
  w.take();
  w.send("I", "set_boolean", sfBool(true));
  CHECK(w.node("S").field("whichChoice")->get<FieldType::SFInt32>() == 5);
}

TEST_CASE("event utilities: TimeTrigger sends the current time", "[runtime][x3d]") {
  RunningWorld w(x3dWorld("DEF T TimeTrigger {}\n"), 10.0);
  w.model->advanceTo(12.5);
  w.take();
  w.send("T", "set_boolean", sfBool(true));
  CHECK(w.take() == Events{"T.triggerTime=12.500"});
  CHECK(w.node("T").field("triggerTime")->get<FieldType::SFTime>() == Approx(12.5));
}

TEST_CASE("event utilities: BooleanSequencer steps by key", "[runtime][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF B BooleanSequencer { key [0.2 0.5 0.8] keyValue [TRUE FALSE TRUE] }
DEF L PointLight {}
ROUTE B.value_changed TO L.on
)"));
  w.send("B", "set_fraction", sfFloat(0.0f));  // below the first key: the first value
  CHECK(w.take() == Events{"B.value_changed=TRUE", "L.on_changed=TRUE"});
  w.send("B", "set_fraction", sfFloat(0.6f));  // no interpolation: the value of key 0.5
  CHECK(w.take() == Events{"B.value_changed=FALSE", "L.on_changed=FALSE"});
  CHECK_FALSE(w.node("L").field("on")->get<FieldType::SFBool>());
  w.send("B", "set_fraction", sfFloat(0.8f));  // at a key: that key's value
  CHECK(w.take() == Events{"B.value_changed=TRUE", "L.on_changed=TRUE"});
  w.send("B", "set_fraction", sfFloat(0.49f));
  CHECK(w.take() == Events{"B.value_changed=TRUE", "L.on_changed=TRUE"});
}

TEST_CASE("event utilities: IntegerSequencer steps, next and previous cycle", "[runtime][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF I IntegerSequencer { key [0 0.5 1] keyValue [4 5 6] }
DEF S Switch {}
ROUTE I.value_changed TO S.whichChoice
)"));
  const auto whichChoice = [&] {
    return w.node("S").field("whichChoice")->get<FieldType::SFInt32>();
  };
  w.send("I", "set_fraction", sfFloat(0.75f));
  CHECK(w.take() == Events{"I.value_changed=5", "S.whichChoice_changed=5"});
  w.send("I", "next", sfBool(true));
  CHECK(w.take() == Events{"I.value_changed=6", "S.whichChoice_changed=6"});
  w.send("I", "next", sfBool(true));  // wraps to the first
  CHECK(whichChoice() == 4);
  w.send("I", "previous", sfBool(true));  // wraps to the last
  CHECK(whichChoice() == 6);
  w.send("I", "previous", sfBool(true));
  CHECK(whichChoice() == 5);
  w.take();
  w.send("I", "next", sfBool(false));  // FALSE does nothing
  CHECK(w.take() == Events{});
  w.send("I", "set_fraction", sfFloat(2.0f));  // past the last key: the last value
  CHECK(whichChoice() == 6);
}

TEST_CASE("event utilities: a sequencer with mismatched keyValue reports once", "[runtime][x3d]") {
  RunningWorld w(x3dWorld("DEF I IntegerSequencer { key [0 0.5 1] keyValue [4 5] }\n"));
  w.send("I", "set_fraction", sfFloat(0.5f));
  w.send("I", "set_fraction", sfFloat(0.7f));
  CHECK(w.take() == Events{});
  std::size_t errors = 0;
  for (const auto& d : w.model->diagnostics().items)
    if (d.message.find("keyValue has 2 values for 3 keys") != std::string::npos) ++errors;
  CHECK(errors == 1);
}

TEST_CASE("event utilities: castle sequencer worlds drive PointLight.on and Switch.whichChoice",
          "[runtime][x3d][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/event_utilities")) return;
  const auto dir = gs::test::corpusDir() / "x3d/castle/event_utilities";
  {
    const auto path = dir / "sequencer_bool_test.x3dv";
    RunningWorld w(gs::test::WorldText{gs::test::readBytes(path), path.string()});
    // Timer: cycleInterval 4, looping from 0. At 1.4 s the fraction is 0.35: the last
    // key <= 0.35 is 0.3, whose value is FALSE (PointLight.on defaults to TRUE).
    w.model->advanceTo(1.4);
    CHECK_FALSE(w.node("L").field("on")->get<FieldType::SFBool>());
    const Events e = w.take();
    CHECK(std::find(e.begin(), e.end(), "BS.value_changed=FALSE") != e.end());
    // At 2.0 s (fraction 0.5) the key is 0.4333: TRUE.
    w.model->advanceTo(2.0);
    CHECK(w.node("L").field("on")->get<FieldType::SFBool>());
    CHECK(w.take() == Events{"Timer.fraction_changed=0.5", "Timer.time=2.000",
                             "BS.value_changed=TRUE", "L.on_changed=TRUE"});
  }
  {
    const auto path = dir / "sequencer_int_test.x3dv";
    RunningWorld w(gs::test::WorldText{gs::test::readBytes(path), path.string()});
    // At 1.0 s the fraction is 0.25: key 0.2, value 6. At 2.2 s (0.55): key 0.5, value 3.
    w.model->advanceTo(1.0);
    CHECK(w.node("S").field("whichChoice")->get<FieldType::SFInt32>() == 6);
    w.model->advanceTo(2.2);
    CHECK(w.node("S").field("whichChoice")->get<FieldType::SFInt32>() == 3);
  }
}
