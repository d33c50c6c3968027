// Clause 4.10: routes, fan-out, fan-in, loops, aliases, routes made at run time.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <memory>

using namespace gs;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

FieldValue vec3(float x, float y, float z) {
  return FieldValue::make<FieldType::SFVec3f>(glm::vec3(x, y, z));
}

}  // namespace

TEST_CASE("runtime: an exposedField event fans out along every route, once", "[runtime]") {
  RunningWorld w(R"(
DEF A Transform {}
DEF B Transform {}
DEF C Transform {}
ROUTE A.translation_changed TO B.set_translation
ROUTE A.translation TO C.translation
)");
  w.take();
  w.send("A", "set_translation", vec3(1, 2, 3));
  CHECK(w.take() == std::vector<std::string>{"A.translation_changed=1 2 3",
                                             "B.translation_changed=1 2 3",
                                             "C.translation_changed=1 2 3"});
  const auto& b = w.node("B").field("translation")->get<FieldType::SFVec3f>();
  CHECK(b == glm::vec3(1, 2, 3));
  CHECK(w.node("B").revision() == 1);
}

TEST_CASE("runtime: a ROUTE loop sends each eventOut once per timestamp", "[runtime]") {
  RunningWorld w(R"(
DEF A Transform {}
DEF B Transform {}
ROUTE A.translation_changed TO B.set_translation
ROUTE B.translation_changed TO A.set_translation
)");
  w.take();
  w.send("A", "set_translation", vec3(1, 0, 0));
  CHECK(w.take() ==
        std::vector<std::string>{"A.translation_changed=1 0 0", "B.translation_changed=1 0 0"});
  CHECK(w.model->statistics().eventsDropped == 1);
  // A new timestamp: the loop runs once more and ends again.
  w.send("B", "set_translation", vec3(2, 0, 0));
  CHECK(w.take() ==
        std::vector<std::string>{"B.translation_changed=2 0 0", "A.translation_changed=2 0 0"});
}

TEST_CASE("runtime: fan-in delivers both events to one eventIn", "[runtime]") {
  RunningWorld w(R"(
DEF A Transform {}
DEF B Transform {}
DEF C Transform {}
ROUTE A.translation_changed TO C.set_translation
ROUTE B.translation_changed TO C.set_translation
)");
  w.take();
  w.model->postEvent(w.node("A"), RunningWorld::field(w.node("A"), "translation"), vec3(1, 0, 0));
  w.model->postEvent(w.node("B"), RunningWorld::field(w.node("B"), "translation"), vec3(2, 0, 0));
  w.model->processEvents();
  // C's eventOut fires once in this timestamp (4.10.3): the first value gets through.
  CHECK(w.take() == std::vector<std::string>{"A.translation_changed=1 0 0",
                                             "B.translation_changed=2 0 0",
                                             "C.translation_changed=1 0 0"});
  CHECK(w.node("C").field("translation")->get<FieldType::SFVec3f>() == glm::vec3(2, 0, 0));
}

TEST_CASE("runtime: routes added and deleted at run time", "[runtime]") {
  RunningWorld w(R"(
DEF A Transform {}
DEF B Transform {}
)");
  auto a = w.scene->rootNodes[0];
  auto b = w.scene->rootNodes[1];
  CHECK_FALSE(w.model->addRoute(a, "translation_changed", b, "set_rotation"));  // types differ
  REQUIRE(w.model->addRoute(a, "translation_changed", b, "set_translation"));
  w.take();
  w.send("A", "translation", vec3(0, 1, 0));
  CHECK(w.take().size() == 2);
  REQUIRE(w.model->deleteRoute(a, "translation_changed", b, "set_translation"));
  w.send("A", "translation", vec3(0, 2, 0));
  CHECK(w.take() == std::vector<std::string>{"A.translation_changed=0 2 0"});
}

TEST_CASE("runtime: set_x eventIns of plain nodes write field x", "[runtime]") {
  RunningWorld w(R"(
Shape { geometry DEF F IndexedFaceSet { coordIndex [0 1 2] } }
)");
  w.send("F", "set_coordIndex",
         FieldValue::make<FieldType::MFInt32>(std::vector<std::int32_t>{2, 1, 0, -1}));
  CHECK(w.node("F").field("coordIndex")->get<FieldType::MFInt32>() ==
        std::vector<std::int32_t>{2, 1, 0, -1});
  CHECK(w.node("F").revision() == 1);
}

TEST_CASE("runtime: addChildren and removeChildren", "[runtime]") {
  RunningWorld w(R"(
DEF G Group { children [ DEF S1 Shape {} ] }
DEF H Group { children [ DEF S2 Shape {} ] }
)");
  auto s2 = w.scene->rootNodes[1]->mfnode("children")[0];
  w.send("G", "addChildren", FieldValue::make<FieldType::MFNode>(std::vector{s2, s2}));
  CHECK(w.node("G").mfnode("children").size() == 2);
  w.send("G", "removeChildren", FieldValue::make<FieldType::MFNode>(std::vector{s2}));
  CHECK(w.node("G").mfnode("children").size() == 1);
}

