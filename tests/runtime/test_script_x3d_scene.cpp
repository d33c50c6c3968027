// Browser.createX3DFromString returns a whole X3DScene (ISO/IEC 19777-1 clause 7.2.3):
// its header, root nodes, DEF names, PROTO declarations, EXPORTs and ROUTEs, apart from
// the world's; its nodes placed in the world by Browser.currentScene.addRootNode, or the
// world replaced by it (Browser.replaceWorld(scene)); a Script in an Inline's world sees
// that world as its currentScene; getBrowserProperty. Small X3D worlds run by the
// execution model; the Scripts' outputs are read back from the Script node.
#include "x3d_script_support.hpp"

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

TEST_CASE("X3D Script: createX3DFromString returns the text's whole X3DScene", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF G Group { }
DEF S Script {
  outputOnly SFString header
  outputOnly SFString names
  outputOnly SFString protos
  outputOnly SFString roots
  outputOnly SFString threw
  inputOnly SFBool go
  url "ecmascript:
    var made;
    function go(v) { made.getNamedNode('PI').set_fraction = 0.5; }
    function initialize() {
      made = Browser.createX3DFromString(
        '#X3D V4.0 utf8\\nPROFILE Interchange\\n' +
        'PROTO Dot [ initializeOnly SFFloat r 3 ] { Sphere { radius IS r } }\\n' +
        'DEF A Transform { children Shape { geometry Dot { } } }\\n' +
        'DEF B Group { }\\n' +
        'DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 4 0 0 ] }\\n' +
        'ROUTE PI.value_changed TO A.set_translation\\n' +
        'EXPORT A AS Moved\\n');
      var world = Browser.currentScene;
      header = (made instanceof X3DScene) + ' ' + made.specificationVersion + ' ' +
               made.profile + ' ' + made.encoding + ' ' + (made !== world);
      names = made.getNamedNode('B').getNodeName() + ' ' +
              (made.getExportedNode('Moved') === made.getNamedNode('A'));
      var p = made.protos;
      protos = p.length + ' ' + p[0].name + ' ' + made.createProto('Dot').r + ' ' +
               p[0].newInstance().getNodeName() + ' ' + world.protos.length;
      var before = world.rootNodes.length;
      made.removeRootNode(made.getNamedNode('B'));
      var kept = made.rootNodes.length;
      world.addRootNode(made.getNamedNode('A'));
      roots = before + ' ' + made.rootNodes.length + ' ' + kept + ' ' + world.rootNodes.length;
      threw = '';
      try { made.getNamedNode('G'); } catch (e) { threw += 'G '; }
      try { world.getNamedNode('B'); } catch (e) { threw += 'B '; }
      try { made.getExportedNode('Nope'); } catch (e) { threw += 'Nope '; }
      try { made.getImportedNode('Moved'); } catch (e) { threw += 'Moved'; }
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "header").get<FieldType::SFString>() == "true 4.0 Interchange Classic VRML true");
  CHECK(outOf(w, "names").get<FieldType::SFString>() == "Group true");
  // Its own declarations, not the world's (which has none).
  CHECK(outOf(w, "protos").get<FieldType::SFString>() == "1 Dot 3 Dot 0");
  // removeRootNode changed the made scene's roots (3 -> 2) and not the world's;
  // addRootNode on the world added A to the world's (2 -> 3) and not to the scene's.
  CHECK(outOf(w, "roots").get<FieldType::SFString>() == "2 2 2 3");
  CHECK(outOf(w, "threw").get<FieldType::SFString>() == "G B Nope Moved");
  REQUIRE(w.scene->rootNodes.size() == 3);
  const vrml::NodePtr& a = w.scene->rootNodes.back();
  CHECK(a->defName == "A");
  // The text's ROUTE runs: the interpolator moves A, now drawn in the world.
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  CHECK(a->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(2, 0, 0));
}

