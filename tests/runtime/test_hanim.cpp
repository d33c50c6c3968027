// H-Anim (X3D 4.0 clause 26) in the execution model: a humanoid's skin follows its joints
// (runtime/src/skin.cpp), values worked out by hand.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>

using namespace gs;
using namespace gs::test;
using vrml::FieldType;
using vrml::FieldValue;

namespace {

bool near(glm::vec3 a, glm::vec3 b) {
  return glm::length(a - b) < 1e-4f;
}

}  // namespace

TEST_CASE("H-Anim: a joint's rotation and translation move the skin points it weighs",
          "[runtime][hanim]") {
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skinCoord DEF SC Coordinate { point [ 1 0 0, 2 0 0, 3 0 0 ] }
  skeleton DEF J HAnimJoint { skinCoordIndex [ 1 2 ] skinCoordWeight [ 1 0.5 ] }
  joints USE J
  skin Shape { geometry PointSet { coord USE SC } }
}
)"));
  const auto points = [&] { return w.node("SC").field("point")->get<FieldType::MFVec3f>(); };
  REQUIRE(points().size() == 3);
  CHECK(near(points()[1], {2, 0, 0}));  // the bind pose, untouched at load
  // A quarter turn about z at the joint's centre (the origin).
  w.send("J", "set_rotation",
         FieldValue::make<FieldType::SFRotation>(vrml::Rotation(0, 0, 1, glm::half_pi<float>())));
  CHECK(near(points()[0], {1, 0, 0}));        // no joint weighs it
  CHECK(near(points()[1], {0, 2, 0}));        // weight 1: turned
  CHECK(near(points()[2], {1.5f, 1.5f, 0}));  // half turned, half at rest
  // Then moved up by 1 as well.
  w.send("J", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0, 1, 0)));
  CHECK(near(points()[1], {0, 3, 0}));
  // Back to the bind pose.
  w.send("J", "set_rotation", FieldValue::make<FieldType::SFRotation>(vrml::Rotation(0, 0, 1, 0)));
  w.send("J", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0, 0, 0)));
  CHECK(near(points()[2], {3, 0, 0}));
}
