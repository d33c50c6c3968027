// The ECMAScript Script host (annex C): eventIns called with (value, timestamp), one
// event per assigned eventOut when the function returns, the SF/MF classes with values
// worked out by hand, SFNode field access, the Browser object, url entries.
#include "script_test_support.hpp"

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace gs;
using namespace gs::test;
using Catch::Detail::Approx;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

FieldValue sfFloat(float f) {
  return FieldValue::make<FieldType::SFFloat>(f);
}

std::vector<float> mfFloat(const FieldValue& v) {
  return v.get<FieldType::MFFloat>();
}

}  // namespace

TEST_CASE("Script: eventIn gets (value, timestamp); one event per eventOut at return", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    eventIn SFFloat set_f
    eventOut SFFloat out
    eventOut SFTime stamp
    eventOut SFBool never)",
                                              R"(
    function set_f(v, ts) {
      out = v * 2;
      out = v * 3;   // assigned twice: one event, the last value
      stamp = ts;
    })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(1.0);
  CHECK(ctx.emitted.empty());
  w.instance->eventIn(w.field("set_f"), sfFloat(2.0f), 10.5);
  REQUIRE(ctx.emitted.size() == 2);
  auto out = ctx.emittedFor(*w.script, "out");
  REQUIRE(out.size() == 1);
  CHECK(out[0].get<FieldType::SFFloat>() == 6.0f);
  auto stamp = ctx.emittedFor(*w.script, "stamp");
  REQUIRE(stamp.size() == 1);
  CHECK(stamp[0].get<FieldType::SFTime>() == 10.5);
  CHECK(ctx.emittedFor(*w.script, "never").empty());
  // The value stays: the next call that does not assign sends nothing.
  ctx.emitted.clear();
  w.instance->eventIn(w.field("set_f"), sfFloat(1.0f), 11.0);
  CHECK(ctx.emittedFor(*w.script, "out").size() == 1);
  CHECK(ctx.diagnostics.empty());
  CHECK_FALSE(w.instance->stopped());
}

TEST_CASE("Script: initialize, eventsProcessed and shutdown", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    field SFInt32 count 10
    eventOut SFInt32 calls
    eventOut SFString last)",
                                              R"(
    function initialize() { count = count + 1; calls = count; last = 'initialize'; }
    function eventsProcessed() { count += 1; calls = count; last = 'eventsProcessed'; }
    function shutdown() { count += 1; calls = count; last = 'shutdown'; })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  w.instance->eventsProcessed(1.0);
  w.instance->eventsProcessed(2.0);
  w.instance->shutdown(3.0);
  auto calls = ctx.emittedFor(*w.script, "calls");
  REQUIRE(calls.size() == 4);
  CHECK(calls[0].get<FieldType::SFInt32>() == 11);
  CHECK(calls[3].get<FieldType::SFInt32>() == 14);
  auto last = ctx.emittedFor(*w.script, "last");
  REQUIRE(last.size() == 4);
  CHECK(last[0].get<FieldType::SFString>() == "initialize");
  CHECK(last[1].get<FieldType::SFString>() == "eventsProcessed");
  CHECK(last[3].get<FieldType::SFString>() == "shutdown");
  CHECK(ctx.diagnostics.empty());
}

