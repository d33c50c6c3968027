// The X3D ECMAScript binding (ISO/IEC 19777-1) beside annex C's: X3D field types as Script
// fields, eventIn arguments and constructors (SFVec3d, SFVec4f, SFColorRGBA, SFMatrix*,
// MFBool, MFDouble ...), Browser's X3D properties and createX3DFromString,
// Browser.currentScene (getNamedNode, rootNodes, createNode, addRoute), X3DConstants and
// getFieldDefinitions, url schemes in X3D worlds. Small X3D worlds run by the execution
// model; the Scripts' outputs are read back from the Script node, with values worked out
// by hand.
#include "x3d_script_support.hpp"

#include <glm/gtc/constants.hpp>

#include <cmath>

using namespace gs;
using namespace gs::test;
using Catch::Detail::Approx;
using vrml::FieldType;
using vrml::FieldValue;

TEST_CASE("X3D Script: SFVec3d, SFVec2d and SFVec4f methods keep doubles", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  initializeOnly SFVec3d a 1 2 3
  outputOnly SFVec3d sum
  outputOnly SFVec3d cross
  outputOnly SFDouble dot
  outputOnly SFDouble len
  outputOnly SFVec3d precise
  outputOnly SFVec2d half
  outputOnly SFVec4f unit
  outputOnly SFVec4d neg
  url "ecmascript:
    function initialize() {
      var b = new SFVec3d(4, 5, 6);
      sum = a.add(b);
      cross = a.cross(b);
      dot = a.dot(b);
      len = a.length();
      precise = new SFVec3d(0.1, 0, 0).add(new SFVec3d(0.2, 0, 0));
      half = new SFVec2d(3, 4).divide(2);
      unit = new SFVec4f(0, 3, 0, 4).normalize();
      var n = new SFVec4d(1, -2, 3, -4).negate();
      n[3] = n.w + 0.5;
      neg = n;
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "sum").get<FieldType::SFVec3d>() == glm::dvec3(5, 7, 9));
  CHECK(outOf(w, "cross").get<FieldType::SFVec3d>() == glm::dvec3(-3, 6, -3));
  CHECK(outOf(w, "dot").get<FieldType::SFDouble>() == 32.0);
  CHECK(outOf(w, "len").get<FieldType::SFDouble>() == Approx(std::sqrt(14.0)));
  // 0.1 + 0.2 as doubles: not rounded to float on the way out.
  CHECK(outOf(w, "precise").get<FieldType::SFVec3d>().x == 0.1 + 0.2);
  CHECK(outOf(w, "half").get<FieldType::SFVec2d>() == glm::dvec2(1.5, 2));
  CHECK(outOf(w, "unit").get<FieldType::SFVec4f>() == glm::vec4(0, 0.6f, 0, 0.8f));
  CHECK(outOf(w, "neg").get<FieldType::SFVec4d>() == glm::dvec4(-1, 2, -3, 4.5));
}

TEST_CASE("X3D Script: an SFVec3d eventIn, and a wrong value for an SFVec3d eventOut",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  inputOnly SFVec3d set_v
  inputOnly SFBool set_bad
  outputOnly SFVec3d doubled
  outputOnly SFDouble vx
  url "javascript:
    function set_v(v, t) { doubled = v.multiply(2); vx = v.x; }
    function set_bad(b) { doubled = 5; }
  "
}
)"),
                 0.0, x3dScripts());
  w.send("S", "set_v", FieldValue::make<FieldType::SFVec3d>(glm::dvec3(0.25, -1, 1e10)));
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "doubled").get<FieldType::SFVec3d>() == glm::dvec3(0.5, -2, 2e10));
  CHECK(outOf(w, "vx").get<FieldType::SFDouble>() == 0.25);
  w.send("S", "set_bad", FieldValue::make<FieldType::SFBool>(true));
  CHECK(modelDiagnostics(w).find("expected SFVec3d") != std::string::npos);
  CHECK(outOf(w, "doubled").get<FieldType::SFVec3d>() == glm::dvec3(0.5, -2, 2e10));
}

