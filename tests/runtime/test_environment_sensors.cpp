// 6.38 ProximitySensor and 6.52 VisibilitySensor against the viewer's pose.
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
