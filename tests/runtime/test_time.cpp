// Clause 4.11 and 6.50: TimeSensor rules, the time-dependent logic, the clock.
#include "runtime/time_dependent.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using gs::runtime::evaluateTime;
using gs::runtime::TimeFields;
using gs::runtime::TimeState;
using gs::runtime::TimeStep;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

TEST_CASE("time: a one-shot cycle activates, runs and ends with fraction 1", "[runtime][time]") {
  TimeFields f;
  f.startTime = 10.0;
  f.cycleInterval = 2.0;
  TimeState s;
  CHECK_FALSE(evaluateTime(s, f, 9.0).output);
  auto a = evaluateTime(s, f, 10.0);
  CHECK((a.activated && a.newCycle && a.output));
  CHECK(a.cycleTime == 10.0);
  CHECK(a.fraction == 0.0);
  auto b = evaluateTime(s, f, 11.5);
  CHECK_FALSE(b.activated);
  CHECK(b.fraction == Approx(0.75));
  auto c = evaluateTime(s, f, 12.5);
  CHECK((c.deactivated && c.output));
  CHECK(c.fraction == 1.0);
  CHECK_FALSE(s.active);
  CHECK_FALSE(evaluateTime(s, f, 13.0).activated);  // past its cycle: stays inactive
}

TEST_CASE("time: a looping sensor with startTime 0 counts its phase from 1970", "[runtime][time]") {
  TimeFields f;
  f.loop = true;
  f.cycleInterval = 4.0;
  TimeState s;
  const double now = 1.7e9 + 1.0;  // 1.7e9 is a multiple of 4
  auto a = evaluateTime(s, f, now);
  CHECK(a.activated);
  CHECK(a.fraction == Approx(0.25));
  CHECK(a.cycleTime == 1.7e9);
  auto b = evaluateTime(s, f, now + 3.5);  // crosses into the next cycle
  CHECK(b.newCycle);
  CHECK(b.cycleTime == 1.7e9 + 4.0);
  CHECK(b.fraction == Approx(0.125));
}

TEST_CASE("time: stopTime, enabled and invalid cycles", "[runtime][time]") {
  TimeFields f;
  f.loop = true;
  f.startTime = 0.0;
  f.stopTime = 5.0;
  TimeState s;
  CHECK(evaluateTime(s, f, 4.5).activated);
  auto stop = evaluateTime(s, f, 6.0);
  CHECK(stop.deactivated);
  CHECK(stop.fraction == 1.0);  // at stopTime 5, the end of cycle 4
  CHECK_FALSE(evaluateTime(s, f, 7.0).activated);
  TimeFields d;
  d.loop = true;
  d.enabled = false;
  TimeState s2;
  CHECK_FALSE(evaluateTime(s2, d, 1.0).activated);
  TimeFields bad;
  bad.cycleInterval = 0.0;
  bad.loop = true;
  TimeState s3;
  CHECK_FALSE(evaluateTime(s3, bad, 1.0).activated);
  // A tiny cycleInterval: more cycles than int64 counts, clamped (UBSan would flag the
  // conversion; tests/data/regressions/gltf_scene).
  TimeFields tiny;
  tiny.cycleInterval = 1e-38;
  tiny.loop = true;
  TimeState s4;
  const TimeStep t4 = evaluateTime(s4, tiny, 5.0);
  CHECK(t4.activated);
  CHECK(std::isfinite(t4.cycleTime));
}

TEST_CASE("TimeSensor: events in order, isActive only on change", "[runtime][time]") {
  RunningWorld w("DEF T TimeSensor { startTime 1 cycleInterval 2 }", 0.0);
  CHECK(w.take().empty());
  w.model->advanceTo(1.5);
  CHECK(w.take() == std::vector<std::string>{"T.isActive=TRUE", "T.cycleTime=1.000",
                                             "T.fraction_changed=0.25", "T.time=1.500"});
  w.model->advanceTo(2.0);
  CHECK(w.take() == std::vector<std::string>{"T.fraction_changed=0.5", "T.time=2.000"});
  w.model->advanceTo(4.0);
  CHECK(w.take() ==
        std::vector<std::string>{"T.fraction_changed=1", "T.time=4.000", "T.isActive=FALSE"});
  w.model->advanceTo(5.0);
  CHECK(w.take().empty());
}

TEST_CASE("TimeSensor: set_startTime is ignored while active, starts it when not",
          "[runtime][time]") {
  RunningWorld w("DEF T TimeSensor { cycleInterval 10 }", 100.0);
  CHECK(w.take().empty());  // startTime 0, not looping: its cycle ended long ago
  w.send("T", "set_startTime", FieldValue::make<FieldType::SFTime>(100.0));
  auto started = w.take();
  REQUIRE(started.size() >= 2);
  CHECK(started[0] == "T.startTime_changed=100.000");
  CHECK(started[1] == "T.isActive=TRUE");
  w.model->advanceTo(101.0);
  w.take();
  w.send("T", "set_startTime", FieldValue::make<FieldType::SFTime>(105.0));
  CHECK(w.take().empty());
  CHECK(w.node("T").field("startTime")->get<FieldType::SFTime>() == 100.0);
}

TEST_CASE("TimeSensor drives an interpolator and a Transform at a fixed time", "[runtime][time]") {
  const char* world = R"(
DEF T TimeSensor { cycleInterval 4 loop TRUE }
DEF P PositionInterpolator { key [0 1] keyValue [0 0 0, 4 0 0] }
DEF X Transform {}
ROUTE T.fraction_changed TO P.set_fraction
ROUTE P.value_changed TO X.set_translation
)";
  RunningWorld w(world, 1.0);
  CHECK(w.node("X").field("translation")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
  w.model->advanceBy(1.5, 1.0 / 60.0);
  CHECK(w.node("X").field("translation")->get<FieldType::SFVec3f>().x == Approx(2.5));
  // The same time reached in one step gives the same value.
  RunningWorld w2(world, 2.5);
  CHECK(w2.node("X").field("translation")->get<FieldType::SFVec3f>().x == Approx(2.5));
}
