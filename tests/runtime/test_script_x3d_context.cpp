// A Script edits its scene's own tables (ISO/IEC 19777-1 clause 7.4.11, X3DExecutionContext
// and X3DScene, with X_ITE 15's names): named nodes, META statements, EXPORTs, the ROUTE
// list; Browser.replaceWorld unloads the old world (its Scripts see shutdown(), its
// TimeSensors stop); a Script in an Inline's world adds root nodes to that world. Small X3D
// worlds run by the execution model; the Scripts' outputs are read back from their nodes.
#include "x3d_script_support.hpp"

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

TEST_CASE("X3D Script: named nodes, META statements and EXPORTs of its scene", "[script][x3d]") {
  RunningWorld w(WorldText{R"(#X3D V4.0 utf8
PROFILE Interchange
META "author" "A"
DEF G Group { children DEF H Transform { } }
DEF S Script {
  outputOnly SFString meta
  outputOnly SFString names
  outputOnly SFString exports
  url "ecmascript:
    function initialize() {
      var s = Browser.currentScene;
      var a = s.getMetaData('author');
      s.setMetaData('k', ['1', '2']);
      s.addMetaData('k', 3);
      s.setMetaData('one', 'x');
      s.removeMetaData('author');
      meta = a.join() + ' ' + s.getMetaData('k').join() + ' ' + s.getMetaData('one').join() + ' ' +
             (s.getMetaData('author') === undefined);
      var made = s.createNode('Shape'), g = s.getNamedNode('G');
      var keys = Object.keys(s.namedNodes).join();
      names = keys + ';';
      try { s.addNamedNode('H', made); } catch (e) { names += 'inUse '; }
      s.addNamedNode('N', made);
      s.updateNamedNode('G2', g);
      names += (s.getNamedNode('N') === made) + ' ' + (s.getNamedNode('G2') === g) + ' ' +
               g.getNodeName() + ';';
      s.removeNamedNode('H');
      try { s.getNamedNode('H'); } catch (e) { names += 'H gone'; }
      s.addExportedNode('E', g);
      exports = String(s.getExportedNode('E') === g);
      try { s.addExportedNode('E', made); } catch (e) { exports += ' inUse'; }
      s.updateExportedNode('E', made);
      exports += ' ' + (s.getExportedNode('E') === made);
      s.removeExportedNode('E');
      try { s.getExportedNode('E'); } catch (e) { exports += ' gone'; }
    }
  "
}
)",
                           "test.x3dv"},
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "meta").get<FieldType::SFString>() == "A 1,2,3 x true");
  CHECK(outOf(w, "names").get<FieldType::SFString>() == "G,H,S;inUse true true Group;H gone");
  CHECK(outOf(w, "exports").get<FieldType::SFString>() == "true inUse true gone");
  // The edits are the world's: its META statements, its nodes' DEF names.
  std::vector<std::pair<std::string, std::string>> meta = w.scene->x3d.meta;
  CHECK(meta == std::vector<std::pair<std::string, std::string>>{
                    {"k", "1"}, {"k", "2"}, {"k", "3"}, {"one", "x"}});
  CHECK(w.scene->rootNodes.at(0)->defName == "G2");
  CHECK(w.scene->x3d.exports.empty());
}

TEST_CASE("X3D Script: routes lists the scene's ROUTEs still in place", "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF T TimeSensor { }
DEF P PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 1 0 0 ] }
DEF X Transform { }
DEF S Script {
  outputOnly SFString listed
  url "ecmascript:
    function text(s) {
      return s.routes.map(function (r) {
        return r.sourceNode.getNodeName() + '.' + r.sourceField + '>' +
               r.destinationNode.getNodeName() + '.' + r.destinationField;
      }).join(' ');
    }
    function initialize() {
      var s = Browser.currentScene;
      listed = text(s) + ' | ';
      var t = s.getNamedNode('T'), p = s.getNamedNode('P'), x = s.getNamedNode('X');
      var r = s.addRoute(p, 'value_changed', x, 'set_scale');
      s.deleteRoute(t, 'fraction_changed', p, 'set_fraction');
      listed += text(s) + ' | ';
      s.deleteRoute(r);
      listed += s.routes.length;
    }
  "
}
ROUTE T.fraction_changed TO P.set_fraction
ROUTE P.value_changed TO X.set_translation
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "listed").get<FieldType::SFString>() ==
        "TimeSensor.fraction_changed>PositionInterpolator.set_fraction "
        "PositionInterpolator.value_changed>Transform.set_translation | "
        "PositionInterpolator.value_changed>Transform.set_translation "
        "PositionInterpolator.value_changed>Transform.set_scale | 1");
  // The deleted route stays deleted when the world grows (the model reads the file's list
  // again from where it was; the Script's routes are kept apart).
  w.model->sceneGrew();
  w.send("P", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(w.node("X").field("translation")->get<FieldType::SFVec3f>() == glm::vec3(0.5f, 0, 0));
  CHECK(w.node("X").field("scale")->get<FieldType::SFVec3f>() == glm::vec3(1, 1, 1));
}

