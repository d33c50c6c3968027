// The X3D Followers component (X3D 4.0 clause 39) in the execution model: dampers and
// chasers move on the runtime's clock, so the same times give the same values.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

FieldValue followerVec3(float x, float y, float z) {
  return FieldValue::make<FieldType::SFVec3f>(glm::vec3(x, y, z));
}

glm::vec3 chasedTranslation(const RunningWorld& w) {
  return w.node("T").field("translation")->get<FieldType::SFVec3f>();
}

bool followerSaw(const std::vector<std::string>& events, const std::string& e) {
  return std::find(events.begin(), events.end(), e) != events.end();
}

}  // namespace

TEST_CASE("followers: a PositionChaser reaches its destination in exactly its duration",
          "[runtime][x3d][followers]") {
  RunningWorld w(x3dWorld(R"(
DEF C PositionChaser { duration 2 }
DEF T Transform {}
ROUTE C.value_changed TO T.set_translation
)"),
                 100.0);
  w.take();
  w.send("C", "set_destination", followerVec3(4, 0, 0));
  CHECK(followerSaw(w.take(), "C.isActive=TRUE"));
  w.model->advanceTo(101.0);  // half way: the smooth step is at 0.5
  CHECK(chasedTranslation(w).x == Approx(2.0f).margin(1e-4));
  w.model->advanceTo(100.5);  // time never goes back: nothing changes
  CHECK(chasedTranslation(w).x == Approx(2.0f).margin(1e-4));
  w.model->advanceTo(101.5);  // (1 - cos(0.75 pi)) / 2 of the way
  CHECK(chasedTranslation(w).x ==
        Approx(4.0 * (0.5 - 0.5 * std::cos(0.75 * 3.14159265358979))).margin(1e-4));
  w.take();
  w.model->advanceTo(102.0);
  CHECK(chasedTranslation(w).x == Approx(4.0f));
  CHECK(followerSaw(w.take(), "C.isActive=FALSE"));
  w.model->advanceTo(103.0);  // at rest: no more events
  CHECK(w.take().empty());
}

TEST_CASE("followers: a new destination while chasing blends in from where the value is",
          "[runtime][x3d][followers]") {
  RunningWorld w(x3dWorld(R"(
DEF C ScalarChaser { duration 1 }
DEF S Script { inputOnly SFFloat set_value url "ecmascript: function set_value(v) {}" }
ROUTE C.value_changed TO S.set_value
)"),
                 0.0);
  w.send("C", "set_destination", FieldValue::make<FieldType::SFFloat>(10.0f));
  w.model->advanceTo(0.5);
  const float half = w.node("C").field("value_changed")->get<FieldType::SFFloat>();
  CHECK(half == Approx(5.0f).margin(1e-4));
  w.send("C", "set_destination", FieldValue::make<FieldType::SFFloat>(0.0f));
  w.model->advanceTo(0.75);  // still continuous: between the two destinations
  const float v = w.node("C").field("value_changed")->get<FieldType::SFFloat>();
  CHECK(v > 0.0f);
  CHECK(v < 10.0f);
  w.model->advanceTo(1.5);  // the second change completes duration after it was made
  CHECK(w.node("C").field("value_changed")->get<FieldType::SFFloat>() == Approx(0.0f).margin(1e-5));
}

TEST_CASE("followers: a PositionDamper approaches exponentially and stops within tolerance",
          "[runtime][x3d][followers]") {
  RunningWorld w(x3dWorld(R"(
DEF D PositionDamper { tau 0.5 order 1 tolerance 0.01 }
DEF T Transform {}
ROUTE D.value_changed TO T.set_translation
)"),
                 0.0);
  w.send("D", "set_destination", followerVec3(0, 1, 0));
  w.model->advanceTo(0.5);  // one stage: 1 - exp(-dt / tau) of the way, dt = tau
  CHECK(chasedTranslation(w).y == Approx(1.0 - std::exp(-1.0)).margin(1e-5));
  w.model->advanceTo(1.0);
  CHECK(chasedTranslation(w).y == Approx(1.0 - std::exp(-2.0)).margin(1e-5));
  w.take();
  for (int i = 1; i <= 40; ++i) w.model->advanceTo(1.0 + 0.1 * i);
  CHECK(chasedTranslation(w).y == Approx(1.0f));  // snapped once within 0.01
  CHECK(followerSaw(w.take(), "D.isActive=FALSE"));
}