TEST_CASE("Script: one element or one component changed in place sends the whole value",
          "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    eventIn SFFloat set_f
    eventIn SFFloat read_only
    eventIn MFFloat set_m
    eventOut MFFloat m
    eventOut SFVec3f pos
    eventOut MFVec3f path
    eventOut SFColor hsv)",
                                              R"(
    function initialize() { m = new MFFloat(1, 2, 3); pos = new SFVec3f(1, 2, 3);
                            path = new MFVec3f(new SFVec3f(0, 0, 0), new SFVec3f(1, 1, 1)); }
    function set_f(v, t) { m[1] = v; pos.x = v; path[1].y = v; pos[2] = 9; hsv.setHSV(0, 1, 1); }
    function read_only(v, t) { var a = m[0] + pos.x + path.length; }
    function set_m(v, t) { v[0] = 42; m = v; m.length = 4; })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  REQUIRE(ctx.emitted.size() == 3);
  ctx.emitted.clear();

  w.instance->eventIn(w.field("set_f"), sfFloat(7.0f), 1.0);
  auto m = ctx.emittedFor(*w.script, "m");
  REQUIRE(m.size() == 1);
  CHECK(mfFloat(m[0]) == std::vector<float>{1, 7, 3});
  auto pos = ctx.emittedFor(*w.script, "pos");
  REQUIRE(pos.size() == 1);
  CHECK(pos[0].get<FieldType::SFVec3f>() == glm::vec3(7, 2, 9));
  auto path = ctx.emittedFor(*w.script, "path");
  REQUIRE(path.size() == 1);
  CHECK(path[0].get<FieldType::MFVec3f>() ==
        std::vector<glm::vec3>{glm::vec3(0, 0, 0), glm::vec3(1, 7, 1)});
  auto hsv = ctx.emittedFor(*w.script, "hsv");
  REQUIRE(hsv.size() == 1);
  CHECK(hsv[0].get<FieldType::SFColor>() == glm::vec3(1, 0, 0));

  // Reading without changing sends nothing.
  ctx.emitted.clear();
  w.instance->eventIn(w.field("read_only"), sfFloat(0.0f), 2.0);
  CHECK(ctx.emitted.empty());

  // An MF eventIn is a fresh array; growing an MF fills with the type's default.
  w.instance->eventIn(w.field("set_m"),
                      FieldValue::make<FieldType::MFFloat>(std::vector<float>{5, 6}), 3.0);
  m = ctx.emittedFor(*w.script, "m");
  REQUIRE(m.size() == 1);
  CHECK(mfFloat(m[0]) == std::vector<float>{42, 6, 0, 0});
  CHECK(ctx.diagnostics.empty());
}

TEST_CASE("Script: vrmlscript conveniences: numbers for SFTime/SFFloat, TRUE, single values",
          "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    eventOut SFTime t
    eventOut SFFloat f
    eventOut SFBool b
    eventOut MFString s
    eventOut SFString str
    eventOut SFInt32 i)",
                                              R"(
    function initialize() { t = 5; f = '2.5'; b = TRUE; s = 'one'; str = new String('SPHERE');
                            i = 3.9; })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  CHECK(ctx.emittedFor(*w.script, "t").at(0).get<FieldType::SFTime>() == 5.0);
  CHECK(ctx.emittedFor(*w.script, "f").at(0).get<FieldType::SFFloat>() == 2.5f);
  CHECK(ctx.emittedFor(*w.script, "b").at(0).get<FieldType::SFBool>() == true);
  CHECK(ctx.emittedFor(*w.script, "s").at(0).get<FieldType::MFString>() ==
        std::vector<std::string>{"one"});
  CHECK(ctx.emittedFor(*w.script, "str").at(0).get<FieldType::SFString>() == "SPHERE");
  CHECK(ctx.emittedFor(*w.script, "i").at(0).get<FieldType::SFInt32>() == 3);
}

TEST_CASE("Script: SFVec3f and SFVec2f methods", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld("eventOut MFFloat r\neventOut SFVec3f v",
                                              R"(
    function initialize() {
      var a = new SFVec3f(1, 2, 3), b = new SFVec3f(4, 5, 6);
      var s = a.add(b), d = b.subtract(a), m = a.multiply(2), q = b.divide(2), c = a.cross(b);
      var n = new SFVec3f(3, 0, 4).normalize(), g = a.negate();
      var p = new SFVec2f(3, 4);
      r = new MFFloat(s.x, s.y, s.z, d.x, d.y, d.z, m.z, q.x, a.dot(b), c.x, c.y, c.z,
                      new SFVec3f(2, 3, 6).length(), n.x, n.z, g.y, a[0], a[2],
                      p.length(), p.normalize().y, p.dot(new SFVec2f(1, 1)), p.add(p).x);
      v = c;
    })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  auto r = ctx.emittedFor(*w.script, "r");
  REQUIRE(r.size() == 1);
  // add (5 7 9), subtract (3 3 3), multiply z 6, divide x 2, dot 32, cross (-3 6 -3),
  // |(2 3 6)| = 7, normalize (3 0 4) = (.6 0 .8), negate y -2, index 0 -> 1, 2 -> 3,
  // |(3 4)| = 5, normalize y .8, dot (1 1) = 7, add x 6.
  std::vector<float> expect{5,  7, 9,    3,    3,  3, 6, 2, 32,   -3, 6,
                            -3, 7, 0.6f, 0.8f, -2, 1, 3, 5, 0.8f, 7,  6};
  std::vector<float> got = mfFloat(r[0]);
  REQUIRE(got.size() == expect.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    INFO("value " << i);
    CHECK(got[i] == Approx(expect[i]).margin(1e-6));
  }
  CHECK(ctx.emittedFor(*w.script, "v").at(0).get<FieldType::SFVec3f>() == glm::vec3(-3, 6, -3));
}