TEST_CASE("Browser.replaceWorld unloads the old world: shutdown(), its TimeSensors stopped",
          "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF OLDT TimeSensor { loop TRUE cycleInterval 4 }
DEF OLDP PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 4 0 0 ] }
DEF OLDX Transform { }
DEF S Script {
  inputOnly SFBool go
  outputOnly SFString down
  url "ecmascript:
    function go(v) {
      Browser.replaceWorld(Browser.createX3DFromString(
        'DEF NEWT TimeSensor { loop TRUE cycleInterval 4 }\\n' +
        'DEF NEWP PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 0 4 0 ] }\\n' +
        'DEF NEWX Transform { }\\n' +
        'ROUTE NEWT.fraction_changed TO NEWP.set_fraction\\n' +
        'ROUTE NEWP.value_changed TO NEWX.set_translation\\n'));
    }
    function shutdown() { down = 'old world unloaded'; }
  "
}
ROUTE OLDT.fraction_changed TO OLDP.set_fraction
ROUTE OLDP.value_changed TO OLDX.set_translation
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  const vrml::NodePtr oldX = w.scene->rootNodes.at(2);
  const vrml::NodePtr script = w.scene->rootNodes.at(3);
  w.model->advanceTo(1.0);
  CHECK(oldX->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  REQUIRE(w.scene->rootNodes.size() == 3);
  const vrml::NodePtr newX = w.scene->rootNodes.at(2);
  CHECK(script->field("down")->get<FieldType::SFString>().empty());  // not during its call
  w.model->advanceTo(2.0);
  CHECK(script->field("down")->get<FieldType::SFString>() == "old world unloaded");
  // The old world's TimeSensor stopped with it; the new world's runs.
  CHECK(oldX->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  CHECK(newX->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(0, 2, 0));
  // The Script gets no more events: it was shut down.
  REQUIRE(w.model->postEvent(*script, RunningWorld::field(*script, "go"),
                             FieldValue::make<FieldType::SFBool>(true)));
  w.model->processEvents();
  CHECK(w.scene->rootNodes.at(2) == newX);
}

TEST_CASE(
    "Browser.replaceWorld unloads the old world's Inline worlds; a new Inline of the "
    "same world takes it again",
    "[script][x3d]") {
  RunningWorld w(x3dWorld(R"(
DEF IN Inline { url "inner.x3dv" }
DEF S Script {
  inputOnly SFBool go
  url "ecmascript:
    function go(v) { Browser.replaceWorld(Browser.createX3DFromString('Group { }')); }
  "
}
)"),
                 0.0, x3dScripts());
  auto inner = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
DEF T TimeSensor { loop TRUE cycleInterval 4 }
DEF P PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 4 0 0 ] }
DEF X Transform { }
DEF L Script {
  outputOnly SFString log
  url "ecmascript:
    var text = '';
    function initialize() { text += 'up '; log = text; }
    function shutdown() { text += 'down '; log = text; }
  "
}
ROUTE T.fraction_changed TO P.set_fraction
ROUTE P.value_changed TO X.set_translation
)",
                                                             "file:///worlds/inner.x3dv"));
  // As session::WorldRuntimes::addInlines does once a frame has loaded the Inline.
  const vrml::NodePtr inlineNode = w.scene->rootNodes.at(0);
  w.model->noteInlineWorld(*inlineNode, inner.get());
  w.model->addInlineScene(inner);
  INFO(modelDiagnostics(w));
  const vrml::NodePtr x = inner->rootNodes.at(2), log = inner->rootNodes.at(3);
  w.model->advanceTo(1.0);
  CHECK(x->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  CHECK(log->field("log")->get<FieldType::SFString>() == "up ");
  // The Inline goes with the world: its world's Script is shut down, its TimeSensor stops.
  w.send("S", "go", FieldValue::make<FieldType::SFBool>(true));
  w.model->advanceTo(2.0);
  CHECK(log->field("log")->get<FieldType::SFString>() == "up down ");
  CHECK(x->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  // The traversal still lists the world it loaded once: not taken again for that.
  w.model->addInlineScene(inner);
  w.model->advanceTo(3.0);
  CHECK(x->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  // A new world whose Inline shows the same world (the session shares it): it runs again,
  // its Script initialized afresh.
  // (S went with the first world: the browser replaces this one.)
  w.model->replaceWorld(w.model->createVrmlFromString("Inline { url \"inner.x3dv\" }"));
  w.model->advanceTo(3.5);
  REQUIRE(w.scene->rootNodes.size() == 1);
  w.model->noteInlineWorld(*inlineNode, inner.get());  // the old node, still listed
  w.model->noteInlineWorld(*w.scene->rootNodes.at(0), inner.get());
  w.model->addInlineScene(inner);
  CHECK(log->field("log")->get<FieldType::SFString>() == "up ");  // a new instance's text
  w.model->advanceTo(4.5);
  CHECK(x->field("translation")->get<FieldType::SFVec3f>() == glm::vec3(0.5f, 0, 0));
}

TEST_CASE("X3D Script: a Script in an Inline's world adds and removes that world's roots",
          "[script][x3d]") {
  RunningWorld w(x3dWorld("DEF Outer Group { }\n"), 0.0, x3dScripts());
  // Made as the Inline loader makes an Inline's world: no const object.
  auto inner = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
DEF Inner Transform { }
DEF S Script {
  outputOnly SFString counts
  url "ecmascript:
    function initialize() {
      var scene = Browser.currentScene;
      var added = scene.createNode('Group');
      scene.addRootNode(added);
      counts = scene.rootNodes.length + ' ';
      scene.removeRootNode(scene.getNamedNode('Inner'));
      counts += scene.rootNodes.length + ' ' + (scene.rootNodes[1] === added);
    }
  "
}
)",
                                                             "file:///worlds/inner.x3dv"));
  w.model->addInlineScene(inner);
  INFO(modelDiagnostics(w));
  const vrml::NodePtr& script = inner->rootNodes.at(0);
  REQUIRE(script->field("counts") != nullptr);
  CHECK(script->field("counts")->get<FieldType::SFString>() == "3 2 true");
  REQUIRE(inner->rootNodes.size() == 2);
  CHECK(inner->rootNodes[1]->typeName() == "Group");
  CHECK(w.scene->rootNodes.size() == 1);  // the browser's world is unchanged
}