TEST_CASE("X3D Script: SFColorRGBA, MFColorRGBA, MFBool, MFDouble and MFVec2d", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  initializeOnly MFBool flags [ TRUE FALSE TRUE ]
  initializeOnly MFDouble values [ 0.5 1.25 2 ]
  initializeOnly MFColorRGBA colors [ 1 0 0 1, 0 0.5 1 0.25 ]
  outputOnly MFBool inverted
  outputOnly SFDouble total
  outputOnly SFColorRGBA second
  outputOnly SFColorRGBA green
  outputOnly MFVec2d points
  outputOnly MFColorRGBA built
  outputOnly SFString text
  url "ecmascript:
    function initialize() {
      var f = new MFBool();
      for (var i = 0; i < flags.length; ++i) f[i] = !flags[i];
      inverted = f;
      var s = 0;
      for (var j = 0; j < values.length; ++j) s += values[j];
      total = s;
      second = colors[1];
      var g = new SFColorRGBA(0, 0, 0, 0.75);
      g.setHSV(2 * Math.PI / 3, 1, 1);  // X3D's hue in radians (X_ITE)
      green = g;
      points = new MFVec2d(new SFVec2d(1, 2), new SFVec2d(3.5, 4));
      built = new MFColorRGBA(new SFColorRGBA(0.25, 0.5, 0.75, 1));
      text = String(colors[0]) + '|' + values.length + '|' + (flags instanceof MFBool);
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "inverted").get<FieldType::MFBool>() == std::vector<bool>{false, true, false});
  CHECK(outOf(w, "total").get<FieldType::SFDouble>() == 3.75);
  CHECK(outOf(w, "second").get<FieldType::SFColorRGBA>() == glm::vec4(0, 0.5f, 1, 0.25f));
  CHECK(outOf(w, "green").get<FieldType::SFColorRGBA>() == glm::vec4(0, 1, 0, 0.75f));
  CHECK(outOf(w, "points").get<FieldType::MFVec2d>() == std::vector<glm::dvec2>{{1, 2}, {3.5, 4}});
  CHECK(outOf(w, "built").get<FieldType::MFColorRGBA>() ==
        std::vector<glm::vec4>{{0.25f, 0.5f, 0.75f, 1}});
  CHECK(outOf(w, "text").get<FieldType::SFString>() == "1 0 0 1|3|true");
}