TEST_CASE("runtime: OutlineGroup is a grouping node: addChildren and removeChildren",
          "[runtime][outline]") {
  // Regression: the runtime kept its own list of grouping nodes without OutlineGroup, so
  // these events were dropped silently; the node model's X3DGroupingNode decides now.
  RunningWorld w(R"(
DEF G OutlineGroup { groupId 0 children [ DEF S1 Shape {} ] }
DEF H Group { children [ DEF S2 Shape {} ] }
)");
  auto s2 = w.scene->rootNodes[1]->mfnode("children")[0];
  w.send("G", "addChildren", FieldValue::make<FieldType::MFNode>(std::vector{s2}));
  CHECK(w.node("G").mfnode("children").size() == 2);
  w.send("G", "removeChildren", FieldValue::make<FieldType::MFNode>(std::vector{s2}));
  CHECK(w.node("G").mfnode("children").size() == 1);
}

TEST_CASE("runtime: events to a PROTO instance reach the IS-connected body field", "[runtime]") {
  RunningWorld w(R"(
PROTO Mover [ exposedField SFVec3f where 0 0 0 ] {
  Transform { translation IS where children Shape {} }
}
DEF M Mover {}
DEF SRC Transform {}
ROUTE SRC.translation_changed TO M.set_where
)");
  w.send("SRC", "translation", vec3(5, 0, 0));
  CHECK(w.scene->rootNodes[0]->field("translation")->get<FieldType::SFVec3f>() ==
        glm::vec3(5, 0, 0));
}

TEST_CASE("runtime: a node freed by a children assignment lends its record to no later node",
          "[runtime][identity]") {
  // Node identity (the owners issue): the execution model keys its records by address.
  // A PositionInterpolator dropped from the graph must not hand its role, field indices
  // and routes to a Transform that createVrmlFromString allocates at the same address.
  RunningWorld w(R"(
DEF G Group { children [ DEF I PositionInterpolator { key [ 0 1 ] keyValue [ 0 0 0, 1 1 1 ] } ] }
)");
  std::weak_ptr<gs::vrml::Node> dropped = w.node("G").mfnode("children").at(0);
  std::uintptr_t droppedAt = reinterpret_cast<std::uintptr_t>(dropped.lock().get());
  w.send("G", "set_children",
         FieldValue::make<FieldType::MFNode>(std::vector<gs::vrml::NodePtr>{}));
  REQUIRE(w.node("G").mfnode("children").empty());
  // The model keeps what it registered alive, so the address cannot be reused.
  CHECK_FALSE(dropped.expired());
  bool reused = false;
  for (int i = 0; i < 64; ++i) {
    std::vector<gs::vrml::NodePtr> made = w.model->createVrmlFromString("Transform { }");
    REQUIRE(made.size() == 1);
    gs::vrml::Node& t = *made[0];
    reused = reused || reinterpret_cast<std::uintptr_t>(&t) == droppedAt;
    const int field = RunningWorld::field(t, "set_translation");
    REQUIRE(w.model->postEvent(t, field, vec3(1, 2, 3)));
    w.model->processEvents();
    CHECK(t.field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 2, 3));
  }
  CHECK_FALSE(reused);
}

TEST_CASE("runtime: untraced, an unrouted eventOut is counted and a route added later carries",
          "[runtime]") {
  // Without a trace hook, an eventOut that never had a route skips its port (the fast path
  // of State::emit); a route added at run time must still carry the next event.
  auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#VRML V2.0 utf8
DEF A Transform {}
DEF B Transform {}
DEF C Transform {}
ROUTE B.translation_changed TO C.set_translation
)",
                                                             "test.wrl"));
  runtime::ExecutionModel model(scene, 0.0);
  vrml::Node& a = *scene->rootNodes[0];
  vrml::Node& b = *scene->rootNodes[1];
  vrml::Node& c = *scene->rootNodes[2];
  const int translation = a.type().findField("translation");
  const auto sent = model.statistics().eventsSent;
  model.postEvent(a, translation, vec3(1, 0, 0));
  model.processEvents();
  CHECK(model.statistics().eventsSent == sent + 1);  // A's, to nowhere
  CHECK(b.field("translation")->get<FieldType::SFVec3f>() == glm::vec3(0, 0, 0));
  REQUIRE(model.addRoute(scene->rootNodes[0], "translation_changed", scene->rootNodes[1],
                         "set_translation"));
  model.postEvent(a, translation, vec3(2, 0, 0));
  model.processEvents();
  CHECK(b.field("translation")->get<FieldType::SFVec3f>() == glm::vec3(2, 0, 0));
  CHECK(c.field("translation")->get<FieldType::SFVec3f>() == glm::vec3(2, 0, 0));
  CHECK(model.statistics().eventsSent == sent + 4);  // A's, then A's, B's and C's
}
