// What an X3D Script learns of its browser and scene (ISO/IEC 19777-1 clause 7.2 and 7.4):
// Browser.supportedProfiles, supportedComponents, getProfile, getComponent and
// getRenderingProperty; X3DScene.profile, components and units; the browser callbacks
// (addBrowserCallback as X_ITE 15 names it, addBrowserListener) for INITIALIZED_EVENT and
// SHUTDOWN_EVENT. Small X3D worlds run by the execution model.
#include "vrml/node_model.hpp"
#include "x3d_script_support.hpp"

#include <map>
#include <sstream>

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

TEST_CASE("X3D Script: the browser's profiles and components", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  outputOnly SFString profiles
  outputOnly SFString components
  outputOnly SFString asked
  url "ecmascript:
    function initialize() {
      profiles = Browser.supportedProfiles.map(function (p) {
        return p.name + ':' + p.components.length;
      }).join(' ');
      components = Browser.supportedComponents.map(function (c) {
        return c.name + ':' + c.level;
      }).join(' ');
      var immersive = Browser.getProfile('Immersive');
      var scripting = immersive.components.filter(function (c) { return c.name === 'Scripting'; });
      asked = (immersive instanceof ProfileInfo) + ' ' + immersive.title + ' ' +
              scripting[0].level + ' ' + Browser.getComponent('Rendering', 9).level + ' ' +
              Browser.getComponent('Rendering', 2).level + ' ' +
              Browser.getComponent('NURBS').title + ' ' + Browser.getProfile('MPEG-4').name;
      try { Browser.getProfile('Nope'); } catch (e) { asked += ' noProfile'; }
      try { Browser.getComponent('Nope', 1); } catch (e) { asked += ' noComponent'; }
      try { Browser.supportedProfiles.push(1); } catch (e) { asked += ' frozen'; }
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "profiles").get<FieldType::SFString>() ==
        "CADInterchange:10 Core:1 Full:37 Immersive:20 Interactive:16 Interchange:12 "
        "MedicalInterchange:17 MPEG4Interactive:14");
  CHECK(outOf(w, "asked").get<FieldType::SFString>() ==
        "true Immersive 1 5 2 NURBS MPEG4Interactive noProfile noComponent frozen");
  // Every node type of X3D 4.0 is in a component the browser names, at a level it supports.
  std::map<std::string, int> levels;
  std::istringstream in(outOf(w, "components").get<FieldType::SFString>());
  for (std::string entry; in >> entry;) {
    const std::size_t colon = entry.find(':');
    REQUIRE(colon != std::string::npos);
    levels[entry.substr(0, colon)] = std::stoi(entry.substr(colon + 1));
  }
  CHECK(levels.size() == 37);
  int nodes = 0;
  for (const vrml::NodeModel& m : vrml::nodeModels()) {
    if (m.extension) continue;
    ++nodes;
    INFO(m.name << " of " << m.component << " level " << m.level);
    const auto it = levels.find(std::string(m.component));
    REQUIRE(it != levels.end());
    CHECK(m.level <= it->second);
  }
  CHECK(nodes >= 260);
}

TEST_CASE("X3D Script: a scene's profile, components and units", "[script][x3d]") {
  RunningWorld w(WorldText{R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT Geospatial:1
COMPONENT HAnim:3
UNIT angle degree 0.017453292519943295
UNIT mass gram 0.001
DEF S Script {
  outputOnly SFString scene
  outputOnly SFString made
  url "ecmascript:
    function initialize() {
      var s = Browser.currentScene;
      scene = s.profile + ' ' + (s.profile instanceof ProfileInfo) + ' ' +
              s.profile.components.length + ' ' +
              s.components.map(function (c) { return c.name + ':' + c.level + ':' + c.title; }).join() + ' ' +
              s.units.map(function (u) { return u.category + ':' + u.name + ':' + u.conversionFactor.toFixed(4); }).join();
      var x = Browser.createX3DFromString('#X3D V4.0 utf8\\nPROFILE Custom\\nGroup { }\\n');
      var y = Browser.createX3DFromString('#X3D V4.0 utf8\\nGroup { }\\n');
      made = x.profile.name + ' ' + x.profile.components.length + ' ' + y.profile + ' ' +
             y.components.length + ' ' + y.units[2].name;
    }
  "
}
)",
                           "test.x3dv"},
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "scene").get<FieldType::SFString>() ==
        "Immersive true 20 Geospatial:1:Geospatial,HAnim:3:Humanoid animation (HAnim) "
        "angle:degree:0.0175,force:newton:1.0000,length:metre:1.0000,mass:gram:0.0010");
  CHECK(outOf(w, "made").get<FieldType::SFString>() == "Custom 0 null 0 metre");
}