TEST_CASE("createVrmlFromURL: the text read resolves and reads under its own URL's rules",
          "[script][url]") {
  // A local world's Script reads a text from the network: the Script in that text names a
  // local file first, then a file beside the text. The text is remote content, so the
  // local file is refused (before, the text took the asking world's URL and rules, and
  // read it) and the relative name resolves beside the text.
  std::vector<std::string> asked;
  base::CallbackFetcher fetcher([&](const std::string& url, const std::string&, base::FetchMode) {
    asked.push_back(url);
    if (url == "http://example.com/r/made.wrl")
      return base::fetchReady(
          "#VRML V2.0 utf8\nDEF M Script { eventOut SFString out "
          "url [ \"file:///tmp/gs_local_script.js\" \"ok.js\" ] }\n");
    if (url == "file:///tmp/gs_local_script.js")
      return base::fetchReady("function initialize() { out = 'a local file'; }");
    if (url == "http://example.com/r/ok.js")
      return base::fetchReady("function initialize() { out = 'beside the text'; }");
    return base::fetchFailed("cannot read " + url);
  });
  runtime::ExecutionOptions options = x3dScripts();
  options.fetcher = &fetcher;
  RunningWorld w(WorldText{R"(#VRML V2.0 utf8
DEF HOLDER Group { }
DEF S Script {
  field SFNode holder USE HOLDER
  directOutput TRUE
  url "javascript:
    function initialize() {
      Browser.createVrmlFromURL(new MFString('http://example.com/r/made.wrl'), holder, 'addChildren');
    }
  "
}
)",
                           "/home/me/world.wrl"},
                 0.0, options);
  w.model->advanceTo(0.5);  // the made Script's files have answered: it starts
  INFO(modelDiagnostics(w));
  const vrml::Node& holder = w.node("HOLDER");
  const auto& children = holder.field("children")->get<FieldType::MFNode>();
  REQUIRE(children.size() == 1);
  CHECK(children[0]->field("out")->get<FieldType::SFString>() == "beside the text");
  // Its nodes keep the text's URL wherever they are put (an Inline or texture in them
  // resolves and reads by it).
  REQUIRE(children[0]->urlBase);
  CHECK(*children[0]->urlBase == "http://example.com/r/made.wrl");
  CHECK(std::find(asked.begin(), asked.end(), "file:///tmp/gs_local_script.js") == asked.end());
}

