// X3D 4.0 clause 27's interpolators in the execution model: NurbsPositionInterpolator
// (27.4.6), NurbsOrientationInterpolator (27.4.5) and NurbsSurfaceInterpolator (27.4.9).
// Expected values are worked out by hand in the comments: an order-2 curve is the polyline
// of its control points, the rational quadratic (1 0 0, 1 1 0, 0 1 0) with weights
// (1, cos 45 degrees, 1), its corner written times its weight (control points are
// homogeneous, geometry/nurbs.hpp), is the unit circle's quarter in the XY plane, the bilinear
// patch of (0 0 0, 1 0 0, 0 1 0, 1 1 1) is S(u, v) = (u, v, uv).
#include "runtime/interpolators_nurbs.hpp"
#include "runtime_fixture.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <string>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

/// Sends set_fraction `f` (SFFloat) to I; the events it caused.
std::vector<std::string> nurbsInterpSend(RunningWorld& w, float f) {
  w.take();
  w.send("I", "set_fraction", FieldValue::make<FieldType::SFFloat>(f));
  return w.take();
}

/// Sends set_fraction `f` to I and reads X.translation (I.value_changed routed there).
glm::vec3 nurbsInterpPositionAt(RunningWorld& w, float f) {
  nurbsInterpSend(w, f);
  return w.node("X").field("translation")->get<FieldType::SFVec3f>();
}

/// Sends set_fraction `f` to I and reads where X.rotation (I.value_changed routed there)
/// turns +Z.
glm::vec3 nurbsInterpTurnedZAt(RunningWorld& w, float f) {
  nurbsInterpSend(w, f);
  const auto r = w.node("X").field("rotation")->get<FieldType::SFRotation>();
  const glm::vec3 axis(r.x, r.y, r.z);
  REQUIRE(glm::length(axis) == Approx(1.0f).epsilon(1e-5));
  return glm::angleAxis(r.w, axis) * glm::vec3(0.0f, 0.0f, 1.0f);
}

/// How many diagnostics of `w`'s model contain `text`.
std::size_t nurbsInterpErrors(const RunningWorld& w, const std::string& text) {
  std::size_t n = 0;
  for (const auto& d : w.model->diagnostics().items)
    if (d.message.find(text) != std::string::npos) ++n;
  return n;
}

void nurbsInterpCheck(const glm::vec3& got, const glm::vec3& want) {
  INFO("got " << got.x << " " << got.y << " " << got.z);
  CHECK(got.x == Approx(want.x).margin(1e-5));
  CHECK(got.y == Approx(want.y).margin(1e-5));
  CHECK(got.z == Approx(want.z).margin(1e-5));
}

constexpr float kNurbsInterpHalfRoot2 = 0.70710678f;

const char* const kNurbsInterpQuarterCircle =
    "order 3 weight [ 1 0.70710678 1 ] controlPoint Coordinate { point [ 1 0 0, "
    "0.70710678 0.70710678 0, 0 1 0 ] }";  // homogeneous: the corner (1, 1, 0) times its weight

}  // namespace

TEST_CASE("NURBS interpolators: an order-2 curve is its polyline; default knots span [0, 1]",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(R"(
DEF I NurbsPositionInterpolator {
  order 2 controlPoint Coordinate { point [ 0 0 0, 1 0 0, 1 1 0 ] }
}
DEF X Transform {}
ROUTE I.value_changed TO X.translation
)"));
  // No knots: 0 0 0.5 1 1 (the uniform ones scaled to [0, 1]); fraction 0.25 is halfway
  // along the first segment.
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.25f), {0.5f, 0.0f, 0.0f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.5f), {1.0f, 0.0f, 0.0f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.75f), {1.0f, 0.5f, 0.0f});
  // Outside [0, 1]: the ends.
  nurbsInterpCheck(nurbsInterpPositionAt(w, -1.0f), {0.0f, 0.0f, 0.0f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 2.0f), {1.0f, 1.0f, 0.0f});
  CHECK(nurbsInterpSend(w, 0.5f) ==
        std::vector<std::string>{"I.value_changed=1 0 0", "X.translation_changed=1 0 0"});
  CHECK(w.model->diagnostics().items.empty());
}

