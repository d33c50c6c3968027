// MovieTexture (6.28) and AudioClip (6.3) as time-dependent nodes (4.6.9): the media time
// the runtime computes, duration_changed and isActive through the event cascade.
#include "runtime/media_time.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

using gs::runtime::mediaTimeAt;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;
using Events = std::vector<std::string>;

namespace {

double mediaTimeOf(const RunningWorld& w, const std::string& name) {
  const auto t = w.model->mediaTime(w.node(name));
  REQUIRE(t.has_value());
  return *t;
}

}  // namespace

TEST_CASE("media time: forwards and backwards through a cycle", "[runtime][media]") {
  CHECK(mediaTimeAt(0.25, 2.0, 1.0) == 0.5);
  CHECK(mediaTimeAt(0.25, 2.0, 2.0) == 0.5);  // the cycle is shorter, not the clip
  CHECK(mediaTimeAt(0.25, 2.0, -1.0) == 1.5);
  CHECK(mediaTimeAt(1.0, 2.0, -1.0) == 0.0);
}

TEST_CASE("MovieTexture: nothing plays before the duration is known; then duration_changed",
          "[runtime][media]") {
  RunningWorld w("DEF M MovieTexture { loop TRUE }");
  CHECK(w.take().empty());
  w.model->advanceTo(0.5);
  CHECK(w.take().empty());
  CHECK(mediaTimeOf(w, "M") == 0.0);
  auto state = w.model->media(w.node("M"));
  REQUIRE(state);
  CHECK(state->movie);
  CHECK_FALSE(state->duration);
  CHECK_FALSE(state->active);
  // The decoder found a 2 s clip: duration_changed, and the looping movie starts at once
  // with its phase counted from startTime 0.
  w.model->setMediaDuration(w.node("M"), 2.0);
  CHECK(w.take() == Events{"M.duration_changed=2.000", "M.isActive=TRUE"});
  CHECK(mediaTimeOf(w, "M") == Approx(0.5));
  w.model->setMediaDuration(w.node("M"), 2.0);  // the same value again: no event
  CHECK(w.take().empty());
  w.model->advanceTo(3.25);
  CHECK(w.take().empty());  // isActive only on change
  CHECK(mediaTimeOf(w, "M") == Approx(1.25));
  CHECK(w.model->animating());
  // Not a media node: no media time.
  RunningWorld other("DEF T TimeSensor {}");
  CHECK_FALSE(other.model->mediaTime(other.node("T")));
}

TEST_CASE("MovieTexture: a one-shot movie stops on its last frame, isActive FALSE",
          "[runtime][media]") {
  RunningWorld w("DEF M MovieTexture { startTime 1 }");
  w.model->setMediaDuration(w.node("M"), 2.0);
  CHECK(w.take() == Events{"M.duration_changed=2.000"});
  w.model->advanceTo(1.5);
  CHECK(w.take() == Events{"M.isActive=TRUE"});
  CHECK(mediaTimeOf(w, "M") == Approx(0.5));
  w.model->advanceTo(3.5);
  CHECK(w.take() == Events{"M.isActive=FALSE"});
  CHECK(mediaTimeOf(w, "M") == Approx(2.0));  // the last frame stays
  w.model->advanceTo(10.0);
  CHECK(mediaTimeOf(w, "M") == Approx(2.0));
  CHECK_FALSE(w.model->animating());
}

