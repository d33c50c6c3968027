// 6.8 Collision: collideTime when the avatar meets a Collision's children or proxy
// (ExecutionModel::collided; scene::walkStep decides the meeting).
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::test::RunningWorld;

TEST_CASE("Collision sends collideTime at now, routed like any eventOut", "[runtime][collision]") {
  RunningWorld w(R"(
DEF OUTER Collision { children DEF C Collision { children Shape { geometry Box {} } } }
DEF T TimeSensor { enabled FALSE }
DEF G Group {}
ROUTE C.collideTime TO T.set_startTime
)");
  w.model->advanceTo(5.0);
  w.take();
  w.model->collided({&w.node("OUTER"), &w.node("C")});
  CHECK(w.take() == std::vector<std::string>{"OUTER.collideTime=5.000", "C.collideTime=5.000",
                                             "T.startTime_changed=5.000"});
  // Not Collision nodes, or none: nothing.
  w.model->collided({&w.node("G")});
  w.model->collided({});
  CHECK(w.take().empty());
  // A later collision, a later time.
  w.model->advanceTo(6.5);
  w.take();
  w.model->collided({&w.node("C")});
  CHECK(w.take() == std::vector<std::string>{"C.collideTime=6.500", "T.startTime_changed=6.500"});
}