TEST_CASE("X3D Script: SFMatrix4f setTransform, multVecMatrix, inverse, transpose, getTransform",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  initializeOnly SFMatrix4f ref 1 0 0 0  0 1 0 0  0 0 1 0  1 2 3 1
  outputOnly SFMatrix4f moved
  outputOnly SFVec3f p
  outputOnly SFVec3f back
  outputOnly SFVec3f t
  outputOnly SFVec3f s
  outputOnly SFRotation r
  outputOnly SFFloat refTy
  outputOnly SFFloat tr
  outputOnly MFMatrix4d list
  outputOnly SFVec2f p2
  url "ecmascript:
    function initialize() {
      var m = new SFMatrix4f();
      m.setTransform(new SFVec3f(1, 2, 3));
      moved = m;
      refTy = ref[13];
      var k = new SFMatrix4f();
      k.setTransform(new SFVec3f(1, 2, 3), new SFRotation(0, 0, 1, Math.PI / 2), new SFVec3f(2, 2, 2));
      p = k.multVecMatrix(new SFVec3f(1, 0, 0));
      back = k.inverse().multVecMatrix(p);
      var tt = new SFVec3f(), ss = new SFVec3f(), rr = new SFRotation();
      k.getTransform(tt, rr, ss);
      t = tt; s = ss; r = rr;
      tr = k.transpose()[3];
      list = new MFMatrix4d(new SFMatrix4d(), k.multRight(k.inverse()));
      var m3 = new SFMatrix3f();
      m3.setTransform(new SFVec2f(10, 0), Math.PI / 2, new SFVec2f(3, 3));
      p2 = m3.multVecMatrix(new SFVec2f(1, 0));
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  // Built by setTransform, equal to the file's matrix with the translation 1 2 3.
  CHECK(outOf(w, "moved").get<FieldType::SFMatrix4f>() ==
        outOf(w, "ref").get<FieldType::SFMatrix4f>());
  CHECK(outOf(w, "refTy").get<FieldType::SFFloat>() == 2.0f);
  // (1,0,0) scaled by 2, turned a quarter about z, moved by (1,2,3).
  const glm::vec3 p = outOf(w, "p").get<FieldType::SFVec3f>();
  CHECK(p.x == Approx(1).margin(1e-6));
  CHECK(p.y == Approx(4).margin(1e-6));
  CHECK(p.z == Approx(3).margin(1e-6));
  const glm::vec3 back = outOf(w, "back").get<FieldType::SFVec3f>();
  CHECK(back.x == Approx(1).margin(1e-6));
  CHECK(back.y == Approx(0).margin(1e-6));
  CHECK(outOf(w, "t").get<FieldType::SFVec3f>() == glm::vec3(1, 2, 3));
  const glm::vec3 s = outOf(w, "s").get<FieldType::SFVec3f>();
  CHECK(s.x == Approx(2));
  CHECK(s.z == Approx(2));
  const vrml::Rotation r = outOf(w, "r").get<FieldType::SFRotation>();
  CHECK(r.z == Approx(1));
  CHECK(r.w == Approx(glm::half_pi<float>()));
  CHECK(outOf(w, "tr").get<FieldType::SFFloat>() == Approx(1.0f));  // element 12 of k
  const auto& list = outOf(w, "list").get<FieldType::MFMatrix4d>();
  REQUIRE(list.size() == 2);
  CHECK(list[0] == glm::dmat4(1));
  CHECK(list[1][0][0] == Approx(1));
  CHECK(list[1][3][0] == Approx(0).margin(1e-6));
  CHECK(list[1][0][3] == Approx(0).margin(1e-6));
  // 2D: (1,0) scaled by 3, turned a quarter, moved by (10,0).
  const glm::vec2 p2 = outOf(w, "p2").get<FieldType::SFVec2f>();
  CHECK(p2.x == Approx(10));
  CHECK(p2.y == Approx(3));
}

TEST_CASE("X3D Script: Browser name, version, currentFrameRate, println, createX3DFromString",
          "[script][x3d]") {
  FakeScriptContext ctx;
  ctx.fps = 30.0;
  ScriptWorld w = loadScript(ctx, R"(#X3D V3.3 utf8
PROFILE Immersive
DEF S Script {
  outputOnly SFString name
  outputOnly SFFloat fps
  outputOnly SFVec3f made
  outputOnly SFInt32 count
  url "ecmascript:
    function initialize() {
      name = Browser.name + ' ' + (typeof Browser.version) + ' ' + (Browser.name === Browser.getName());
      fps = Browser.currentFrameRate + Browser.currentSpeed;
      Browser.println('hello', 42);
      Browser.description = 'About';
      name += ' ' + Browser.description;
      var scene = Browser.createX3DFromString('DEF A Transform { translation 1 2 3 } Group { }');
      count = scene.rootNodes.length;
      made = scene.rootNodes[0].translation;
    }
  "
}
)",
                             relaxedLimits(), "test.x3dv");
  REQUIRE(w.instance);
  w.instance->initialize(0.0);
  INFO(ctx.diagnosticText());
  auto name = ctx.emittedFor(*w.script, "name");
  REQUIRE(name.size() == 1);
  CHECK(name[0].get<FieldType::SFString>() == "GhostSpace string true About");
  CHECK(ctx.description == "About");
  auto fps = ctx.emittedFor(*w.script, "fps");
  REQUIRE(fps.size() == 1);
  CHECK(fps[0].get<FieldType::SFFloat>() == 30.0f);
  REQUIRE(ctx.printed.size() == 1);
  CHECK(ctx.printed[0] == "hello 42");
  auto count = ctx.emittedFor(*w.script, "count");
  REQUIRE(count.size() == 1);
  CHECK(count[0].get<FieldType::SFInt32>() == 2);
  auto made = ctx.emittedFor(*w.script, "made");
  REQUIRE(made.size() == 1);
  CHECK(made[0].get<FieldType::SFVec3f>() == glm::vec3(1, 2, 3));
  REQUIRE(ctx.created.size() == 1);
  CHECK(ctx.created[0]->x3d.version == "3.3");
}