TEST_CASE("Script: SFRotation methods", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    eventOut SFVec3f turned
    eventOut SFVec3f composed
    eventOut SFRotation inv
    eventOut SFRotation half
    eventOut SFRotation between
    eventOut SFRotation axis
    eventOut SFVec3f gotAxis)",
                                              R"(
    function initialize() {
      var z90 = new SFRotation(0, 0, 1, Math.PI / 2), x90 = new SFRotation(1, 0, 0, Math.PI / 2);
      turned = z90.multVec(new SFVec3f(1, 0, 0));
      // multiply: x90 first, then z90: (0 1 0) -x90-> (0 0 1) -z90-> (0 0 1)
      //                                (0 0 1) -x90-> (0 -1 0) -z90-> (1 0 0)
      composed = z90.multiply(x90).multVec(new SFVec3f(0, 0, 1));
      inv = z90.inverse();
      half = new SFRotation(0, 0, 1, 0).slerp(z90, 0.5);
      between = new SFRotation(new SFVec3f(1, 0, 0), new SFVec3f(0, 2, 0));
      axis = new SFRotation(new SFVec3f(0, 1, 0), 0.25);
      var r = new SFRotation(1, 0, 0, 1); r.setAxis(new SFVec3f(0, 0, 1));
      gotAxis = r.getAxis();
    })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  auto vec = [&](const char* name) {
    return ctx.emittedFor(*w.script, name).at(0).get<FieldType::SFVec3f>();
  };
  auto rot = [&](const char* name) {
    return ctx.emittedFor(*w.script, name).at(0).get<FieldType::SFRotation>();
  };
  const float pi = glm::pi<float>();
  glm::vec3 t = vec("turned");
  CHECK(t.x == Approx(0).margin(1e-6));
  CHECK(t.y == Approx(1));
  CHECK(t.z == Approx(0).margin(1e-6));
  glm::vec3 c = vec("composed");
  CHECK(c.x == Approx(1));
  CHECK(c.y == Approx(0).margin(1e-6));
  CHECK(c.z == Approx(0).margin(1e-6));
  CHECK(rot("inv") == vrml::Rotation(0, 0, 1, -pi / 2));
  vrml::Rotation h = rot("half");
  CHECK(h.z == Approx(1));
  CHECK(h.w == Approx(pi / 4));
  vrml::Rotation b = rot("between");
  CHECK(b.z == Approx(1));
  CHECK(b.w == Approx(pi / 2));
  CHECK(rot("axis") == vrml::Rotation(0, 1, 0, 0.25f));
  CHECK(vec("gotAxis") == glm::vec3(0, 0, 1));
}

TEST_CASE("Script: SFColor HSV, SFImage, MF constructors and toString", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld(R"(
    eventOut MFFloat hsv
    eventOut SFColor rgb
    eventOut SFImage img
    eventOut MFString text
    eventOut MFRotation rots
    eventOut MFInt32 ints)",
                                              R"(
    function initialize() {
      var h = new SFColor(0, 0.5, 1).getHSV();    // 210 deg, s 1, v 1
      hsv = new MFFloat(h[0], h[1], h[2]);
      var c = new SFColor(0, 0, 0); c.setHSV(120, 0.5, 0.8); rgb = c;  // (.4 .8 .4)
      img = new SFImage(2, 1, 1, new MFInt32(255, 128));
      text = new MFString(new SFVec3f(1, 2, 3).toString(), new MFFloat(1, 2).toString(),
                          String(new MFInt32(1.7, -2.2).length), Browser.getName());
      rots = new MFRotation(new SFRotation(0, 1, 0, 3.14));
      ints = new MFInt32(1.7, -2.2);
    })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  std::vector<float> h = mfFloat(ctx.emittedFor(*w.script, "hsv").at(0));
  REQUIRE(h.size() == 3);
  CHECK(h[0] == Approx(210));
  CHECK(h[1] == Approx(1));
  CHECK(h[2] == Approx(1));
  glm::vec3 rgb = ctx.emittedFor(*w.script, "rgb").at(0).get<FieldType::SFColor>();
  CHECK(rgb.r == Approx(0.4));
  CHECK(rgb.g == Approx(0.8));
  CHECK(rgb.b == Approx(0.4));
  vrml::SFImage img = ctx.emittedFor(*w.script, "img").at(0).get<FieldType::SFImage>();
  CHECK(img.width == 2);
  CHECK(img.height == 1);
  CHECK(img.components == 1);
  CHECK(img.pixels == std::vector<std::uint32_t>{255, 128});
  CHECK(ctx.emittedFor(*w.script, "text").at(0).get<FieldType::MFString>() ==
        std::vector<std::string>{"1 2 3", "[1, 2]", "2", "GhostSpace"});
  CHECK(ctx.emittedFor(*w.script, "rots").at(0).get<FieldType::MFRotation>() ==
        std::vector<vrml::Rotation>{vrml::Rotation(0, 1, 0, 3.14f)});
  CHECK(ctx.emittedFor(*w.script, "ints").at(0).get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{1, -2});
}