TEST_CASE("followers: damper order, tau 0, set_value and initial values",
          "[runtime][x3d][followers]") {
  RunningWorld w(x3dWorld(R"(
DEF D3 ScalarDamper { tau 1 }
DEF D0 ScalarDamper { tau 0 }
DEF I ColorDamper { initialValue 1 0 0 initialDestination 0 0 1 tau 0.2 }
DEF O OrientationChaser { duration 1 }
)"),
                 0.0);
  w.send("D3", "set_destination", FieldValue::make<FieldType::SFFloat>(1.0f));
  w.send("D0", "set_destination", FieldValue::make<FieldType::SFFloat>(1.0f));
  w.send("O", "set_destination",
         FieldValue::make<FieldType::SFRotation>(gs::vrml::Rotation(0, 0, 1, 3.14159265f / 2)));
  w.model->advanceTo(1.0);
  // Three stages after one tau: well behind one stage's 1 - 1/e.
  const float third = w.node("D3").field("value_changed")->get<FieldType::SFFloat>();
  CHECK(third > 0.0f);
  CHECK(third < 1.0f - std::exp(-1.0f) - 0.2f);
  CHECK(w.node("D0").field("value_changed")->get<FieldType::SFFloat>() == 1.0f);
  // The initial value moves to the initial destination by itself.
  const glm::vec3 c = w.node("I").field("value_changed")->get<FieldType::SFColor>();
  CHECK(c.b > 0.9f);
  CHECK(c.r < 0.1f);
  // The chaser turned a quarter turn about z in its duration.
  const auto r = w.node("O").field("value_changed")->get<FieldType::SFRotation>();
  CHECK(std::abs(r.z) == Approx(1.0f).margin(1e-4));
  CHECK(r.w * (r.z < 0 ? -1.0f : 1.0f) == Approx(3.14159265f / 2).margin(1e-4));
  // set_value jumps, then the damper moves on towards its destination.
  w.send("D3", "set_value", FieldValue::make<FieldType::SFFloat>(-5.0f));
  CHECK(w.node("D3").field("value_changed")->get<FieldType::SFFloat>() == -5.0f);
  w.model->advanceTo(2.0);
  const float after = w.node("D3").field("value_changed")->get<FieldType::SFFloat>();
  CHECK(after > -5.0f);
  CHECK(after < 1.0f);
}

TEST_CASE("followers: hostile values neither crash nor hang", "[runtime][x3d][followers]") {
  RunningWorld w(x3dWorld(R"(
DEF D PositionDamper { order 99 tau -1 tolerance -5 }
DEF C CoordinateChaser { duration -3 initialValue [ 0 0 0 ] }
DEF N ScalarDamper { tau 1e300 }
)"),
                 0.0);
  const float nan = std::nanf("");
  w.send("D", "set_destination", followerVec3(nan, 1e30f, -1e30f));
  w.send("N", "set_destination", FieldValue::make<FieldType::SFFloat>(nan));
  // A coordinate list of another length jumps; then many long changes stay bounded.
  w.send("C", "set_destination",
         FieldValue::make<FieldType::MFVec3f>(std::vector<glm::vec3>(3, glm::vec3(1.0f))));
  for (int i = 0; i < 300; ++i)
    w.send("C", "set_destination",
           FieldValue::make<FieldType::MFVec3f>(
               std::vector<glm::vec3>(3, glm::vec3(static_cast<float>(i)))));
  for (int f = 1; f <= 10; ++f) w.model->advanceTo(0.1 * f);
  CHECK(w.node("C").field("value_changed")->get<FieldType::MFVec3f>().size() == 3);
  CHECK(w.node("C").field("value_changed")->get<FieldType::MFVec3f>()[0].x == 299.0f);
  CHECK(w.node("D").field("value_changed")->get<FieldType::SFVec3f>().y == 1e30f);
}