TEST_CASE("X3D Script: currentScene getNamedNode, rootNodes, createNode and addRoute",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 10 0 0 ] }
DEF T Transform { }
DEF S Script {
  outputOnly SFInt32 roots
  outputOnly SFString info
  outputOnly SFBool missingThrew
  outputOnly SFBool routed
  outputOnly SFBool deleted
  inputOnly SFBool unroute
  outputOnly SFFloat disk
  url "ecmascript:
    var route;
    function unroute(v) { deleted = Browser.currentScene.deleteRoute(route); }
    function initialize() {
      var scene = Browser.currentScene;
      roots = scene.rootNodes.length;
      var made = scene.createNode('Group');
      disk = new SFNode('Disk2D { outerRadius 2.5 }').outerRadius;
      info = scene.specificationVersion + ' ' + scene.encoding + ' ' + made.getNodeName() + ' ' +
             scene.getNamedNode('T').getNodeName() + ' ' + (scene instanceof X3DScene);
      try { scene.getNamedNode('Nope'); missingThrew = false; } catch (e) { missingThrew = true; }
      var r = scene.addRoute(scene.getNamedNode('PI'), 'value_changed', scene.getNamedNode('T'), 'set_translation');
      routed = r instanceof X3DRoute && r.sourceField === 'value_changed';
      route = r;
      scene.getNamedNode('T').scale = new SFVec3f(2, 2, 2);
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "roots").get<FieldType::SFInt32>() == 3);
  CHECK(outOf(w, "info").get<FieldType::SFString>() == "4.0 Classic VRML Group Transform true");
  CHECK(outOf(w, "missingThrew").get<FieldType::SFBool>());
  // new SFNode(text) in an X3D world reads X3D's nodes.
  CHECK(outOf(w, "disk").get<FieldType::SFFloat>() == 2.5f);
  CHECK(outOf(w, "routed").get<FieldType::SFBool>());
  // Written through the SFNode of getNamedNode.
  CHECK(w.node("T").field("scale")->get<FieldType::SFVec3f>() == glm::vec3(2, 2, 2));
  // The route the Script added carries the interpolator's value.
  w.send("PI", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(w.node("T").field("translation")->get<FieldType::SFVec3f>() == glm::vec3(5, 0, 0));
  // deleteRoute(the X3DRoute): the interpolator's events no longer arrive.
  w.send("S", "unroute", FieldValue::make<FieldType::SFBool>(true));
  CHECK(outOf(w, "deleted").get<FieldType::SFBool>());
  w.send("PI", "set_fraction", FieldValue::make<FieldType::SFFloat>(1.0f));
  CHECK(w.node("T").field("translation")->get<FieldType::SFVec3f>() == glm::vec3(5, 0, 0));
}