TEST_CASE("Script: VrmlMatrix setTransform, multVecMatrix, inverse, getTransform", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld("eventOut MFVec3f r\neventOut SFRotation rot",
                                              R"(
    function initialize() {
      var m = new VrmlMatrix();
      m.setTransform(new SFVec3f(1, 2, 3), new SFRotation(0, 0, 1, Math.PI / 2),
                     new SFVec3f(2, 2, 2));
      // (1 0 0): scaled (2 0 0), turned (0 2 0), moved (1 4 3)
      var p = m.multVecMatrix(new SFVec3f(1, 0, 0));
      var back = m.inverse().multVecMatrix(p);
      var t = new SFVec3f(), s = new SFVec3f(), q = new SFRotation();
      m.getTransform(t, q, s);
      r = new MFVec3f(p, back, t, s);
      rot = q;
    })"));
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  auto r = ctx.emittedFor(*w.script, "r").at(0).get<FieldType::MFVec3f>();
  REQUIRE(r.size() == 4);
  auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-5f; };
  CHECK(near(r[0], {1, 4, 3}));
  CHECK(near(r[1], {1, 0, 0}));
  CHECK(near(r[2], {1, 2, 3}));
  CHECK(near(r[3], {2, 2, 2}));
  vrml::Rotation q = ctx.emittedFor(*w.script, "rot").at(0).get<FieldType::SFRotation>();
  CHECK(q.z == Approx(1));
  CHECK(q.w == Approx(glm::pi<float>() / 2));
}

TEST_CASE("Script: SFNode fields read and written, new SFNode from VRML text", "[script]") {
  FakeScriptContext ctx;
  std::string world = R"(#VRML V2.0 utf8
DEF T Transform { translation 1 2 3 children [ Shape {} ] }
DEF S Script {
  field SFNode target USE T
  eventIn SFFloat go
  eventOut SFVec3f seen
  eventOut SFNode made
  eventOut SFInt32 kids
  eventOut SFBool same
  directOutput TRUE
  url "javascript:
    function go(v, t) {
      seen = target.translation;
      kids = target.children.length;
      target.set_translation = new SFVec3f(v, 0, 0);
      target.rotation = new SFRotation(0, 1, 0, v);
      made = new SFNode('Box { size 1 2 3 }');
      same = target.children[0] === target.children[0];
    }"
}
)";
  ScriptWorld w = loadScript(ctx, world);
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->eventIn(w.field("go"), sfFloat(4.0f), 1.0);
  CHECK(ctx.emittedFor(*w.script, "seen").at(0).get<FieldType::SFVec3f>() == glm::vec3(1, 2, 3));
  CHECK(ctx.emittedFor(*w.script, "kids").at(0).get<FieldType::SFInt32>() == 1);
  CHECK(ctx.emittedFor(*w.script, "same").at(0).get<FieldType::SFBool>());
  REQUIRE(ctx.sent.size() == 2);
  const vrml::Node* t = w.scene.rootNodes[0].get();
  CHECK(ctx.sent[0].node == t);
  CHECK(ctx.sent[0].field == t->type().findExact("translation"));
  CHECK(ctx.sent[0].value.get<FieldType::SFVec3f>() == glm::vec3(4, 0, 0));
  CHECK(ctx.sent[1].field == t->type().findExact("rotation"));
  vrml::NodePtr made = ctx.emittedFor(*w.script, "made").at(0).get<FieldType::SFNode>();
  REQUIRE(made);
  CHECK(made->typeName() == "Box");
  CHECK(made->get<FieldType::SFVec3f>("size", glm::vec3(0)) == glm::vec3(1, 2, 3));
  CHECK(ctx.diagnostics.empty());
}