TEST_CASE(
    "X3D Script: replaceWorld takes createX3DFromString's scene; a VRML97 Script gets "
    "its root nodes",
    "[script][x3d]") {
  const char* body = R"(
DEF S Script {
  %s
  url "ecmascript:
    function initialize() {
      var made = Browser.createX3DFromString('Group { } Transform { } Shape { }');
      kind = typeof X3DScene === 'undefined' ? 'plain ' + made.rootNodes.length
                                              : String(made instanceof X3DScene);
      Browser.replaceWorld(made);
    }
  "
}
)";
  for (const bool x3d : {true, false}) {
    FakeScriptContext ctx;
    char text[1024];
    std::snprintf(text, sizeof text, body,
                  x3d ? "outputOnly SFString kind" : "eventOut SFString kind");
    const std::string world = (x3d ? "#X3D V4.0 utf8\n" : "#VRML V2.0 utf8\n") + std::string(text);
    ScriptWorld w = loadScript(ctx, world, relaxedLimits(), x3d ? "test.x3dv" : "test.wrl");
    REQUIRE(w.instance);
    w.instance->initialize(0.0);
    INFO(ctx.diagnosticText());
    auto kind = ctx.emittedFor(*w.script, "kind");
    REQUIRE(kind.size() == 1);
    CHECK(kind[0].get<FieldType::SFString>() == (x3d ? "true" : "plain 3"));
    REQUIRE(ctx.replacedWith.size() == 3);
    CHECK(ctx.replacedWith[1]->typeName() == "Transform");
  }
}

TEST_CASE("X3D Script: a Script in an Inline's world has that world as its currentScene",
          "[script][x3d]") {
  RunningWorld w(x3dWorld("DEF Outer Group { }\nDEF Second Group { }\n"), 0.0, x3dScripts());
  auto inner = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Immersive
DEF Inner Transform { }
DEF S Script {
  outputOnly SFString info
  outputOnly SFString threw
  url "ecmascript:
    function initialize() {
      var scene = Browser.currentScene;
      info = scene.rootNodes.length + ' ' + scene.getNamedNode('Inner').getNodeName() + ' ' +
             scene.worldURL + ' ' + scene.profile;
      threw = '';
      try { scene.getNamedNode('Outer'); } catch (e) { threw += 'Outer '; }
      try { scene.getImportedNode('Outer'); } catch (e) { threw += 'import'; }
    }
  "
}
)",
                                                             "file:///worlds/sub/inner.x3dv"));
  w.model->addInlineScene(inner);  // as session::WorldRuntimes::addInlines does
  INFO(modelDiagnostics(w));
  const vrml::NodePtr& script = inner->rootNodes.at(1);
  REQUIRE(script->field("info") != nullptr);
  CHECK(script->field("info")->get<FieldType::SFString>() ==
        "2 Transform file:///worlds/sub/inner.x3dv Immersive");
  CHECK(script->field("threw")->get<FieldType::SFString>() == "Outer import");
  CHECK(w.scene->rootNodes.size() == 2);  // the browser's world is unchanged
}

TEST_CASE("X3D Script: getBrowserProperty answers what this browser can do", "[script][x3d]") {
  FakeScriptContext ctx;
  ScriptWorld w = loadScript(ctx, R"(#X3D V4.0 utf8
DEF S Script {
  outputOnly SFString answers
  url "ecmascript:
    function initialize() {
      var names = ['ABSTRACT_NODES', 'CONCRETE_NODES', 'EXTERNAL_INTERACTIONS', 'PROTOTYPE_CREATE',
                   'DOM_IMPORT', 'XML_ENCODING', 'CLASSIC_VRML_ENCODING', 'BINARY_ENCODING', 'NOPE'];
      answers = names.map(function (n) { return Browser.getBrowserProperty(n) ? 1 : 0; }).join('');
    }
  "
}
)",
                             relaxedLimits(), "test.x3dv");
  REQUIRE(w.instance);
  w.instance->initialize(0.0);
  INFO(ctx.diagnosticText());
  auto answers = ctx.emittedFor(*w.script, "answers");
  REQUIRE(answers.size() == 1);
  CHECK(answers[0].get<FieldType::SFString>() == "110101100");
}

