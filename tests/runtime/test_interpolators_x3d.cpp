// X3D 4.0 clause 19 interpolators in the execution model: PositionInterpolator2D and
// CoordinateInterpolator2D (linear), EaseInEaseOut, the spline interpolators (19.2.4) and
// SquadOrientationInterpolator. Expected values are worked out by hand in the comments
// (Hermite basis at s = 0.5: h1 = h2 = 0.5, h3 = 0.125, h4 = -0.125).
#include "runtime/interpolators_x3d.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <string>

using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

/// A float sink: the interpolator `out` of `node` routed to M.transparency.
std::string interpX3dScalarWorld(const std::string& node,
                                 const std::string& out = "value_changed") {
  return node + R"(
Shape { appearance Appearance { material DEF M Material {} } }
ROUTE I.)" +
         out + " TO M.transparency\n";
}

/// Sends set_fraction `f` to I; the events it caused.
std::vector<std::string> interpX3dSend(RunningWorld& w, float f) {
  w.take();
  w.send("I", "set_fraction", FieldValue::make<FieldType::SFFloat>(f));
  return w.take();
}

/// Sends set_fraction `f` to I and reads M.transparency (a float routed there).
float interpX3dScalarAt(RunningWorld& w, float f) {
  interpX3dSend(w, f);
  return w.node("M").field("transparency")->get<FieldType::SFFloat>();
}

/// Sends set_fraction `f` to I and reads X.translation (an SFVec3f routed there).
glm::vec3 interpX3dVec3At(RunningWorld& w, float f) {
  interpX3dSend(w, f);
  return w.node("X").field("translation")->get<FieldType::SFVec3f>();
}

/// Sends set_fraction `f` to I and reads X.rotation (an SFRotation routed there).
gs::vrml::Rotation interpX3dRotationAt(RunningWorld& w, float f) {
  interpX3dSend(w, f);
  return w.node("X").field("rotation")->get<FieldType::SFRotation>();
}

}  // namespace