TEST_CASE("Script: writing a field that is not an eventIn is an error with its line", "[script]") {
  FakeScriptContext ctx;
  std::string world = R"(#VRML V2.0 utf8
DEF T TimeSensor {}
DEF S Script {
  field SFNode target USE T
  eventIn SFFloat go
  url "javascript:
    function go(v, t) {
      target.fraction_changed = 0.5;
    }"
}
)";
  ScriptWorld w = loadScript(ctx, world, {}, "worlds/bad.wrl");
  REQUIRE(w.instance);
  w.instance->eventIn(w.field("go"), sfFloat(1.0f), 1.0);
  REQUIRE(ctx.diagnostics.size() == 1);
  const vrml::Diagnostic& d = ctx.diagnostics[0];
  CHECK(d.severity == vrml::Severity::error);
  CHECK(d.location.file == "worlds/bad.wrl");
  CHECK(d.location.line == 3);
  CHECK(d.message ==
        "Script 'S': TypeError: fraction_changed of TimeSensor is eventOut: it cannot be "
        "written (javascript: line 3, in eventIn 'go')");
  CHECK(d.format() ==
        "worlds/bad.wrl:3:7: error: Script 'S': TypeError: fraction_changed of TimeSensor is "
        "eventOut: it cannot be written (javascript: line 3, in eventIn 'go')");
  CHECK(ctx.sent.empty());
  CHECK_FALSE(w.instance->stopped());
}

TEST_CASE("Script: Browser object", "[script]") {
  FakeScriptContext ctx;
  ctx.time = 1234.5;
  ctx.fps = 60;
  std::string world = R"(#VRML V2.0 utf8
DEF A TimeSensor {}
DEF B Transform {}
DEF S Script {
  field SFNode a USE A
  field SFNode b USE B
  eventOut MFString info
  eventOut MFNode nodes
  url "javascript:
    function initialize() {
      info = new MFString(Browser.getName(), Browser.getVersion(),
                          String(Browser.getCurrentTime()), String(Browser.getCurrentFrameRate()),
                          Browser.getWorldURL());
      nodes = Browser.createVrmlFromString('Group {} Box {}');
      Browser.addRoute(a, 'fraction_changed', b, 'set_scale');
      Browser.deleteRoute(a, 'fraction_changed', b, 'set_scale');
      Browser.loadURL(new MFString('next.wrl'), new MFString('target=_blank'));
      Browser.setDescription('hello');
      Browser.print('one', 2);
      print('three');
      Browser.replaceWorld(nodes);
    }"
}
)";
  ScriptWorld w = loadScript(ctx, world);
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->initialize(0.0);
  auto info = ctx.emittedFor(*w.script, "info").at(0).get<FieldType::MFString>();
  REQUIRE(info.size() == 5);
  CHECK(info[0] == "GhostSpace");
  CHECK_FALSE(info[1].empty());
  CHECK(info[2] == "1234.5");
  CHECK(info[3] == "60");
  CHECK(info[4] == "file:///worlds/test.wrl");
  auto nodes = ctx.emittedFor(*w.script, "nodes").at(0).get<FieldType::MFNode>();
  REQUIRE(nodes.size() == 2);
  CHECK(nodes[1]->typeName() == "Box");
  CHECK(ctx.routes == std::vector<std::string>{"add A.fraction_changed B.set_scale",
                                               "delete A.fraction_changed B.set_scale"});
  CHECK(ctx.loaded == std::vector<std::vector<std::string>>{{"next.wrl", "target=_blank"}});
  CHECK(ctx.description == "hello");
  CHECK(ctx.printed == std::vector<std::string>{"one 2", "three"});
  CHECK(ctx.replacedWith == nodes);
  CHECK(ctx.diagnostics.empty());
}