TEST_CASE("X3D Script: currentScene protos, externprotos and createProto", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
PROTO Ball [ inputOutput SFColor color 1 0 0 initializeOnly SFFloat radius 2 ] {
  Shape { appearance Appearance { material Material { diffuseColor IS color } }
          geometry Sphere { radius IS radius } }
}
EXTERNPROTO Far [ inputOutput SFFloat size ] [ "far.x3dv#Far" "http://example.org/far.x3dv" ]
DEF S Script {
  outputOnly SFString protos
  outputOnly SFString externs
  outputOnly SFString made
  outputOnly SFBool missingThrew
  url "ecmascript:
    function initialize() {
      var scene = Browser.currentScene;
      var p = scene.protos, e = scene.externprotos;
      protos = p.length + ' ' + p[0].name + ' ' + p[0].isExternProto + ' ' + p[0].fields.length +
               ' ' + p[0].fields[0].name + ' ' + (p[0].fields[0].dataType === X3DConstants.SFColor) +
               ' ' + (p[0].fields[1].accessType === X3DConstants.initializeOnly);
      externs = e.length + ' ' + e[0].name + ' ' + e[0].isExternProto + ' ' + e[0].urls.length +
                ' ' + e[0].urls[1];
      var ball = scene.createProto('Ball');
      var other = p[0].newInstance();
      made = ball.getNodeName() + ' ' + ball.radius + ' ' + other.color.r;
      try { scene.createProto('Nope'); missingThrew = false; } catch (x) { missingThrew = true; }
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "protos").get<FieldType::SFString>() == "1 Ball false 2 color true true");
  CHECK(outOf(w, "externs").get<FieldType::SFString>() ==
        "1 Far true 2 http://example.org/far.x3dv");
  CHECK(outOf(w, "made").get<FieldType::SFString>() == "Ball 2 1");  // the declared defaults
  CHECK(outOf(w, "missingThrew").get<FieldType::SFBool>());
}

TEST_CASE("X3D Script: addRootNode and removeRootNode change the world's root nodes",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF G Group { }
DEF S Script {
  outputOnly SFString counts
  outputOnly SFBool nullThrew
  url "ecmascript:
    function initialize() {
      var scene = Browser.currentScene;
      var t = scene.createNode('Transform');
      var before = scene.rootNodes.length;
      scene.addRootNode(t);
      scene.addRootNode(t);  // already a root: nothing
      var added = scene.rootNodes.length;
      var g = scene.getNamedNode('G');
      scene.removeRootNode(g);
      scene.removeRootNode(g);  // no longer one: nothing
      counts = before + ' ' + added + ' ' + scene.rootNodes.length + ' ' +
               scene.rootNodes[scene.rootNodes.length - 1].getNodeName();
      try { scene.addRootNode(null); nullThrew = false; } catch (e) { nullThrew = true; }
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "counts").get<FieldType::SFString>() == "2 3 2 Transform");
  CHECK(outOf(w, "nullThrew").get<FieldType::SFBool>());
  // The world itself, as the renderer walks it: S and the new Transform.
  REQUIRE(w.scene->rootNodes.size() == 2);
  CHECK(w.scene->rootNodes[1]->typeName() == "Transform");
}

TEST_CASE("X3D Script: another node's X3D-typed fields through its SFNode", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF C ColorRGBA { color [ 0.25 0.5 0.75 0.125 ] }
DEF M TextureTransformMatrix3D { }
DEF S Script {
  initializeOnly SFNode c USE C
  initializeOnly SFNode m USE M
  outputOnly SFFloat alpha
  outputOnly SFFloat diagonal
  url "ecmascript:
    function initialize() {
      alpha = c.color[0].a;
      diagonal = m.matrix[0] + m.matrix[5] + m.matrix[10] + m.matrix[15] + m.matrix[1];
      c.color = new MFColorRGBA(new SFColorRGBA(1, 0, 0, 0.5), [0, 1, 0, 1]);
      var t = new SFMatrix4f();
      t.setTransform(new SFVec3f(7, 8, 9));
      m.matrix = t;
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "alpha").get<FieldType::SFFloat>() == 0.125f);
  CHECK(outOf(w, "diagonal").get<FieldType::SFFloat>() == 4.0f);
  CHECK(w.node("C").field("color")->get<FieldType::MFColorRGBA>() ==
        std::vector<glm::vec4>{{1, 0, 0, 0.5f}, {0, 1, 0, 1}});
  // The translation is the matrix's last row as X3D writes it (numbers 12 13 14).
  const glm::mat4 m = w.node("M").field("matrix")->get<FieldType::SFMatrix4f>();
  CHECK(m[0][3] == 7.0f);
  CHECK(m[1][3] == 8.0f);
  CHECK(m[2][3] == 9.0f);
  CHECK(m[0][0] == 1.0f);
}

