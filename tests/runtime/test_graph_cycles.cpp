// The scene graph stays acyclic (X3D 4.0 clause 4.4.2.2): an event that would make a node
// its own descendant is refused with one error per node, whoever sends it (a Script's
// field assignment, addChildren, a ROUTE); fields that name nodes placed elsewhere (a
// Script's own, TransformSensor.targetObject) may name an ancestor.
#include "x3d_script_support.hpp"

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

/// How many of `w`'s model diagnostics say an event was refused for a cycle.
int cycleErrors(const RunningWorld& w) {
  int n = 0;
  for (const auto& d : w.model->diagnostics().items)
    n += d.message.find("a node cannot be among its own descendants") != std::string::npos;
  return n;
}

}  // namespace

TEST_CASE(
    "graph cycles: a Script's assignment that puts a node among its own descendants "
    "is refused",
    "[runtime][script][cycles]") {
  RunningWorld w(x3dWorld(R"(
DEF G Group { children Shape { geometry Box { } } }
DEF T Transform { }
DEF S Script {
  inputOnly SFTime again
  inputOutput SFNode g USE G
  inputOutput SFNode t USE T
  url "ecmascript:
    function initialize() {
      g.children = new MFNode(t);   // G holds T: accepted
      t.children = new MFNode(g);   // T would hold G, which holds T: refused
      g.addChildren = new MFNode(g);  // G itself: refused
    }
    function again() { t.children = new MFNode(g); }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  REQUIRE(w.node("G").mfnode("children").size() == 1);
  CHECK(w.node("G").mfnode("children").at(0).get() == &w.node("T"));
  CHECK(w.node("T").mfnode("children").empty());
  CHECK(cycleErrors(w) == 2);  // one per node
  w.send("S", "again", FieldValue::make<FieldType::SFTime>(1.0));
  CHECK(w.node("T").mfnode("children").empty());
  CHECK(cycleErrors(w) == 2);  // said once
}

TEST_CASE("graph cycles: a ROUTE of children_changed into a child is refused",
          "[runtime][cycles]") {
  RunningWorld w(R"(
DEF OUTER Group { children DEF INNER Group { } }
ROUTE OUTER.children_changed TO INNER.set_children
)");
  w.send("OUTER", "set_children",
         FieldValue::make<FieldType::MFNode>(
             std::vector<vrml::NodePtr>{w.node("OUTER").mfnode("children").at(0)}));
  CHECK(w.node("INNER").mfnode("children").empty());
  CHECK(cycleErrors(w) == 1);
}

TEST_CASE("graph cycles: fields that name nodes elsewhere may name an ancestor",
          "[runtime][script][cycles]") {
  RunningWorld w(x3dWorld(R"(
DEF P Transform { children DEF G Group { } }
DEF S Script {
  inputOutput SFNode p USE P
  inputOutput SFNode g USE G
  outputOnly SFBool done
  url "ecmascript:
    function initialize() {
      var sensor = Browser.currentScene.createNode('TransformSensor');
      sensor.targetObject = p;  // the sensor sits below the node it watches
      g.children = new MFNode(sensor);
      g.addChildren = new MFNode(Browser.currentScene.createNode('Group'));
      p.removeChildren = new MFNode(g);
      p.addChildren = new MFNode(g);
      done = true;
    }
  "
}
)"),
                 0.0, x3dScripts());
  INFO(modelDiagnostics(w));
  CHECK(outOf(w, "done").get<FieldType::SFBool>());
  REQUIRE(w.node("G").mfnode("children").size() == 2);
  CHECK(w.node("G").mfnode("children").at(0)->sfnode("targetObject").get() == &w.node("P"));
  CHECK(w.node("P").mfnode("children").size() == 1);
  CHECK(cycleErrors(w) == 0);
}

TEST_CASE("graph cycles: a field that names an ancestor does not keep the world alive",
          "[runtime][script][cycles]") {
  std::weak_ptr<vrml::Node> watched, script;
  {
    RunningWorld w(x3dWorld(R"(
DEF P Transform { children DEF G Group { } }
DEF S Script {
  inputOutput SFNode p USE P
  inputOutput SFNode g USE G
  url "ecmascript:
    function initialize() {
      var sensor = Browser.currentScene.createNode('TransformSensor');
      sensor.targetObject = p;
      g.children = new MFNode(sensor);
      g.addChildren = new MFNode(Browser.currentScene.getNamedNode('S'));  // S names P
    }
  "
}
)"),
                   0.0, x3dScripts());
    INFO(modelDiagnostics(w));
    REQUIRE(w.node("G").mfnode("children").size() == 2);
    watched = w.scene->rootNodes.at(0);
    script = w.scene->rootNodes.at(1);
  }
  // P holds the sensor and S, which both name P: emptied when the world went.
  CHECK(watched.expired());
  CHECK(script.expired());
}