TEST_CASE("Browser.getRenderingProperty: the renderer's limits and the Shading option",
          "[script][x3d]") {
  const std::string world = R"(
DEF S Script {
  outputOnly SFString answers
  url "ecmascript:
    function initialize() {
      answers = ['Shading', 'MaxTextureSize', 'TextureUnits', 'MaxLights', 'Antialiased',
                 'ColorDepth', 'TextureMemory', 'Nope'].map(function (n) {
        return String(Browser.getRenderingProperty(n));
      }).join(' ');
    }
  "
}
)";
  runtime::ExecutionOptions o = x3dScripts();
  o.browserOptions["Shading"] = {"GOURAUD", {}};
  o.rendering = {16384, 4, 8, true, 24};
  RunningWorld given(x3dWorld(world), 0.0, std::move(o));
  INFO(modelDiagnostics(given));
  CHECK(outOf(given, "answers").get<FieldType::SFString>() ==
        "GOURAUD 16384 4 8 true 24 undefined undefined");
  // A host that gives none (a test's execution model): undefined, never a made-up value.
  RunningWorld none(x3dWorld(world), 0.0, x3dScripts());
  CHECK(outOf(none, "answers").get<FieldType::SFString>() ==
        "undefined undefined undefined undefined undefined undefined undefined undefined");
}

TEST_CASE(
    "X3D Script: browser callbacks see INITIALIZED_EVENT after the load and "
    "SHUTDOWN_EVENT before shutdown()",
    "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  inputOnly SFBool go
  outputOnly SFString log
  url "ecmascript:
    var text = '';
    function note(what) { text += what + ' '; log = text; }
    function initialize() {
      note('initialize');
      Browser.addBrowserCallback('k', X3DConstants.INITIALIZED_EVENT, function (e) { note('init:' + e); });
      Browser.addBrowserCallback('all', function (e) { note('all:' + e); });
      Browser.addBrowserCallback('gone', function (e) { note('gone:' + e); });
      Browser.removeBrowserCallback('gone');
      Browser.addBrowserListener(function (e) { note('listener:' + e); });
      Browser.addBrowserCallback('k', X3DConstants.SHUTDOWN_EVENT, function (e) { note('down:' + e); });
    }
    function go(v) { Browser.replaceWorld(Browser.createX3DFromString('Group { }')); }
    function shutdown() { note('shutdown'); }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  const vrml::NodePtr script = w.scene->rootNodes.at(0);
  // Nothing until the world's file is read to its end (session::WorldRuntimes says so).
  CHECK(script->field("log")->get<FieldType::SFString>() == "initialize ");
  w.model->worldLoaded();
  w.model->worldLoaded();  // once only
  // The 'k' callback for INITIALIZED_EVENT stays: one key may hold one callback per event.
  CHECK(script->field("log")->get<FieldType::SFString>() == "initialize init:2 all:2 listener:2 ");
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  w.model->advanceTo(1.0);
  CHECK(script->field("log")->get<FieldType::SFString>() ==
        "initialize init:2 all:2 listener:2 all:3 listener:3 down:3 shutdown ");
}

TEST_CASE("X3D Script: INITIALIZED_ERROR when the world's file ends short or a link fails",
          "[script][x3d]") {
  const char* world = R"(
DEF S Script {
  outputOnly SFString log
  url "ecmascript:
    var text = '';
    function initialize() {
      Browser.addBrowserCallback('k', function (e) { text += e + ' '; log = text; });
    }
  "
}
)";
  // The stream ended short (failed or stopped): INITIALIZED_ERROR in place of
  // INITIALIZED_EVENT, once.
  RunningWorld cut(x3dWorld(world), 0.0, x3dScripts());
  INFO(modelDiagnostics(cut));
  const vrml::NodePtr script = cut.scene->rootNodes.at(0);
  cut.model->worldLoaded(false);
  cut.model->worldLoaded(true);
  CHECK(script->field("log")->get<FieldType::SFString>() == "4 ");
  // A link the world asked for could not open: INITIALIZED_ERROR each time.
  RunningWorld whole(x3dWorld(world), 0.0, x3dScripts());
  const vrml::NodePtr other = whole.scene->rootNodes.at(0);
  whole.model->worldLoaded();
  whole.model->linkFailed();
  whole.model->linkFailed();
  CHECK(other->field("log")->get<FieldType::SFString>() == "2 4 4 ");
}