TEST_CASE("X3D Script: createX3DFromURL sends the file's nodes to the eventIn", "[script][x3d]") {
  FakeScriptContext ctx;
  ctx.files["part.x3dv"] = "#X3D V3.3 utf8\nTransform { translation 4 5 6 }\n";
  ScriptWorld w = loadScript(ctx, R"(#X3D V3.3 utf8
DEF G Group { }
DEF S Script {
  initializeOnly SFNode g USE G
  url "ecmascript:
    function initialize() { Browser.createX3DFromURL(new MFString('missing.x3dv', 'part.x3dv'), 'addChildren', g); }
  "
}
)",
                             relaxedLimits(), "test.x3dv");
  REQUIRE(w.instance);
  w.instance->initialize(0.0);
  INFO(ctx.diagnosticText());
  REQUIRE(ctx.sent.size() == 1);
  CHECK(ctx.sent[0].node->typeName() == "Group");
  CHECK(ctx.sent[0].field == ctx.sent[0].node->type().findField("addChildren"));
  const auto& nodes = ctx.sent[0].value.get<FieldType::MFNode>();
  REQUIRE(nodes.size() == 1);
  CHECK(nodes[0]->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(4, 5, 6));
  CHECK(ctx.diagnosticText().find("missing.x3dv") != std::string::npos);
}

TEST_CASE("X3D Script: an MFVec3d longer than the memory limit allows is refused",
          "[script][x3d]") {
  FakeScriptContext ctx;
  runtime::ScriptLimits limits = relaxedLimits();
  limits.heapBytes = 8u * 1024u * 1024u;
  ScriptWorld w = loadScript(ctx, R"(#X3D V4.0 utf8
DEF S Script {
  outputOnly MFVec3d big
  outputOnly MFMatrix4d many
  outputOnly SFInt32 after
  url "ecmascript:
    function initialize() {
      var a = new MFVec3d();
      a.length = 100000000;
      try { big = a; } catch (e) { after = 1; }
      var b = new MFMatrix4d();
      b.length = 100000000;
      try { many = b; } catch (e) { after += 1; }
    }
  "
}
)",
                             limits, "test.x3dv");
  REQUIRE(w.instance);
  w.instance->initialize(0.0);
  INFO(ctx.diagnosticText());
  CHECK(ctx.emittedFor(*w.script, "big").empty());
  CHECK(ctx.emittedFor(*w.script, "many").empty());
  auto after = ctx.emittedFor(*w.script, "after");
  REQUIRE(after.size() == 1);
  CHECK(after[0].get<FieldType::SFInt32>() == 2);
  CHECK_FALSE(w.instance->stopped());
}

TEST_CASE("X3D Script: X3DConstants and getFieldDefinitions", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF T Transform { }
DEF S Script {
  initializeOnly SFNode t USE T
  outputOnly MFInt32 constants
  outputOnly SFString translation
  outputOnly SFString own
  url "ecmascript:
    function describe(node, name) {
      var defs = node.getFieldDefinitions();
      for (var i = 0; i < defs.length; ++i)
        if (defs[i].name === name) return name + ' ' + defs[i].accessType + ' ' + defs[i].dataType;
      return 'none';
    }
    function initialize() {
      constants = new MFInt32(X3DConstants.initializeOnly, X3DConstants.inputOnly,
                              X3DConstants.outputOnly, X3DConstants.inputOutput,
                              X3DConstants.SFBool, X3DConstants.SFVec3f, X3DConstants.SFVec3d,
                              X3DConstants.MFBool, X3DConstants.MFVec4f);
      translation = describe(t, 'translation') + ',' + describe(t, 'addChildren');
      own = describe(Browser.currentScene.getNamedNode('S'), 'own');
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "constants").get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{0, 1, 2, 3, 0, 18, 17, 21, 41});
  CHECK(outOf(w, "translation").get<FieldType::SFString>() == "translation 3 18,addChildren 1 32");
  CHECK(outOf(w, "own").get<FieldType::SFString>() == "own 2 13");
}

