// Clause 4.6.8 and the interpolator nodes of part 6.
#include "runtime/interpolators.hpp"
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace gs::runtime;
using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

TEST_CASE("interpolators: key spans, clamping and step keys", "[runtime][interp]") {
  const std::vector<float> key{0.0f, 0.5f, 0.5f, 1.0f};
  CHECK(findKeySpan(key, -1.0f).index == 0);
  auto s = findKeySpan(key, 0.25f);
  CHECK(s.index == 0);
  CHECK(s.t == Approx(0.5));
  CHECK(findKeySpan(key, 0.5f).index == 2);  // the later value wins at a step
  CHECK(findKeySpan(key, 2.0f).index == 3);
  std::string problem;
  const auto v = interpolate(InterpolatorKind::Scalar, key,
                             FieldValue::make<FieldType::MFFloat>(std::vector<float>{0, 1, 2, 3}),
                             0.5f, problem);
  REQUIRE(v);
  CHECK(v->get<FieldType::SFFloat>() == 2.0f);
}

TEST_CASE("interpolators: OrientationInterpolator takes the shorter arc", "[runtime][interp]") {
  const auto r = slerpRotation({0, 1, 0, 0}, {0, 1, 0, 3.0f}, 0.5f);
  CHECK(r.y == Approx(1.0));
  CHECK(r.w == Approx(1.5));
  // 0.2 rad and 2*pi - 0.2 rad (i.e. -0.2) about Y: the short way passes through 0.
  const auto m = slerpRotation({0, 1, 0, 0.2f}, {0, 1, 0, 6.2831853f - 0.2f}, 0.5f);
  CHECK(std::abs(m.w) < 1e-3);
  // Between keys of a node.
  RunningWorld w(R"(
DEF O OrientationInterpolator { key [0 1] keyValue [1 0 0 0, 1 0 0 1.5708] }
DEF X Transform {}
ROUTE O.value_changed TO X.rotation
)");
  w.send("O", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  const auto rot = w.node("X").field("rotation")->get<FieldType::SFRotation>();
  CHECK(rot.x == Approx(1.0));
  CHECK(rot.w == Approx(0.7854).epsilon(1e-3));
}

TEST_CASE("interpolators: Coordinate and Normal give one array per key", "[runtime][interp]") {
  std::string problem;
  auto v = interpolate(InterpolatorKind::Coordinate, {0, 1},
                       FieldValue::make<FieldType::MFVec3f>(
                           std::vector<glm::vec3>{{0, 0, 0}, {1, 1, 1}, {2, 0, 0}, {3, 3, 3}}),
                       0.5f, problem);
  REQUIRE(v);
  CHECK(v->get<FieldType::MFVec3f>() == std::vector<glm::vec3>{{1, 0, 0}, {2, 2, 2}});
  auto n = interpolate(
      InterpolatorKind::Normal, {0, 1},
      FieldValue::make<FieldType::MFVec3f>(std::vector<glm::vec3>{{1, 0, 0}, {0, 1, 0}}), 0.5f,
      problem);
  REQUIRE(n);
  const glm::vec3 mid = n->get<FieldType::MFVec3f>()[0];
  CHECK(glm::length(mid) == Approx(1.0));
  CHECK(mid.x == Approx(std::sqrt(0.5)));
  CHECK(interpolate(
            InterpolatorKind::Color, {0, 1},
            FieldValue::make<FieldType::MFColor>(std::vector<glm::vec3>{{1, 0, 0}, {0, 0, 1}}),
            0.25f, problem)
            ->get<FieldType::SFColor>() == glm::vec3(0.75f, 0, 0.25f));
}

TEST_CASE("interpolators: a bad key count is a diagnostic and no output", "[runtime][interp]") {
  RunningWorld w(R"(
DEF P PositionInterpolator { key [0 0.5 1] keyValue [0 0 0, 1 1 1] }
DEF X Transform {}
ROUTE P.value_changed TO X.translation
)");
  w.take();
  w.send("P", "set_fraction", FieldValue::make<FieldType::SFFloat>(0.5f));
  CHECK(w.take().empty());
  REQUIRE(w.model->diagnostics().items.size() == 1);
  CHECK(w.model->diagnostics().items[0].message.find("2 values for 3 keys") != std::string::npos);
  CHECK(w.model->diagnostics().items[0].location.line == 3);
}