TEST_CASE("X3D Script: a scene and a node written as Classic VRML, XML and JSON text",
          "[script][x3d]") {
  RunningWorld w(WorldText{R"(#X3D V4.0 utf8
PROFILE Interchange
DEF T Transform { translation 1 2 3 children Shape { geometry Box { } } }
DEF S Script {
  outputOnly SFString vrml
  outputOnly SFString xml
  outputOnly SFString json
  outputOnly SFString scene
  url "ecmascript:
    function initialize() {
      var t = Browser.currentScene.getNamedNode('T');
      vrml = t.toVRMLString();
      xml = t.toXMLString();
      json = t.toJSONString();
      var made = Browser.createX3DFromString('#X3D V4.0 utf8\\nPROFILE Immersive\\nGroup { }\\n');
      scene = made.toVRMLString() + '|' + Browser.currentScene.toXMLString().indexOf('<Transform DEF=');
    }
  "
}
)",
                           "test.x3dv"},
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "vrml").get<FieldType::SFString>() ==
        "DEF T Transform {\n  children [\n    Shape {\n      geometry Box { }\n    }\n  ]\n"
        "  translation 1 2 3\n}\n");
  CHECK(outOf(w, "xml").get<FieldType::SFString>() ==
        "<Transform DEF=\"T\" translation=\"1 2 3\">\n  <Shape>\n    <Box/>\n  </Shape>\n"
        "</Transform>\n");
  CHECK(outOf(w, "json").get<FieldType::SFString>() ==
        "{\"Transform\": {\n  \"@DEF\": \"T\",\n  \"@translation\": [1, 2, 3],\n"
        "  \"-children\": [\n    {\"Shape\": {\n      \"-geometry\": {\"Box\": {}}\n    }}\n"
        "  ]\n}}\n");
  const std::string scene = outOf(w, "scene").get<FieldType::SFString>();
  CHECK(scene.starts_with("#X3D V4.0 utf8\nPROFILE Immersive\n\nGroup { }\n|"));
  CHECK(!scene.ends_with("|-1"));
}

TEST_CASE(
    "X3D Script: toVRMLString refuses a node among its own descendants, a chain too "
    "deep and a graph that would write too many nodes",
    "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  inputOnly SFBool go
  outputOnly SFString made
  url "ecmascript:
    var cycle, cycleB, shallow, deep, wide;
    function group() { return Browser.currentScene.createNode('Group'); }
    function chain(n) {
      var top = group(), c = top;
      for (var i = 1; i < n; ++i) { var d = group(); c.children = new MFNode(d); c = d; }
      return top;
    }
    function initialize() {
      // A children cycle is refused (test_graph_cycles.cpp); a TransformSensor below the
      // node it watches is a cycle too, through a field that names its target.
      cycle = group();
      cycleB = Browser.currentScene.createNode('TransformSensor');
      cycleB.targetObject = cycle;
      cycle.children = new MFNode(cycleB);
      shallow = chain(200);
      deep = chain(300);
      // 30 levels of a pair of children that are one node: 2^30 nodes written out.
      wide = group();
      var c = wide;
      for (var i = 0; i < 30; ++i) { var d = group(); c.children = new MFNode(d, d); c = d; }
    }
    function text(n, how) {
      try { return String(n[how]().length > 0); } catch (e) { return e.name; }
    }
    function go(v) {
      made = [text(cycle, 'toVRMLString'), text(cycle, 'toXMLString'), text(cycle, 'toJSONString'),
              text(shallow, 'toVRMLString'), text(deep, 'toVRMLString'), text(wide, 'toXMLString')].join(' ');
      cycleB.targetObject = null;  // the cycle freed
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  CHECK(outOf(w, "made").get<FieldType::SFString>() ==
        "RangeError RangeError RangeError true RangeError RangeError");
}

TEST_CASE("X3D Script: a scene's COMPONENT and UNIT statements edited", "[script][x3d]") {
  RunningWorld w(WorldText{R"(#X3D V4.0 utf8
PROFILE Interchange
COMPONENT Geospatial:1
UNIT mass gram 0.001
DEF S Script {
  outputOnly SFString edits
  url "ecmascript:
    function initialize() {
      var s = Browser.currentScene, out = [];
      out.push(s.hasComponent('Geospatial') + ' ' + s.hasComponent('Geospatial', 2) + ' ' +
               s.hasComponent('NURBS'));
      s.addComponent(Browser.getComponent('NURBS', 2));
      try { s.addComponent(Browser.getComponent('NURBS', 4)); } catch (e) { out.push('inUse'); }
      s.updateComponent(Browser.getComponent('Geospatial', 2));
      s.removeComponent('Nope');
      out.push(s.components.map(function (c) { return c.name + ':' + c.level; }).join());
      s.removeComponent('Geospatial');
      s.updateUnit('length', 'km', 1000);
      s.updateUnit('mass', 'kilogram', 1);
      try { s.updateUnit('time', 's', 1); } catch (e) { out.push('noCategory'); }
      try { s.updateUnit('length', 'x', -1); } catch (e) { out.push(e.name); }
      out.push(s.components.length + ' ' + s.getUnit('length').name + ' ' +
               s.getUnit('length').conversionFactor + ' ' + s.getUnit('mass').name + ' ' +
               s.getUnit('angle').name);
      edits = out.join(';');
    }
  "
}
)",
                           "test.x3dv"},
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "edits").get<FieldType::SFString>() ==
        "true false false;inUse;Geospatial:2,NURBS:2;noCategory;RangeError;1 km 1000 kilogram "
        "radian");
  // The edits are the world's statements.
  CHECK(w.scene->x3d.components == std::vector<std::pair<std::string, int>>{{"NURBS", 2}});
  REQUIRE(w.scene->x3d.units.size() == 2);
  CHECK(w.scene->x3d.units[0].category == "length");
  CHECK(w.scene->x3d.units[1].name == "kilogram");
}