TEST_CASE("Script: url entries: inline schemes, files through fetchText, none runnable",
          "[script]") {
  SECTION("the first entry that reads and compiles runs") {
    FakeScriptContext ctx;
    ctx.files["good.js"] = "function initialize() { out = 'from file'; }";
    ctx.files["broken.js"] = "function initialize( {";
    std::string world = R"(#VRML V2.0 utf8
DEF S Script {
  eventOut SFString out
  url [ "missing.js" "Hello.class" "broken.js" "good.js" "javascript: out = 'inline';" ]
}
)";
    ScriptWorld w = loadScript(ctx, world);
    REQUIRE(w.instance);
    w.instance->initialize(0.0);
    CHECK(ctx.emittedFor(*w.script, "out").at(0).get<FieldType::SFString>() == "from file");
    REQUIRE(ctx.diagnostics.size() == 3);
    CHECK_THAT(ctx.diagnostics[0].message, Catch::Contains("cannot read 'missing.js'"));
    CHECK_THAT(ctx.diagnostics[1].message, Catch::Contains("Java"));
    CHECK_THAT(ctx.diagnostics[2].message,
               Catch::Contains("SyntaxError") && Catch::Contains("broken.js"));
  }
  SECTION("ecmascript: and vrmlscript: in any case") {
    for (const char* scheme : {"ecmascript:", "VRMLScript:", "  javascript:"}) {
      FakeScriptContext ctx;
      std::string world =
          std::string("#VRML V2.0 utf8\nDEF S Script { eventOut SFInt32 out url \"") + scheme +
          " function initialize() { out = 7; }\" }\n";
      ScriptWorld w = loadScript(ctx, world);
      REQUIRE(w.instance);
      w.instance->initialize(0.0);
      CHECK(ctx.emittedFor(*w.script, "out").at(0).get<FieldType::SFInt32>() == 7);
    }
  }
  SECTION("no entry runs: no instance, a diagnostic") {
    FakeScriptContext ctx;
    ScriptWorld w = loadScript(
        ctx, "#VRML V2.0 utf8\nDEF S Script { url [ \"nothing.js\" \"javascript: {\" ] }\n");
    CHECK_FALSE(w.instance);
    REQUIRE_FALSE(ctx.diagnostics.empty());
    CHECK_THAT(ctx.diagnostics.back().message, Catch::Contains("no url entry"));
    CHECK(ctx.diagnostics.back().location.line == 2);
  }
}

TEST_CASE("Script: exposedField-like use and eventIns without a function", "[script]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, scriptWorld("eventIn SFFloat nobody\neventIn SFFloat some",
                                              "function some(v) { print('some ' + v); }"));
  REQUIRE(w.instance);
  w.instance->eventIn(w.field("nobody"), sfFloat(1), 1.0);
  w.instance->eventIn(w.field("nobody"), sfFloat(1), 2.0);
  w.instance->eventIn(w.field("some"), sfFloat(1.5f), 2.0);
  REQUIRE(ctx.diagnostics.size() == 1);  // warned once
  CHECK(ctx.diagnostics[0].severity == vrml::Severity::warning);
  CHECK_THAT(ctx.diagnostics[0].message, Catch::Contains("nobody"));
  CHECK(ctx.printed == std::vector<std::string>{"some 1.5"});
  // An event of the wrong type is ignored with a warning.
  w.instance->eventIn(w.field("some"), FieldValue::make<FieldType::SFInt32>(1), 3.0);
  CHECK(ctx.printed.size() == 1);
  CHECK(ctx.diagnostics.size() == 2);
}

TEST_CASE("Script: Browser.createVrmlFromURL sends the nodes to the node's eventIn", "[script]") {
  FakeScriptContext ctx;
  ctx.files["part.wrl"] = "#VRML V2.0 utf8\nBox { size 2 2 2 }\n";
  std::string world = R"(#VRML V2.0 utf8
DEF G Group {}
DEF S Script {
  field SFNode g USE G
  url "javascript:
    function initialize() {
      Browser.createVrmlFromURL(new MFString('missing.wrl', 'part.wrl'), g, 'addChildren');
    }"
}
)";
  ScriptWorld w = loadScript(ctx, world);
  REQUIRE(w.instance);
  w.instance->initialize(0.0);
  INFO(ctx.diagnosticText());
  REQUIRE(ctx.sent.size() == 1);
  CHECK(ctx.sent[0].node == w.scene.rootNodes[0].get());
  CHECK(ctx.sent[0].field == w.scene.rootNodes[0]->type().findExact("addChildren"));
  const auto& nodes = ctx.sent[0].value.get<FieldType::MFNode>();
  REQUIRE(nodes.size() == 1);
  CHECK(nodes[0]->typeName() == "Box");
  REQUIRE(ctx.diagnostics.size() == 1);
  CHECK(ctx.diagnostics[0].severity == vrml::Severity::warning);
  CHECK_THAT(ctx.diagnostics[0].message, Catch::Contains("missing.wrl"));
}