TEST_CASE("MovieTexture: speed 2 halves the cycle, speed -1 plays backwards", "[runtime][media]") {
  RunningWorld w(R"(DEF F MovieTexture { speed 2 startTime 10 }
DEF B MovieTexture { speed -1 startTime 10 })");
  w.model->setMediaDuration(w.node("F"), 4.0);
  w.model->setMediaDuration(w.node("B"), 4.0);
  CHECK(mediaTimeOf(w, "F") == 0.0);
  CHECK(mediaTimeOf(w, "B") == 4.0);  // inactive, backwards: the last frame (6.28)
  w.take();
  w.model->advanceTo(11.0);
  CHECK(w.take() == Events{"F.isActive=TRUE", "B.isActive=TRUE"});
  CHECK(mediaTimeOf(w, "F") == Approx(2.0));
  CHECK(mediaTimeOf(w, "B") == Approx(3.0));
  // set_speed is ignored while the movie plays.
  w.send("F", "set_speed", FieldValue::make<FieldType::SFFloat>(1.0f));
  CHECK(w.node("F").field("speed")->get<FieldType::SFFloat>() == 2.0f);
  CHECK(w.take().empty());
  w.model->advanceTo(12.0);  // F's 2 s cycle ends
  CHECK(mediaTimeOf(w, "F") == Approx(4.0));
  CHECK_FALSE(w.model->media(w.node("F"))->active);
  CHECK(mediaTimeOf(w, "B") == Approx(2.0));
  w.model->advanceTo(14.5);
  CHECK(mediaTimeOf(w, "B") == Approx(0.0));  // ended on frame 0
  CHECK(w.take() == Events{"F.isActive=FALSE", "B.isActive=FALSE"});
}

TEST_CASE("AudioClip: loop, stopTime and pitch through the runtime", "[runtime][media]") {
  RunningWorld w(R"(DEF A AudioClip { loop TRUE pitch 2 startTime 5 }
DEF T TimeSensor { enabled FALSE }
ROUTE A.isActive TO T.set_enabled)");
  w.model->setMediaDuration(w.node("A"), 3.0);
  CHECK(w.take() == Events{"A.duration_changed=3.000"});
  w.model->advanceTo(5.0);
  CHECK(w.take() == Events{"A.isActive=TRUE", "T.enabled_changed=TRUE"});
  CHECK(mediaTimeOf(w, "A") == 0.0);
  w.model->advanceTo(6.0);  // pitch 2: 2 s of sound in 1 s, a cycle of 1.5 s
  CHECK(mediaTimeOf(w, "A") == Approx(2.0));
  w.model->advanceTo(7.0);  // looped: 0.5 s into the second cycle
  CHECK(mediaTimeOf(w, "A") == Approx(1.0));
  w.send("A", "set_stopTime", FieldValue::make<FieldType::SFTime>(7.25));
  CHECK(w.take() == Events{"A.stopTime_changed=7.250"});
  w.model->advanceTo(7.5);
  CHECK(w.take() == Events{"A.isActive=FALSE", "T.enabled_changed=FALSE"});
  CHECK(mediaTimeOf(w, "A") == Approx(1.5));  // where it stopped: 7.25 s
  // A second start is a new activation, from the clip's beginning.
  w.send("A", "set_startTime", FieldValue::make<FieldType::SFTime>(8.0));
  w.send("A", "set_stopTime", FieldValue::make<FieldType::SFTime>(0.0));
  w.take();
  w.model->advanceTo(8.5);
  CHECK(w.take() == Events{"A.isActive=TRUE", "T.enabled_changed=TRUE"});
  CHECK(mediaTimeOf(w, "A") == Approx(1.0));
}

TEST_CASE("AudioClip: an unreadable clip reports duration -1 and never plays", "[runtime][media]") {
  RunningWorld w("DEF A AudioClip { loop TRUE }");
  w.model->setMediaDuration(w.node("A"), -1.0);
  CHECK(w.take() == Events{"A.duration_changed=-1.000"});
  w.model->advanceTo(2.0);
  CHECK(w.take().empty());
  CHECK_FALSE(w.model->media(w.node("A"))->active);
  // pitch 0 is undefined by 6.3: never active either.
  RunningWorld z("DEF A AudioClip { loop TRUE pitch 0 }");
  z.model->setMediaDuration(z.node("A"), 1.0);
  z.model->advanceTo(1.0);
  CHECK_FALSE(z.model->media(z.node("A"))->active);
}