TEST_CASE("Browser.loadURL from a Script in an Inline's world links under that world's rules",
          "[script][url]") {
  FakeScriptContext ctx;
  auto s = loadInlineScript(ctx, "/home/me/main.wrl", R"(#VRML V2.0 utf8
DEF S Script {
  url "javascript:
    function initialize() { Browser.loadURL(new MFString('file:///home/me/x.wrl', 'next.wrl', '#V')); }
  "
}
)",
                            "http://example.com/w/inner.wrl");
  REQUIRE(s->instance);
  s->instance->initialize(0.0);
  CHECK(ctx.loaded ==
        std::vector<std::vector<std::string>>{{"http://example.com/w/next.wrl", "#V"}});
  CHECK_THAT(ctx.diagnosticText(), Catch::Contains("may only reference http(s) URLs"));
}

TEST_CASE("hostile Script: a scene's META statements and names are bounded outside its heap",
          "[script][x3d][hostile]") {
  // The tables live outside the Script's heap: values added in a loop end in a RangeError
  // at a quarter of the heap's limit, not in the browser's memory.
  runtime::ExecutionOptions options = x3dScripts();
  options.scriptLimits.heapBytes = 8u * 1024u * 1024u;
  RunningWorld w(x3dWorld(R"(
DEF S Script {
  outputOnly SFString meta
  outputOnly SFString names
  url "ecmascript:
    function initialize() {
      var s = Browser.currentScene, big = new Array(65537).join('x'), i = 0;
      try { for (;;) { s.addMetaData('k', big); ++i; } } catch (e) { meta = e.name + ' ' + i; }
      names = '';
      var node = s.createNode('Group'), long = new Array(1026).join('n');
      try { s.addNamedNode(long, node); } catch (e) { names += e.name + ' '; }
      try { s.addExportedNode(long, node); } catch (e) { names += e.name; }
    }
  "
}
)"),
                 0.0, options);
  INFO(modelDiagnostics(w));
  // 2 MiB of values: 31 of 64 KiB (each with its name).
  CHECK(outOf(w, "meta").get<FieldType::SFString>() == "RangeError 31");
  CHECK(outOf(w, "names").get<FieldType::SFString>() == "RangeError RangeError");
  CHECK(w.scene->x3d.namedNodes.empty());
}

TEST_CASE("X3D Script: code run as its Inline's world loads may add a root to that world",
          "[script][x3d][url]") {
  // The Script's code runs while the world is read: its new root is appended and reached by
  // that read, and the next Script of the (remote) world still has the world's rules.
  base::CallbackFetcher fetcher([&](const std::string& url, const std::string&, base::FetchMode) {
    if (url == "file:///tmp/gs_local_inline.js")
      return base::fetchReady("function initialize() { out = 'a local file'; }");
    return base::fetchFailed("cannot read " + url);
  });
  runtime::ExecutionOptions options = x3dScripts();
  options.fetcher = &fetcher;
  RunningWorld w(x3dWorld("DEF Outer Group { }\n"), 0.0, options);
  auto inner = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
DEF First Script {
  url "ecmascript:
    Browser.currentScene.addRootNode(Browser.currentScene.createNode('Transform'));
  "
}
DEF Second Script { outputOnly SFString out url "file:///tmp/gs_local_inline.js" }
)",
                                                             "http://example.com/w/inner.x3dv"));
  w.model->addInlineScene(inner);
  INFO(modelDiagnostics(w));
  REQUIRE(inner->rootNodes.size() == 3);
  CHECK(inner->rootNodes[2]->typeName() == "Transform");
  CHECK(inner->rootNodes[1]->field("out")->get<FieldType::SFString>().empty());
  CHECK_THAT(modelDiagnostics(w), Catch::Contains("may only reference http(s) URLs"));
  // The file goes on arriving: its next root is taken, not skipped.
  vrml::Scene more = vrml::parseVrml(R"(#X3D V4.0 utf8
DEF Third Script { outputOnly SFString out url "ecmascript: function initialize() { out = 'ran'; }" }
)",
                                     "http://example.com/w/inner.x3dv");
  inner->rootNodes.push_back(more.rootNodes.at(0));
  w.model->sceneGrew();
  CHECK(inner->rootNodes[3]->field("out")->get<FieldType::SFString>() == "ran");
}