TEST_CASE("Script: an event sent to itself during a call re-enters it safely", "[script]") {
  FakeScriptContext ctx;
  std::string world = R"(#VRML V2.0 utf8
DEF S Script {
  field SFNode self USE S
  eventIn SFFloat a
  eventIn SFFloat b
  eventOut SFFloat outA
  eventOut SFFloat outB
  url "javascript:
    function a(v, t) { self.b = v + 1; outA = v; }
    function b(v, t) { outB = v * 10; }"
}
)";
  ScriptWorld w = loadScript(ctx, world);
  REQUIRE(w.instance);
  ctx.onSend = [&](vrml::Node& node, int field, const FieldValue& v) {
    if (&node == w.script.get()) w.instance->eventIn(field, v, 1.0);
  };
  w.instance->eventIn(w.field("a"), sfFloat(1.0f), 1.0);
  INFO(ctx.diagnosticText());
  CHECK(ctx.diagnostics.empty());
  CHECK(ctx.emittedFor(*w.script, "outA").at(0).get<FieldType::SFFloat>() == 1.0f);
  CHECK(ctx.emittedFor(*w.script, "outB").at(0).get<FieldType::SFFloat>() == 20.0f);
}

TEST_CASE("Script: a Script written in an EXTERNPROTO's file reads its files beside that file",
          "[script][proto][url]") {
  // vrml::Node::urlBase (set by the parser on an EXTERNPROTO file's nodes) is the base of
  // the Script's file entries; a remote base may not name a local file.
  FakeScriptContext ctx;
  ctx.files["/lib/sub/good.js"] = "function initialize() { out = 'beside the PROTO'; }";
  ctx.files["good.js"] = "function initialize() { out = 'beside the world'; }";
  ctx.files["file:///lib/sub/good.js"] = "function initialize() { out = 'local'; }";
  vrml::Scene scene = vrml::parseVrml(
      "#VRML V2.0 utf8\nDEF S Script { eventOut SFString out url \"good.js\" }\n", "test.wrl");
  vrml::NodePtr script = findScript(scene.rootNodes);
  REQUIRE(script);
  script->urlBase = std::make_shared<const std::string>("/lib/sub/protos.wrl");
  auto instance = runtime::ecmascriptFactory()(*script, ctx, relaxedLimits());
  REQUIRE(instance);
  instance->initialize(0.0);
  CHECK(ctx.emittedFor(*script, "out").at(0).get<FieldType::SFString>() == "beside the PROTO");
  CHECK(ctx.diagnostics.empty());

  FakeScriptContext remote;
  remote.files = ctx.files;
  script->urlBase = std::make_shared<const std::string>("http://example.com/lib/protos.wrl");
  *script->field("url") =
      FieldValue::make<FieldType::MFString>(std::vector<std::string>{"file:///lib/sub/good.js"});
  CHECK_FALSE(runtime::ecmascriptFactory()(*script, remote, relaxedLimits()));
  REQUIRE_FALSE(remote.diagnostics.empty());
  CHECK_THAT(remote.diagnostics[0].message, Catch::Contains("may not reference"));
}

TEST_CASE("Script: a Script in an Inline's world reads its files beside that world",
          "[script][inline][url]") {
  // ScriptContext::sceneOf names the Inline's world the Script is in: its URL is the base
  // of the Script's file entries, and a remote one may not name a local file.
  FakeScriptContext ctx;
  ctx.files["/worlds/sub/good.js"] = "function initialize() { out = 'beside the Inline'; }";
  ctx.files["good.js"] = "function initialize() { out = 'beside the world'; }";
  ctx.files["file:///lib/good.js"] = "function initialize() { out = 'local'; }";
  auto s =
      loadInlineScript(ctx, "/worlds/main.wrl",
                       "#VRML V2.0 utf8\nDEF S Script { eventOut SFString out url \"good.js\" }\n",
                       "/worlds/sub/inner.wrl");
  REQUIRE(s->instance);
  s->instance->initialize(0.0);
  vrml::Scene& world = s->world;
  vrml::Scene& inner = s->inner;
  const vrml::NodePtr& script = s->script;
  INFO(ctx.diagnosticText());
  CHECK(ctx.emittedFor(*script, "out").at(0).get<FieldType::SFString>() == "beside the Inline");

  FakeScriptContext remote;
  remote.files = ctx.files;
  inner.url = "http://example.com/w/inner.wrl";
  remote.world = &world;
  remote.own = &inner;
  *script->field("url") =
      FieldValue::make<FieldType::MFString>(std::vector<std::string>{"file:///lib/good.js"});
  CHECK_FALSE(runtime::ecmascriptFactory()(*script, remote, relaxedLimits()));
  REQUIRE_FALSE(remote.diagnostics.empty());
  CHECK_THAT(remote.diagnostics[0].message, Catch::Contains("may not reference"));
}