TEST_CASE("X3D Script: node type constants and SFNode.getNodeType", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF T Transform { }
DEF S Script {
  initializeOnly SFNode t USE T
  outputOnly SFString kinds
  url "ecmascript:
    function has(types, c) { return types.indexOf(c) >= 0 ? 'y' : 'n'; }
    function initialize() {
      var types = t.getNodeType();
      kinds = (types[0] === X3DConstants.Transform ? 'T' : '?') +
              has(types, X3DConstants.X3DGroupingNode) + has(types, X3DConstants.X3DChildNode) +
              has(types, X3DConstants.X3DBoundedObject) + has(types, X3DConstants.X3DShapeNode) +
              (X3DConstants.Transform !== X3DConstants.Group ? 'd' : 's') +
              (typeof X3DConstants.X3DPrototypeInstance) + ' ' +
              Browser.currentScene.getNamedNode('S').getNodeType().indexOf(X3DConstants.Script);
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  // A Transform is a grouping, child and bounded node and no shape; Script is its type.
  CHECK(outOf(w, "kinds").get<FieldType::SFString>() ==
        "Tyyynd"
        "number 0");
}

TEST_CASE("X3D Script: getImportedNode answers the world's IMPORTs", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF T Transform { }
DEF S Script {
  inputOnly SFTime look
  outputOnly SFString found
  url "ecmascript:
    function look() {
      var scene = Browser.currentScene;
      var parts = [];
      try { parts.push(scene.getImportedNode('Imported').getNodeName()); }
      catch (e) { parts.push('none'); }
      try { scene.getImportedNode('Unknown'); parts.push('?'); }
      catch (e) { parts.push(e.message.indexOf('Unknown') >= 0 ? 'error' : 'other'); }
      found = parts.join(' ');
    }
  "
}
)"),
                 0.0, x3dScripts());
  // Before the IMPORT's Inline arrives there is none; session::WorldRuntimes then records it.
  w.send("S", "look", vrml::FieldValue::make<FieldType::SFTime>(1.0));
  CHECK(outOf(w, "found").get<FieldType::SFString>() == "none error");
  w.model->setImportedNode("Imported", w.scene->rootNodes.front());
  w.send("S", "look", vrml::FieldValue::make<FieldType::SFTime>(2.0));
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "found").get<FieldType::SFString>() == "Transform error");
}

TEST_CASE("X3D Script: inline code in the XML encoding's CDATA and ecmascript: urls run",
          "[script][x3d]") {
  RunningWorld xml(WorldText{R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile="Immersive" version="3.3">
  <Scene>
    <Script DEF="S">
      <field name="out" type="SFVec3d" accessType="outputOnly"/>
      <field name="start" type="SFVec3d" accessType="initializeOnly" value="1 2 3"/>
      <![CDATA[
        function initialize() { out = start.add(new SFVec3d(0.5, 0.5, 0.5)); }
      ]]>
    </Script>
  </Scene>
</X3D>
)",
                             "test.x3d"},
                   0.0, x3dScripts());
  INFO(modelDiagnostics(xml));
  CHECK(outOf(xml, "out").get<FieldType::SFVec3d>() == glm::dvec3(1.5, 2.5, 3.5));

  RunningWorld classic(x3dWorld(R"(
DEF S Script {
  outputOnly SFDouble out
  url [ "ecmascript: function initialize() { out = 1 / 3; }" ]
}
)"),
                       0.0, x3dScripts());
  INFO(modelDiagnostics(classic));
  CHECK(outOf(classic, "out").get<FieldType::SFDouble>() == 1.0 / 3.0);
}

TEST_CASE("X3D Script: a VRML97 world's Script goes without the X3D classes", "[script][x3d]") {
  RunningWorld w(R"(
DEF S Script {
  eventOut SFString seen
  url "javascript:
    function initialize() {
      seen = typeof SFVec3d + ' ' + typeof X3DConstants + ' ' + typeof Browser.currentScene + ' ' +
             typeof SFVec3f + ' ' + Browser.name;
    }
  "
}
)",
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "seen").get<FieldType::SFString>() ==
        "undefined undefined undefined function GhostSpace");
}