TEST_CASE("x3d interpolators: PositionInterpolator2D and CoordinateInterpolator2D are linear",
          "[runtime][x3d][interp]") {
  RunningWorld w(x3dWorld(R"(
DEF I PositionInterpolator2D { key [0 0.5 1] keyValue [0 0, 2 4, 2 0] }
DEF C CoordinateInterpolator2D { key [0 1] keyValue [0 0, 1 1, 4 2, 3 5] }
Shape {
  appearance Appearance { textureTransform DEF T TextureTransform {} }
  geometry IndexedFaceSet { texCoord DEF TC TextureCoordinate {} }
}
ROUTE I.value_changed TO T.translation
ROUTE C.value_changed TO TC.point
)"));
  const auto translation = [&] {
    return w.node("T").field("translation")->get<FieldType::SFVec2f>();
  };
  interpX3dSend(w, 0.25f);
  CHECK(translation() == glm::vec2(1, 2));
  interpX3dSend(w, 0.75f);
  CHECK(translation() == glm::vec2(2, 2));
  interpX3dSend(w, -1.0f);
  CHECK(translation() == glm::vec2(0, 0));
  interpX3dSend(w, 5.0f);
  CHECK(translation() == glm::vec2(2, 0));
  w.send("C", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(w.node("TC").field("point")->get<FieldType::MFVec2f>() ==
        std::vector<glm::vec2>{{2, 1}, {2, 3}});
  // Three values for two keys: not a whole multiple; a diagnostic and no output.
  RunningWorld bad(
      x3dWorld("DEF C CoordinateInterpolator2D { key [0 1] keyValue [0 0, 1 1, 2 2] }\n"));
  bad.take();
  bad.send("C", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(bad.take().empty());
  REQUIRE(bad.model->diagnostics().items.size() == 1);
  CHECK(bad.model->diagnostics().items[0].message.find("not a multiple") != std::string::npos);
}

TEST_CASE("x3d interpolators: EaseInEaseOut modifies the fraction of each key interval",
          "[runtime][x3d][interp]") {
  // easeOut 0.5 at key 0, easeIn 0.5 at key 1: S = 1, t = 1 / (2 - 1) = 1.
  RunningWorld w(x3dWorld(
      interpX3dScalarWorld("DEF I EaseInEaseOut { key [0 1] easeInEaseOut [0 0.5, 0.5 0] }",
                           "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(w, 0.25f) == Approx(0.125));  // (t / 0.5) 0.25^2
  CHECK(interpX3dScalarAt(w, 0.5f) == Approx(0.5));     // t (2 0.5 - 0.5)
  CHECK(interpX3dScalarAt(w, 0.75f) == Approx(0.875));  // 1 - t 0.25^2 / 0.5
  CHECK(interpX3dScalarAt(w, 1.0f) == Approx(1.0));
  CHECK(interpX3dScalarAt(w, 0.0f) == Approx(0.0));
  CHECK(interpX3dScalarAt(w, -3.0f) == Approx(0.0));
  CHECK(interpX3dScalarAt(w, 3.0f) == Approx(1.0));
  CHECK(interpX3dSend(w, 0.25f) == std::vector<std::string>{"I.modifiedFraction_changed=0.125",
                                                            "M.transparency_changed=0.125"});

  // Only easeOut 0.2: t = 1 / 1.8; the linear part is t (2u - 0.2), no easeIn.
  RunningWorld out(x3dWorld(interpX3dScalarWorld(
      "DEF I EaseInEaseOut { key [0 1] easeInEaseOut [0 0.2, 0 0] }", "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(out, 0.1f) == Approx(0.1 * 0.1 / (1.8 * 0.2)));
  CHECK(interpX3dScalarAt(out, 0.6f) == Approx((1.2 - 0.2) / 1.8));
  CHECK(interpX3dScalarAt(out, 1.0f) == Approx(1.0));

  // A sum over 1 is scaled down to 1: (0.8, 0.8) acts as (0.5, 0.5).
  RunningWorld big(x3dWorld(
      interpX3dScalarWorld("DEF I EaseInEaseOut { key [0 1] easeInEaseOut [0 0.8, 0.8 0] }",
                           "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(big, 0.25f) == Approx(0.125));
  CHECK(interpX3dScalarAt(big, 0.75f) == Approx(0.875));

  // A negative sum leaves the fraction as it is.
  RunningWorld neg(x3dWorld(interpX3dScalarWorld(
      "DEF I EaseInEaseOut { key [0 1] easeInEaseOut [0 -1, -1 0] }", "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(neg, 0.3f) == Approx(0.3));
}

TEST_CASE("x3d interpolators: EaseInEaseOut over several keys and with missing values",
          "[runtime][x3d][interp]") {
  // The eased fraction is local to the interval the fraction falls in (X_ITE, FreeWRL).
  RunningWorld w(x3dWorld(interpX3dScalarWorld(
      "DEF I EaseInEaseOut { key [0 0.5 1] easeInEaseOut [0 0.5, 0.5 0.5, 0.5 0] }",
      "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(w, 0.125f) == Approx(0.125));  // u = 0.25 in [0, 0.5]
  CHECK(interpX3dScalarAt(w, 0.625f) == Approx(0.125));  // u = 0.25 in [0.5, 1]
  CHECK(interpX3dScalarAt(w, 0.875f) == Approx(0.875));
  // No easeInEaseOut values: padded with (0, 0), the fraction unchanged.
  RunningWorld none(x3dWorld(
      interpX3dScalarWorld("DEF I EaseInEaseOut { key [0 1] }", "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(none, 0.3f) == Approx(0.3));
  // One value for two keys: padded with it (easeIn 0.5 at key 1 too).
  RunningWorld one(x3dWorld(interpX3dScalarWorld(
      "DEF I EaseInEaseOut { key [0 1] easeInEaseOut [0.5 0.5] }", "modifiedFraction_changed")));
  CHECK(interpX3dScalarAt(one, 0.75f) == Approx(0.875));
  // No keys: no events, a diagnostic.
  RunningWorld empty(x3dWorld(interpX3dScalarWorld("DEF I EaseInEaseOut { easeInEaseOut [0 0.5] }",
                                                   "modifiedFraction_changed")));
  CHECK(interpX3dSend(empty, 0.5f).empty());
  REQUIRE(empty.model->diagnostics().items.size() == 1);
  CHECK(empty.model->diagnostics().items[0].message.find("key is empty") != std::string::npos);
}

TEST_CASE("x3d interpolators: SplineScalarInterpolator uses Catmull-Rom tangents",
          "[runtime][x3d][interp]") {
  // T_1 = (3 - 0) / 2 = 1.5; the open ends have zero tangents.
  RunningWorld w(x3dWorld(
      interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0 0.5 1] keyValue [0 1 3] }")));
  CHECK(interpX3dScalarAt(w, 0.0f) == Approx(0.0));
  CHECK(interpX3dScalarAt(w, 0.5f) == Approx(1.0));
  CHECK(interpX3dScalarAt(w, 1.0f) == Approx(3.0));
  CHECK(interpX3dScalarAt(w, -2.0f) == Approx(0.0));
  CHECK(interpX3dScalarAt(w, 2.0f) == Approx(3.0));
  CHECK(interpX3dScalarAt(w, 0.25f) == Approx(0.3125));  // 0.5 1 - 0.125 1.5
  CHECK(interpX3dScalarAt(w, 0.75f) == Approx(2.1875));  // 0.5 (1 + 3) + 0.125 1.5
  // Uneven keys: F-_1 = 2 0.75 / 1 = 1.5 arrives, F+_1 = 2 0.25 / 1 = 0.5 leaves.
  RunningWorld uneven(x3dWorld(
      interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0 0.25 1] keyValue [0 1 3] }")));
  CHECK(interpX3dScalarAt(uneven, 0.125f) == Approx(0.21875));  // 0.5 - 0.125 1.5 1.5
  CHECK(interpX3dScalarAt(uneven, 0.625f) == Approx(2.09375));  // 2 + 0.125 0.5 1.5
  CHECK(gs::runtime::hermite(0, 1, 0, 1.5f, 0.5f) == Approx(0.3125));
}

TEST_CASE("x3d interpolators: closed splines wrap the end tangents", "[runtime][x3d][interp]") {
  // Closed: T_0 = T_3 = (v_1 - v_2) / 2 = -0.5, T_1 = 1, T_2 = -0.5; even keys, F = 1.
  RunningWorld closed(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1 2 3] keyValue [0 1 2 0] closed TRUE }")));
  CHECK(interpX3dScalarAt(closed, 0.5f) == Approx(0.3125));  // 0.5 - 0.0625 - 0.125
  CHECK(interpX3dScalarAt(closed, 2.5f) == Approx(1.0));     // 1 - 0.0625 + 0.0625
  CHECK(interpX3dScalarAt(closed, 3.0f) == Approx(0.0));
  RunningWorld open(x3dWorld(
      interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0 1 2 3] keyValue [0 1 2 0] }")));
  CHECK(interpX3dScalarAt(open, 0.5f) == Approx(0.375));   // T_0 = 0
  CHECK(interpX3dScalarAt(open, 2.5f) == Approx(0.9375));  // T_3 = 0
  // closed is ignored when the first and last values differ.
  RunningWorld unequal(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1 2 3] keyValue [0 1 2 0.5] closed TRUE }")));
  CHECK(interpX3dScalarAt(unequal, 0.5f) == Approx(0.375));
  // Closed with uneven keys: F+_0 = 2 (t_3 - t_2) / ((t_1 - t_0) + (t_3 - t_2)) = 2 2 / 3.
  RunningWorld wrap(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1 2 4] keyValue [0 1 2 0] closed TRUE }")));
  // T0_0 = -0.5 4/3; T_1 = 1 with F-_1 = 2 1 / 2 = 1.
  CHECK(interpX3dScalarAt(wrap, 0.5f) == Approx(0.5 + 0.125 * (-0.5 * 4.0 / 3.0) - 0.125));
}

TEST_CASE("x3d interpolators: keyVelocity and normalizeVelocity", "[runtime][x3d][interp]") {
  // Every velocity given: T_0 = 2, T_1 = 0.
  RunningWorld given(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1] keyValue [0 1] keyVelocity [2 0] }")));
  CHECK(interpX3dScalarAt(given, 0.5f) == Approx(0.75));  // 0.5 + 0.125 2
  // Normalized: Dtot = 1, T_0 = 2 (1 / 2) = 1; a zero velocity stays zero.
  RunningWorld normalized(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1] keyValue [0 1] keyVelocity [2 0] "
      "normalizeVelocity TRUE }")));
  CHECK(interpX3dScalarAt(normalized, 0.5f) == Approx(0.625));
  // Two velocities for three keys: the ends; T_1 = (3 - 0) / 2 computed.
  RunningWorld ends(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1 2] keyValue [0 1 3] keyVelocity [4 0] }")));
  CHECK(interpX3dScalarAt(ends, 0.5f) == Approx(0.8125));  // 0.5 + 0.125 4 - 0.125 1.5
  // One velocity for three keys: ignored, every tangent computed.
  RunningWorld odd(x3dWorld(interpX3dScalarWorld(
      "DEF I SplineScalarInterpolator { key [0 1 2] keyValue [0 1 3] keyVelocity [4] }")));
  CHECK(interpX3dScalarAt(odd, 0.5f) == Approx(0.3125));
  // A vector velocity is normalized to the polyline's length: Dtot = 5, T_0 = (5, 0, 0).
  RunningWorld vec(x3dWorld(R"(
DEF I SplinePositionInterpolator {
  key [0 1] keyValue [0 0 0, 3 4 0] keyVelocity [1 0 0, 0 0 0] normalizeVelocity TRUE
}
DEF X Transform {}
ROUTE I.value_changed TO X.translation
)"));
  const glm::vec3 p = interpX3dVec3At(vec, 0.5f);
  CHECK(p.x == Approx(2.125));  // 1.5 + 0.125 5
  CHECK(p.y == Approx(2.0));
  vec.send("I", "normalizeVelocity", FieldValue::make<FieldType::SFBool>(false));
  CHECK(interpX3dVec3At(vec, 0.5f).x == Approx(1.625));  // 1.5 + 0.125 1
}

TEST_CASE("x3d interpolators: SplinePositionInterpolator and its 2D form",
          "[runtime][x3d][interp]") {
  RunningWorld w(x3dWorld(R"(
DEF I SplinePositionInterpolator { key [0 0.5 1] keyValue [0 0 0, 1 2 0, 3 4 0] }
DEF J SplinePositionInterpolator2D { key [0 0.5 1] keyValue [0 0, 1 2, 3 4] }
DEF X Transform {}
Shape { appearance Appearance { textureTransform DEF T TextureTransform {} } }
ROUTE I.value_changed TO X.translation
ROUTE J.value_changed TO T.translation
)"));
  // x: as the scalar case; y: T_1 = (4 - 0) / 2 = 2.
  glm::vec3 p = interpX3dVec3At(w, 0.25f);
  CHECK(p.x == Approx(0.3125));
  CHECK(p.y == Approx(0.75));  // 0.5 2 - 0.125 2
  CHECK(p.z == Approx(0.0));
  p = interpX3dVec3At(w, 0.75f);
  CHECK(p.x == Approx(2.1875));
  CHECK(p.y == Approx(3.25));  // 0.5 (2 + 4) + 0.125 2
  CHECK(interpX3dVec3At(w, 0.5f) == glm::vec3(1, 2, 0));
  CHECK(interpX3dVec3At(w, 9.0f) == glm::vec3(3, 4, 0));
  w.send("J", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.25f));
  const glm::vec2 q = w.node("T").field("translation")->get<FieldType::SFVec2f>();
  CHECK(q.x == Approx(0.3125));
  CHECK(q.y == Approx(0.75));
}

TEST_CASE("x3d interpolators: degenerate spline inputs", "[runtime][x3d][interp]") {
  // Two values for three keys: a diagnostic (once) and no output.
  RunningWorld bad(x3dWorld(
      interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0 0.5 1] keyValue [0 1] }")));
  CHECK(interpX3dSend(bad, 0.5f).empty());
  CHECK(interpX3dSend(bad, 0.7f).empty());
  REQUIRE(bad.model->diagnostics().items.size() == 1);
  CHECK(bad.model->diagnostics().items[0].message.find("2 values for 3 keys") != std::string::npos);
  // No keys: nothing.
  RunningWorld empty(x3dWorld(interpX3dScalarWorld("DEF I SplineScalarInterpolator {}")));
  CHECK(interpX3dSend(empty, 0.5f).empty());
  // One key: its value for any fraction.
  RunningWorld one(
      x3dWorld(interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0.5] keyValue [7] }")));
  CHECK(interpX3dScalarAt(one, 0.0f) == Approx(7.0));
  CHECK(interpX3dScalarAt(one, 0.9f) == Approx(7.0));
  // Equal keys (a step) with closed, zero velocities and normalizeVelocity: no crash, finite
  // values, the later value at the step.
  RunningWorld step(x3dWorld(
      interpX3dScalarWorld("DEF I SplineScalarInterpolator { key [0 0.5 0.5 1] keyValue [0 1 5 6] "
                           "closed TRUE normalizeVelocity TRUE keyVelocity [0 0 0 0] }")));
  CHECK(interpX3dScalarAt(step, 0.5f) == Approx(5.0));
  CHECK(std::isfinite(interpX3dScalarAt(step, 0.25f)));
  CHECK(std::isfinite(interpX3dScalarAt(step, 0.75f)));
  // keyValue of a type no spline has: nothing.
  std::string problem;
  const auto wrong = gs::runtime::interpolateSpline(
      {0, 1}, FieldValue::make<FieldType::MFRotation>(std::vector<gs::vrml::Rotation>(2)), {}, 0.5f,
      problem);
  CHECK_FALSE(wrong);
  CHECK(problem == "keyValue has the wrong type");
}

TEST_CASE("x3d interpolators: SquadOrientationInterpolator", "[runtime][x3d][interp]") {
  // Rotations about one axis commute: with angles a_i, s_1 turns by
  // a_1 - (a_0 + a_2 - 2 a_1) / 4 = 1 - (0 + 3 - 2) / 4 = 0.75; s_0 = q_0, s_2 = q_2.
  RunningWorld w(x3dWorld(R"(
DEF I SquadOrientationInterpolator { key [0 0.5 1] keyValue [0 1 0 0, 0 1 0 1, 0 1 0 3] }
DEF X Transform {}
ROUTE I.value_changed TO X.rotation
)"));
  auto r = interpX3dRotationAt(w, 0.5f);  // at a key: the key's rotation
  CHECK(r.y == Approx(1.0));
  CHECK(r.w == Approx(1.0));
  r = interpX3dRotationAt(w, 1.0f);
  CHECK(r.y == Approx(1.0));
  CHECK(r.w == Approx(3.0));
  // Midway in [0, 0.5]: slerp(0.5, slerp(0, 0.75, 0.5) = 0.375, 2 h (1 - h) = 0.5) = 0.4375.
  r = interpX3dRotationAt(w, 0.25f);
  CHECK(r.y == Approx(1.0));
  CHECK(r.w == Approx(0.4375));
  // Midway in [0.5, 1]: slerp(2, (0.75 + 3) / 2 = 1.875, 0.5) = 1.9375.
  r = interpX3dRotationAt(w, 0.75f);
  CHECK(r.w == Approx(1.9375));
  // Below the first key: the first value (the identity, axis 0 0 1 angle 0).
  r = interpX3dRotationAt(w, -1.0f);
  CHECK(r.w == Approx(0.0).margin(1e-6));

  // Two keys: squad is slerp along the shorter arc (0.2 and 2 pi - 0.2 meet at 0).
  RunningWorld two(x3dWorld(R"(
DEF I SquadOrientationInterpolator { key [0 1] keyValue [1 0 0 0.2, 1 0 0 6.0831853] }
DEF X Transform {}
ROUTE I.value_changed TO X.rotation
)"));
  CHECK(interpX3dRotationAt(two, 0.5f).w == Approx(0.0).margin(1e-4));
  r = interpX3dRotationAt(two, 0.25f);
  CHECK(r.x == Approx(1.0));
  CHECK(r.w == Approx(0.1).margin(1e-4));
}

TEST_CASE("x3d interpolators: squad's intermediate quaternion and degenerate inputs",
          "[runtime][x3d][interp]") {
  using gs::runtime::squadIntermediate;
  const glm::dvec3 y(0, 1, 0);
  const glm::dquat s =
      squadIntermediate(glm::angleAxis(0.0, y), glm::angleAxis(1.0, y), glm::angleAxis(3.0, y));
  CHECK(glm::angle(s) == Approx(0.75));
  // Neighbours given in the other hemisphere make no difference.
  const glm::dquat t =
      squadIntermediate(-glm::angleAxis(0.0, y), glm::angleAxis(1.0, y), -glm::angleAxis(3.0, y));
  CHECK(glm::dot(s, t) == Approx(1.0));
  // Off one axis: at the keys squad gives the keys, and s is a unit quaternion.
  const glm::dquat u =
      squadIntermediate(glm::angleAxis(0.5, glm::dvec3(1, 0, 0)), glm::angleAxis(0.7, y),
                        glm::angleAxis(0.4, glm::dvec3(0, 0, 1)));
  CHECK(glm::length(u) == Approx(1.0));
  std::string problem;
  const std::vector<gs::vrml::Rotation> values{{1, 0, 0, 0.5f}, {0, 1, 0, 0.7f}, {0, 0, 1, 0.4f}};
  const auto at = gs::runtime::interpolateSquad({0, 1, 2}, values, 1.0f, problem);
  REQUIRE(at);
  CHECK(at->y == Approx(1.0));
  CHECK(at->w == Approx(0.7));
  // Mismatched counts and no keys: nothing; one key: that key.
  CHECK_FALSE(gs::runtime::interpolateSquad({0, 1}, values, 0.5f, problem));
  CHECK(problem == "keyValue has 3 values for 2 keys");
  CHECK_FALSE(gs::runtime::interpolateSquad({}, {}, 0.5f, problem));
  const auto single =
      gs::runtime::interpolateSquad({0.3f}, {{0, 2, 0, 0.5f}}, 0.9f, problem);  // axis made unit
  REQUIRE(single);
  CHECK(single->y == Approx(1.0));
  CHECK(single->w == Approx(0.5));
  RunningWorld bad(x3dWorld(R"(
DEF I SquadOrientationInterpolator { key [0 1] keyValue [0 1 0 1] }
DEF X Transform {}
ROUTE I.value_changed TO X.rotation
)"));
  CHECK(interpX3dSend(bad, 0.5f).empty());
  REQUIRE(bad.model->diagnostics().items.size() == 1);
}

TEST_CASE("x3d interpolators: a TimeSensor drives EaseInEaseOut into a spline",
          "[runtime][x3d][interp]") {
  // cycleInterval 4 from t = 100: fraction (t - 100) / 4, eased, then the spline of the
  // first test case (x: 0 1 3 at 0 0.5 1).
  RunningWorld w(x3dWorld(R"(
DEF TS TimeSensor { cycleInterval 4 startTime 100 }
DEF E EaseInEaseOut { key [0 1] easeInEaseOut [0 0.5, 0.5 0] }
DEF I SplinePositionInterpolator { key [0 0.5 1] keyValue [0 0 0, 1 2 0, 3 4 0] }
DEF X Transform {}
ROUTE TS.fraction_changed TO E.set_fraction
ROUTE E.modifiedFraction_changed TO I.set_fraction
ROUTE I.value_changed TO X.translation
)"),
                 99.0);
  const auto x = [&] { return w.node("X").field("translation")->get<FieldType::SFVec3f>().x; };
  w.model->advanceTo(101.0);  // fraction 0.25 -> 0.125; spline segment 0 at s = 0.25
  // hermite(0, 1, 0, 1.5, 0.25) = 0.15625 - 0.0703125 = 0.0859375
  CHECK(x() == Approx(0.0859375));
  w.model->advanceTo(102.0);  // fraction 0.5 -> 0.5: the middle key
  CHECK(x() == Approx(1.0));
  w.model->advanceTo(103.0);  // 0.75 -> 0.875; segment 1 at s = 0.75
  // hermite(1, 3, 1.5, 0, 0.75) = 1 0.15625 + 3 0.84375 + 1.5 0.046875 = 2.7578125
  CHECK(x() == Approx(2.7578125));
  w.model->advanceTo(104.5);  // ended at fraction 1
  CHECK(x() == Approx(3.0));
}