TEST_CASE("Script: a node's fields are live objects for a call, sent when it returns", "[script]") {
  // X_ITE's scripts build geometry in place (create3000's Texturing3D/Volume.x3d,
  // Follower/ColorDamper.x3dv): coord.point.push(...), color.length = n then
  // color[i].setHSV(...), one element changed; each field changed is one event.
  FakeScriptContext ctx;
  std::string world = R"(#VRML V2.0 utf8
DEF C Coordinate { point [ 9 9 9 ] }
DEF K Color { }
DEF T Transform { translation 1 2 3 }
DEF S Script {
  field SFNode coord USE C
  field SFNode colors USE K
  field SFNode target USE T
  eventIn SFFloat go
  eventIn SFFloat look
  eventIn SFFloat grow
  eventOut SFBool caught
  eventOut SFInt32 count
  eventOut SFBool same
  directOutput TRUE
  url "javascript:
    function go(v, t) {
      coord.point.length = 0;
      coord.point.push(new SFVec3f(1, 2, 3), new SFVec3f(4, 5, 6));
      var c = colors.color;
      c.length = 2;
      c[1].setHSV(0, 1, v);
      c[c.length] = c[1];
      target.translation = new SFVec3f(v, 0, 0);
      target.translation.y = 7;
      count = coord.point.length;
      same = coord.point === coord.point;
    }
    function look(v, t) { var n = coord.point.length + target.translation.x; }
    function grow(v, t) {
      var c = colors.color;
      c[4] = new SFColor(0, 0, 1);
      c[3].r = 0.5;
      try { coord.point.length = -1; } catch (e) { caught = e instanceof RangeError; }
    }"
}
)";
  ScriptWorld w = loadScript(ctx, world);
  REQUIRE(w.instance);
  INFO(ctx.diagnosticText());
  w.instance->eventIn(w.field("go"), sfFloat(0.5f), 1.0);
  CHECK(ctx.emittedFor(*w.script, "count").at(0).get<FieldType::SFInt32>() == 2);
  CHECK(ctx.emittedFor(*w.script, "same").at(0).get<FieldType::SFBool>());
  const vrml::Node& c = *w.scene.rootNodes[0];
  const vrml::Node& k = *w.scene.rootNodes[1];
  const vrml::Node& t = *w.scene.rootNodes[2];
  const auto sentTo = [&](const vrml::Node& n, const std::string& field) {
    std::vector<FieldValue> out;
    for (const auto& e : ctx.sent)
      if (e.node == &n && e.field == n.type().findExact(field)) out.push_back(e.value);
    return out;
  };
  const auto points = sentTo(c, "point");
  REQUIRE(points.size() == 1);
  CHECK(points[0].get<FieldType::MFVec3f>() == std::vector<glm::vec3>{{1, 2, 3}, {4, 5, 6}});
  const auto colorsSent = sentTo(k, "color");
  REQUIRE(colorsSent.size() == 1);  // grown elements are SFColor defaults, not holes
  CHECK(colorsSent[0].get<FieldType::MFColor>() ==
        std::vector<glm::vec3>{{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}});
  // The assignment is one event; the change after it, read back in the same call, another.
  const auto translations = sentTo(t, "translation");
  REQUIRE(translations.size() == 2);
  CHECK(translations[0].get<FieldType::SFVec3f>() == glm::vec3(0.5f, 0, 0));
  CHECK(translations[1].get<FieldType::SFVec3f>() == glm::vec3(0.5f, 7, 0));
  // Reading without changing sends nothing.
  ctx.sent.clear();
  w.instance->eventIn(w.field("look"), sfFloat(0.0f), 2.0);
  CHECK(ctx.sent.empty());
  // Growing by an index fills the elements before it (Duktape gives the trap a number);
  // a length that is no array length is the array's own RangeError.
  ctx.sent.clear();
  w.instance->eventIn(w.field("grow"), sfFloat(0.0f), 3.0);
  const auto grown = sentTo(k, "color");
  REQUIRE(grown.size() == 1);
  CHECK(grown[0].get<FieldType::MFColor>() ==
        std::vector<glm::vec3>{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0.5f, 0, 0}, {0, 0, 1}});
  CHECK(ctx.emittedFor(*w.script, "caught").at(0).get<FieldType::SFBool>());
  CHECK(ctx.diagnostics.empty());
}