TEST_CASE("NURBS interpolators: a two-point line's midpoint, explicit knots and CoordinateDouble",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(R"(
DEF I NurbsPositionInterpolator {
  order 2 knot [ 0 0 4 4 ] controlPoint CoordinateDouble { point [ 2 0 0, 4 2 6 ] }
}
DEF X Transform {}
ROUTE I.value_changed TO X.translation
)"));
  // Knots 0 0 4 4: the range [0, 4] and the fraction is the knot value: 2 is the midpoint,
  // 0.5 an eighth of the way, past 4 the end.
  nurbsInterpCheck(nurbsInterpPositionAt(w, 2.0f), {3.0f, 1.0f, 3.0f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.5f), {2.25f, 0.25f, 0.75f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 5.0f), {4.0f, 2.0f, 6.0f});
  // Without knots (0 0 1 1), fraction 0.5 is the midpoint.
  RunningWorld plain(x3dWorld(R"(
DEF I NurbsPositionInterpolator { order 2 controlPoint CoordinateDouble { point [ 2 0 0, 4 2 6 ] } }
DEF X Transform {}
ROUTE I.value_changed TO X.translation
)"));
  nurbsInterpCheck(nurbsInterpPositionAt(plain, 0.5f), {3.0f, 1.0f, 3.0f});
}

TEST_CASE("NURBS interpolators: a rational quadratic quarter circle has radius 1",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(std::string("DEF I NurbsPositionInterpolator { ") +
                          kNurbsInterpQuarterCircle +
                          " }\nDEF X Transform {}\nROUTE I.value_changed TO X.translation\n"));
  for (float f = 0.0f; f <= 1.0f; f += 0.125f) {
    const glm::vec3 p = nurbsInterpPositionAt(w, f);
    CHECK(glm::length(p) == Approx(1.0f).epsilon(1e-5));
    CHECK(p.z == Approx(0.0f).margin(1e-6));
  }
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.0f), {1.0f, 0.0f, 0.0f});
  nurbsInterpCheck(nurbsInterpPositionAt(w, 0.5f),
                   {kNurbsInterpHalfRoot2, kNurbsInterpHalfRoot2, 0.0f});  // symmetric
  nurbsInterpCheck(nurbsInterpPositionAt(w, 1.0f), {0.0f, 1.0f, 0.0f});
}

TEST_CASE("NURBS interpolators: the orientation turns +Z onto the tangent, along the circle",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(std::string("DEF I NurbsOrientationInterpolator { ") +
                          kNurbsInterpQuarterCircle +
                          " }\nDEF X Transform {}\nROUTE I.value_changed TO X.rotation\n"));
  // The counter-clockwise circle's tangent at (x, y) is (-y, x, 0).
  nurbsInterpCheck(nurbsInterpTurnedZAt(w, 0.0f), {0.0f, 1.0f, 0.0f});
  nurbsInterpCheck(nurbsInterpTurnedZAt(w, 0.5f),
                   {-kNurbsInterpHalfRoot2, kNurbsInterpHalfRoot2, 0.0f});
  nurbsInterpCheck(nurbsInterpTurnedZAt(w, 1.0f), {-1.0f, 0.0f, 0.0f});
  // At 0: +Z onto +Y is a quarter turn about -X.
  nurbsInterpSend(w, 0.0f);
  const auto r0 = w.node("X").field("rotation")->get<FieldType::SFRotation>();
  nurbsInterpCheck({r0.x, r0.y, r0.z}, {-1.0f, 0.0f, 0.0f});
  CHECK(r0.w == Approx(1.5707963f));
  // Between, the tangent stays perpendicular to the radius.
  RunningWorld p(x3dWorld(std::string("DEF I NurbsPositionInterpolator { ") +
                          kNurbsInterpQuarterCircle +
                          " }\nDEF X Transform {}\nROUTE I.value_changed TO X.translation\n"));
  for (float f = 0.1f; f < 1.0f; f += 0.2f) {
    const glm::vec3 at = nurbsInterpPositionAt(p, f);
    nurbsInterpCheck(nurbsInterpTurnedZAt(w, f), {-at.y, at.x, 0.0f});
  }
}

