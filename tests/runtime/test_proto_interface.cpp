// PROTO instances keep their declared interface (ISO/IEC 14772-1 clause 4.8.3): a
// Script's SFNode of an instance shows the interface, not the body node's fields;
// writing a member reaches every IS-connected body member; Browser.addRoute addresses
// interface members; an exposedField IS works both ways.
#include "runtime/script_ecmascript.hpp"
#include "runtime_fixture.hpp"
#include "vrml/proto.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

const char* kLampWorld = R"(
PROTO Lamp [ exposedField SFFloat level 0.5 field SFColor tint 1 0 0 ] {
  Group { children [ DEF L PointLight { intensity IS level color IS tint } ] }
}
DEF P Lamp { level 0.25 }
DEF SI ScalarInterpolator { key [ 0 1 ] keyValue [ 0 1 ] }
DEF S Script {
  field SFNode lamp USE P
  field SFNode si USE SI
  eventIn SFBool go
  eventIn SFBool wire
  eventIn SFFloat levelNow
  eventOut SFFloat seen
  eventOut SFBool bodyHidden
  eventOut SFFloat tintGreen
  eventOut SFFloat echo
  eventOut SFBool wired
  directOutput TRUE
  url "javascript:
    function initialize() {
      seen = lamp.level;
      bodyHidden = (lamp.children === undefined);
      tintGreen = lamp.tint.g;
    }
    function go(v) { lamp.level = 0.75; }
    function wire(v) { wired = Browser.addRoute(si, 'value_changed', lamp, 'set_level'); }
    function levelNow(v) { echo = v; }
  "
}
ROUTE P.level_changed TO S.levelNow
)";

bool has(const std::vector<std::string>& events, const std::string& e) {
  return std::find(events.begin(), events.end(), e) != events.end();
}

runtime::ExecutionOptions withScripts() {
  runtime::ExecutionOptions o;
  o.scripts = runtime::ecmascriptFactory();
  return o;
}

float intensity(const vrml::Node& light) {
  return light.field("intensity")->get<FieldType::SFFloat>();
}

}  // namespace

TEST_CASE("PROTO interface: a Script's SFNode of an instance reads the declared interface",
          "[runtime][proto]") {
  RunningWorld w(kLampWorld, 0.0, withScripts());
  const std::vector<std::string> events = w.take();
  CHECK(has(events, "S.seen=0.25"));
  // The instance's node is the body's Group: its `children` is not part of the interface.
  CHECK(has(events, "S.bodyHidden=TRUE"));
  CHECK(has(events, "S.tintGreen=0"));
}

TEST_CASE("PROTO interface: writing an interface member reaches the IS-connected body member",
          "[runtime][proto]") {
  RunningWorld w(kLampWorld, 0.0, withScripts());
  w.take();
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  CHECK(intensity(w.node("L")) == 0.75f);
  // exposedField IS both ways: the body's change is the instance's level_changed.
  CHECK(has(w.take(), "S.echo=0.75"));
}

TEST_CASE("PROTO interface: Browser.addRoute to an interface member of an instance",
          "[runtime][proto]") {
  RunningWorld w(kLampWorld, 0.0, withScripts());
  w.send("S", "wire", FieldValue::make<FieldType::SFBool>(true));
  CHECK(has(w.take(), "S.wired=TRUE"));
  w.send("SI", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.4f));
  CHECK(intensity(w.node("L")) == Catch::Detail::Approx(0.4f));
  CHECK(w.model->diagnostics().errorCount() == 0);
}

TEST_CASE("PROTO interface: addRoute and deleteRoute resolve through the instance's IS map",
          "[runtime][proto]") {
  RunningWorld w(kLampWorld, 0.0, withScripts());
  vrml::NodePtr lamp = w.scene->rootNodes[0];
  vrml::NodePtr si = w.scene->rootNodes[1];
  REQUIRE(lamp->protoName() == "Lamp");
  // The body node (a Group) has no set_level: only the interface does.
  CHECK(lamp->type().findField("set_level") < 0);
  CHECK(w.model->addRoute(si, "value_changed", lamp, "set_level"));
  w.send("SI", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(intensity(w.node("L")) == Catch::Detail::Approx(0.5f));
  CHECK(w.model->deleteRoute(si, "value_changed", lamp, "set_level"));
  w.send("SI", "set_fraction", FieldValue::make<FieldType::SFFloat>(1.0f));
  CHECK(intensity(w.node("L")) == Catch::Detail::Approx(0.5f));
  // A mismatched type is refused with a diagnostic naming the PROTO.
  CHECK_FALSE(w.model->addRoute(si, "value_changed", lamp, "tint"));
}