TEST_CASE("Browser.replaceWorld: the scene's nodes become the world, its first Viewpoint bound",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF OLD Viewpoint { position 0 0 10 }
DEF G Group { }
DEF S Script {
  inputOnly SFBool go
  url "ecmascript:
    function go(v) {
      Browser.replaceWorld(Browser.createX3DFromString(
        'DEF T Transform { children DEF NEW Viewpoint { position 0 0 3 } } ' +
        'DEF LATER Viewpoint { position 0 0 7 }'));
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  using gs::runtime::BindableKind;
  REQUIRE(w.model->bound(BindableKind::Viewpoint) == &w.node("OLD"));
  const std::uint64_t revision = w.model->bindingRevision();
  w.take();
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  REQUIRE(w.scene->rootNodes.size() == 2);
  CHECK(w.scene->rootNodes[0]->defName == "T");
  CHECK(w.scene->rootNodes[1]->defName == "LATER");
  const vrml::Node* bound = w.model->bound(BindableKind::Viewpoint);
  REQUIRE(bound != nullptr);
  CHECK(bound->defName == "NEW");  // the first in file order, inside the Transform
  CHECK(w.model->bindStack(BindableKind::Viewpoint).size() == 1);
  CHECK(w.model->bindingRevision() > revision);
  const std::vector<std::string> events = w.take();
  CHECK(std::find(events.begin(), events.end(), "OLD.isBound=FALSE") != events.end());
  CHECK(std::find(events.begin(), events.end(), "NEW.isBound=TRUE") != events.end());
  // The same world again: its first Viewpoint stays bound, without events.
  const std::vector<vrml::NodePtr> same = w.scene->rootNodes;  // as a Script would pass them
  w.model->replaceWorld(same);
  CHECK(w.model->bound(BindableKind::Viewpoint) == bound);
  for (const std::string& e : w.take()) CHECK(e.find("isBound") == std::string::npos);
}

TEST_CASE("X3D Script: a field changed in place reaches its node before a later event to it",
          "[script][x3d]") {
  // create3000's Core/EXPORT.x3d: `transform.children.length = 0; transform.addChildren =
  // node.children` empties the children, then adds the exported node's (X_ITE runs the two
  // in that order). The in-place change used to be sent at the call's end, after
  // addChildren, leaving no children.
  RunningWorld w(x3dWorld(R"(
DEF T Transform { children [ Group { } Group { } ] }
DEF E Transform { children DEF SHAPE Shape { geometry Box { } } }
EXPORT E AS Exported
DEF S Script {
  initializeOnly SFNode transform USE T
  url "ecmascript:
    function initialize() {
      var node = Browser.currentScene.getExportedNode('Exported');
      transform.children.length = 0;
      transform.addChildren = node.children;
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  const auto& children = w.node("T").field("children")->get<FieldType::MFNode>();
  REQUIRE(children.size() == 1);
  CHECK(children[0]->defName == "SHAPE");
}

TEST_CASE("X3D Script: live fields sent before an event, and then assigned", "[script][x3d]") {
  // A field changed in place and then assigned: its routes see the assigned value last. A
  // value whose valueOf reads many more live fields while the changed ones are being sent
  // (the list of live fields grows under that loop).
  RunningWorld w(x3dWorld(R"(
DEF C Coordinate { point [ 1 1 1, 2 2 2 ] }
DEF D Coordinate { }
ROUTE C.point_changed TO D.set_point
DEF T Transform { }
DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 1 1 1 ] }
DEF S Script {
  initializeOnly SFNode c USE C
  initializeOnly SFNode t USE T
  initializeOnly SFNode pi USE PI
  url "ecmascript:
    function initialize() {
      c.point.length = 0;
      c.point = new MFVec3f(new SFVec3f(7, 8, 9));
      var others = [];
      for (var i = 0; i < 200; ++i) others.push(Browser.currentScene.createNode('Transform'));
      pi.key[1] = { valueOf: function () {
        for (var i = 0; i < others.length; ++i) others[i].translation.x = 1;
        return 2;
      } };
      pi.set_fraction = 0.5;
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  const auto& point = w.node("D").field("point")->get<FieldType::MFVec3f>();
  REQUIRE(point.size() == 1);
  CHECK(point[0] == glm::vec3(7, 8, 9));
  const auto& key = w.node("PI").field("key")->get<FieldType::MFFloat>();
  REQUIRE(key.size() == 2);
  CHECK(key[1] == 2.0f);
}