TEST_CASE("NURBS interpolators: a straight line along +X, a repeated point, a line along -Z",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(R"(
DEF I NurbsOrientationInterpolator {
  order 2 controlPoint Coordinate { point [ 0 0 0, 3 0 0, 3 0 0, 5 0 0 ] }
}
DEF X Transform {}
ROUTE I.value_changed TO X.rotation
)"));
  // z x x = +Y, a quarter turn: (0 1 0 1.5708).
  nurbsInterpSend(w, 0.1f);
  const auto r = w.node("X").field("rotation")->get<FieldType::SFRotation>();
  nurbsInterpCheck({r.x, r.y, r.z}, {0.0f, 1.0f, 0.0f});
  CHECK(r.w == Approx(1.5707963f));
  // The middle segment is a point (no derivative): the direction of its neighbours.
  nurbsInterpCheck(nurbsInterpTurnedZAt(w, 0.5f), {1.0f, 0.0f, 0.0f});
  RunningWorld back(x3dWorld(R"(
DEF I NurbsOrientationInterpolator { order 2 controlPoint Coordinate { point [ 0 0 1, 0 0 -1 ] } }
DEF X Transform {}
ROUTE I.value_changed TO X.rotation
)"));
  nurbsInterpCheck(nurbsInterpTurnedZAt(back, 0.5f), {0.0f, 0.0f, -1.0f});  // a half turn about +Y
}

TEST_CASE("NURBS interpolators: NurbsSurfaceInterpolator's position and normal",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(R"(
DEF I NurbsSurfaceInterpolator {
  uDimension 2 vDimension 2 uOrder 2 vOrder 2
  controlPoint Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 1 ] }
}
DEF P Transform {}
DEF N Transform {}
ROUTE I.position_changed TO P.translation
ROUTE I.normal_changed TO N.translation
)"));
  const auto at = [&](float u, float v) {
    w.take();
    w.send("I", "set_fraction", FieldValue::make<FieldType::SFVec2f>(glm::vec2(u, v)));
    return std::pair{w.node("P").field("translation")->get<FieldType::SFVec3f>(),
                     w.node("N").field("translation")->get<FieldType::SFVec3f>()};
  };
  // S(u, v) = (u, v, uv); dS/du = (1, 0, v), dS/dv = (0, 1, u), their cross (-v, -u, 1).
  auto [p, n] = at(0.5f, 0.5f);
  nurbsInterpCheck(p, {0.5f, 0.5f, 0.25f});
  const float k = 1.0f / std::sqrt(1.5f);
  nurbsInterpCheck(n, {-0.5f * k, -0.5f * k, k});
  std::tie(p, n) = at(1.0f, 0.0f);
  nurbsInterpCheck(p, {1.0f, 0.0f, 0.0f});
  nurbsInterpCheck(n, {0.0f, -1.0f / std::sqrt(2.0f), 1.0f / std::sqrt(2.0f)});
  std::tie(p, n) = at(0.0f, 0.0f);
  nurbsInterpCheck(n, {0.0f, 0.0f, 1.0f});
  CHECK(w.model->diagnostics().items.empty());
  // A patch whose v = 1 edge collapses to a point (a pole): the normal of the plane still.
  RunningWorld pole(x3dWorld(R"(
DEF I NurbsSurfaceInterpolator {
  uDimension 2 vDimension 2 uOrder 2 vOrder 2
  controlPoint Coordinate { point [ 0 0 0, 2 0 0, 1 1 0, 1 1 0 ] }
}
DEF N Transform {}
ROUTE I.normal_changed TO N.translation
)"));
  pole.send("I", "set_fraction", FieldValue::make<FieldType::SFVec2f>(glm::vec2(0.5f, 1.0f)));
  nurbsInterpCheck(pole.node("N").field("translation")->get<FieldType::SFVec3f>(),
                   {0.0f, 0.0f, 1.0f});
}

