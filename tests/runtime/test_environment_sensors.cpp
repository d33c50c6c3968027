// 6.38 ProximitySensor and 6.52 VisibilitySensor against the viewer's pose; X3D's
// TransformSensor against a target node.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::ViewerPose;
using gs::test::RunningWorld;

TEST_CASE("ProximitySensor: enter, move inside, exit", "[runtime][sensor]") {
  RunningWorld w(R"(
Transform { translation 10 0 0 children DEF PS ProximitySensor { size 2 2 2 } }
)");
  w.take();
  ViewerPose v;
  v.position = {10.5f, 0.0f, 0.0f};
  w.model->setViewer(v);
  w.model->advanceTo(1.0);
  CHECK(w.take() == std::vector<std::string>{"PS.isActive=TRUE", "PS.enterTime=1.000",
                                             "PS.position_changed=0.5 0 0",
                                             "PS.orientation_changed=0 0 1 0"});
  w.model->advanceTo(2.0);  // not moved: nothing
  CHECK(w.take().empty());
  v.position = {10.0f, 0.25f, 0.0f};
  w.model->setViewer(v);
  w.model->advanceTo(3.0);
  CHECK(w.take() ==
        std::vector<std::string>{"PS.position_changed=0 0.25 0", "PS.orientation_changed=0 0 1 0"});
  v.position = {0.0f, 0.0f, 0.0f};
  w.model->setViewer(v);
  w.model->advanceTo(4.0);
  CHECK(w.take() == std::vector<std::string>{"PS.isActive=FALSE", "PS.exitTime=4.000"});
}

TEST_CASE("VisibilitySensor: in view and behind the viewer", "[runtime][sensor]") {
  RunningWorld w("DEF VS VisibilitySensor { size 1 1 1 }");
  w.take();
  ViewerPose v;  // at 0 0 10 looking along -Z: the box at the origin is in view
  w.model->setViewer(v);
  w.model->advanceTo(1.0);
  CHECK(w.take() == std::vector<std::string>{"VS.isActive=TRUE", "VS.enterTime=1.000"});
  v.orientation = glm::angleAxis(3.14159265f, glm::vec3(0, 1, 0));  // looking along +Z
  w.model->setViewer(v);
  w.model->advanceTo(2.0);
  CHECK(w.take() == std::vector<std::string>{"VS.isActive=FALSE", "VS.exitTime=2.000"});
}

TEST_CASE("TransformSensor: a target moving through the box, no viewer needed",
          "[runtime][sensor][x3d]") {
  // The sensor's box sits at x = 10 under a Transform; the target is a Transform elsewhere
  // in the graph, moved by events.
  RunningWorld w(gs::test::x3dWorld(R"(
DEF T Transform { children Shape { geometry Box {} } }
Transform { translation 10 0 0 children
  DEF S TransformSensor { size 2 2 2 targetObject USE T } }
)"));
  w.take();
  w.model->advanceTo(1.0);  // the target at the origin: outside
  CHECK(w.take().empty());
  auto move = [&](float x, double t) {
    w.send("T", "set_translation",
           gs::vrml::FieldValue::make<gs::vrml::FieldType::SFVec3f>(glm::vec3(x, 0.0f, 0.0f)));
    w.take();  // T.translation_changed
    w.model->advanceTo(t);
    return w.take();
  };
  CHECK(move(10.5f, 2.0) == std::vector<std::string>{"S.isActive=TRUE", "S.enterTime=2.000",
                                                     "S.position_changed=0.5 0 0",
                                                     "S.orientation_changed=0 0 1 0"});
  CHECK(move(9.75f, 3.0) ==
        std::vector<std::string>{"S.position_changed=-0.25 0 0", "S.orientation_changed=0 0 1 0"});
  CHECK(move(20.0f, 4.0) == std::vector<std::string>{"S.isActive=FALSE", "S.exitTime=4.000"});
}