TEST_CASE("NURBS interpolators: a TimeSensor drives NurbsPositionInterpolator",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(R"(
DEF T TimeSensor { cycleInterval 4 loop TRUE }
DEF I NurbsPositionInterpolator { order 2 controlPoint Coordinate { point [ 0 0 0, 8 0 0 ] } }
DEF X Transform {}
ROUTE T.fraction_changed TO I.set_fraction
ROUTE I.value_changed TO X.translation
)"));
  w.model->advanceTo(1.0);  // fraction 0.25
  nurbsInterpCheck(w.node("X").field("translation")->get<FieldType::SFVec3f>(), {2.0f, 0.0f, 0.0f});
}

TEST_CASE("NURBS interpolators: bad fields give one error and no output", "[runtime][x3d][nurbs]") {
  struct Bad {
    const char* fields;
    const char* message;
  };
  for (const Bad& bad : {
           Bad{"order 2 knot [ 0 1 0.5 2 ] controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "the knots decrease"},
           Bad{"order 2 knot [ 0 0 1 ] controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "3 knots, not the 4"},
           Bad{"order 1 controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }", "order 1 is below 2"},
           Bad{"order 3 controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "fewer than the order"},
           Bad{"order 2 weight [ 1 0 ] controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "a weight is not > 0"},
           Bad{"order 2 weight [ 1 ] controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "1 weights for 2 control points"},
           Bad{"order 2 knot [ 1 1 1 1 ] controlPoint Coordinate { point [ 0 0 0, 1 0 0 ] }",
               "no parameter range"},
           Bad{"order 2", "no control points"},
       }) {
    INFO(bad.fields);
    for (const char* type : {"NurbsPositionInterpolator", "NurbsOrientationInterpolator"}) {
      INFO(type);
      RunningWorld w(x3dWorld(std::string("DEF I ") + type + " { " + bad.fields + " }\n"));
      CHECK(nurbsInterpSend(w, 0.5f).empty());
      CHECK(nurbsInterpSend(w, 0.7f).empty());
      CHECK(w.model->diagnostics().items.size() == 1);
      CHECK(nurbsInterpErrors(w, bad.message) == 1);
    }
  }
  RunningWorld s(x3dWorld(R"(
DEF I NurbsSurfaceInterpolator {
  uDimension 2 vDimension 3 uOrder 2 vOrder 2
  controlPoint Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 1 ] }
}
)"));
  s.send("I", "set_fraction", FieldValue::make<FieldType::SFVec2f>(glm::vec2(0.5f)));
  CHECK(s.take().empty());
  CHECK(nurbsInterpErrors(s, "4 control points, uDimension x vDimension is 2 x 3") == 1);
}

TEST_CASE("NURBS interpolators: the pure functions give no NaN for NaN fractions",
          "[runtime][x3d][nurbs]") {
  RunningWorld w(x3dWorld(std::string("DEF I NurbsPositionInterpolator { ") +
                          kNurbsInterpQuarterCircle + " }\nDEF O NurbsOrientationInterpolator { " +
                          kNurbsInterpQuarterCircle + " }\n"));
  std::string problem;
  const auto p = gs::runtime::nurbsPositionAt(w.node("I"), std::nanf(""), problem);
  REQUIRE(p);
  nurbsInterpCheck(*p, {1.0f, 0.0f, 0.0f});  // NaN counts as 0
  const auto r = gs::runtime::nurbsOrientationAt(w.node("O"), std::nanf(""), problem);
  REQUIRE(r);
  CHECK(std::isfinite(r->w));
}
