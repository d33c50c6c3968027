// H-Anim (X3D 4.0 clause 26) in the execution model: a humanoid's skin follows its joints
// (runtime/src/skin.cpp), values worked out by hand.
#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

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

TEST_CASE("H-Anim: displacers move the points they list by weight, turned with their joint",
          "[runtime][hanim]") {
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skinCoord DEF SC Coordinate { point [ 1 0 0, 2 0 0 ] }
  skeleton DEF J HAnimJoint {
    skinCoordIndex [ 1 ] skinCoordWeight [ 1 ]
    displacers DEF D HAnimDisplacer { coordIndex [ 0 1 ] displacements [ 0 2 0, 1 0 0 ] weight 0.5 }
  }
  joints USE J
  segments DEF S HAnimSegment {
    coord DEF SEG Coordinate { point [ 0 0 0, 5 5 5 ] }
    displacers DEF E HAnimDisplacer { coordIndex [ 1 ] displacements [ 0 0 -4 ] weight 0 }
  }
  skin Shape { geometry PointSet { coord USE SC } }
}
)"));
  const auto skin = [&] { return w.node("SC").field("point")->get<FieldType::MFVec3f>(); };
  const auto seg = [&] { return w.node("SEG").field("point")->get<FieldType::MFVec3f>(); };
  // At load: displaced by half their displacements.
  CHECK(near(skin()[0], {1, 1, 0}));
  CHECK(near(skin()[1], {2.5f, 0, 0}));
  CHECK(near(seg()[1], {5, 5, 5}));  // weight 0
  w.send("D", "set_weight", FieldValue::make<FieldType::SFFloat>(1.0f));
  w.send("E", "set_weight", FieldValue::make<FieldType::SFFloat>(0.25f));
  CHECK(near(skin()[0], {1, 2, 0}));
  CHECK(near(seg()[1], {5, 5, 4}));
  // The joint turns a quarter about z: point 1 (weighed by it) and its displacement turn.
  w.send("J", "set_rotation",
         FieldValue::make<FieldType::SFRotation>(vrml::Rotation(0, 0, 1, glm::half_pi<float>())));
  CHECK(near(skin()[1], {0, 3, 0}));   // (2, 0, 0) turned, plus (1, 0, 0) turned
  CHECK(near(skin()[0], {-1, 0, 0}));  // rest (1, 0, 0) + (0, 2, 0) turned to (-2, 0, 0)
}

TEST_CASE("H-Anim: an HAnimMotion drives its joints by name, frame by frame", "[runtime][hanim]") {
  // Three frames 0.5 s apart: the root moves 1 m along x per frame, l_shoulder turns 90
  // degrees about z per frame; looping, the cycle is 1 s long from the load (time 0).
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skeleton DEF R HAnimJoint { name "humanoid_root" children DEF A HAnimJoint { name " l_shoulder " } }
  joints [ USE R USE A ]
  motions DEF M HAnimMotion { joints "HumanoidRoot l_shoulder" loop TRUE frameDuration 0.5
    channels "3 Xposition Yposition Zposition 1 Zrotation"
    values [ 0 0 0 0,  1 0 0 90,  2 0 0 180 ] }
}
)"));
  const auto translation = [&] {
    return w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1));
  };
  const auto rotation = [&] {
    const vrml::Rotation r = w.node("A").get<FieldType::SFRotation>("rotation", vrml::Rotation{});
    return glm::angleAxis(r.w, glm::normalize(glm::vec3(r.x, r.y, r.z)));
  };
  w.model->advanceTo(0.25);  // a quarter of the cycle: halfway between frames 0 and 1
  CHECK(near(translation(), {0.5f, 0, 0}));
  CHECK(std::abs(glm::dot(rotation(), glm::angleAxis(glm::radians(45.0f), glm::vec3(0, 0, 1)))) ==
        Approx(1.0f).margin(1e-5));
  CHECK(w.node("M").get<FieldType::SFInt32>("frameCount", 0) == 3);
  w.model->advanceTo(0.75);  // between frames 1 and 2
  CHECK(near(translation(), {1.5f, 0, 0}));
  CHECK(std::abs(glm::dot(rotation(), glm::angleAxis(glm::radians(135.0f), glm::vec3(0, 0, 1)))) ==
        Approx(1.0f).margin(1e-5));
  w.model->advanceTo(1.25);  // looped: a quarter into the second cycle
  CHECK(near(translation(), {0.5f, 0, 0}));
  // motionsEnabled FALSE: the joints stay where they are.
  w.send("H", "motionsEnabled", FieldValue::make<FieldType::MFBool>(std::vector<bool>{false}));
  w.model->advanceTo(1.5);
  CHECK(near(translation(), {0.5f, 0, 0}));
}

TEST_CASE("H-Anim: an HAnimMotion that does not loop stops on its end frame", "[runtime][hanim]") {
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skeleton DEF R HAnimJoint { name "humanoid_root" }
  joints USE R
  motions HAnimMotion { joints "humanoid_root" frameDuration 1 startFrame 1 endFrame 2
    channels "1 Yposition" values [ 5 10 20 30 ] }
}
)"));
  const auto y = [&] {
    return w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1)).y;
  };
  w.model->advanceTo(0.5);  // from frame 1 (10) towards frame 2 (20)
  CHECK(y() == Approx(15.0f));
  w.model->advanceTo(3.0);  // past the end: on frame 2
  CHECK(y() == Approx(20.0f));
}

TEST_CASE("H-Anim: an HAnimMotion's next and previous step its frames", "[runtime][hanim]") {
  // Held (frameIncrement 0) on frame 1 of four; frames 1 to 3 are its range.
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skeleton DEF R HAnimJoint { name "humanoid_root" }
  joints USE R
  motions DEF M HAnimMotion { joints "humanoid_root" frameIncrement 0 frameIndex 1
    startFrame 1 endFrame 3 channels "1 Yposition" values [ 0 10 20 30 ] }
}
)"));
  const auto y = [&] {
    return w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1)).y;
  };
  const auto frameIndex = [&] { return w.node("M").get<FieldType::SFInt32>("frameIndex", -1); };
  const auto step = [&](const char* field, double time) {
    w.send("M", field, FieldValue::make<FieldType::SFBool>(true));
    w.model->advanceTo(time);
  };
  w.model->advanceTo(0.1);
  CHECK(y() == Approx(10.0f));
  step("next", 0.2);  // frameIncrement 0 steps by 1
  CHECK(frameIndex() == 2);
  CHECK(y() == Approx(20.0f));
  step("next", 0.3);
  CHECK(y() == Approx(30.0f));
  step("next", 0.4);  // past endFrame without loop: ignored
  CHECK(frameIndex() == 3);
  CHECK(y() == Approx(30.0f));
  w.send("M", "loop", FieldValue::make<FieldType::SFBool>(true));
  step("next", 0.5);  // looping: back to startFrame
  CHECK(frameIndex() == 1);
  CHECK(y() == Approx(10.0f));
  step("previous", 0.6);  // and from startFrame back to endFrame
  CHECK(frameIndex() == 3);
  step("previous", 0.7);
  CHECK(y() == Approx(20.0f));
  // FALSE does nothing.
  w.send("M", "next", FieldValue::make<FieldType::SFBool>(false));
  w.model->advanceTo(0.8);
  CHECK(frameIndex() == 2);
}

TEST_CASE("H-Anim: a playing HAnimMotion says its frame and cycles, and plays backwards",
          "[runtime][hanim]") {
  // Three frames 1 s apart, looping: a 2 s cycle from the load.
  RunningWorld w(x3dWorld(R"(
DEF H HAnimHumanoid {
  skeleton DEF R HAnimJoint { name "humanoid_root" }
  joints USE R
  motions DEF M HAnimMotion { joints "humanoid_root" loop TRUE frameDuration 1
    channels "1 Xposition" values [ 0 1 2 ] }
}
)"));
  const auto x = [&] {
    return w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1)).x;
  };
  const auto frameIndex = [&] { return w.node("M").get<FieldType::SFInt32>("frameIndex", -1); };
  w.model->advanceTo(0.5);
  CHECK(frameIndex() == 0);
  CHECK(w.node("M").get<FieldType::SFTime>("cycleTime", -1.0) == Approx(0.0));
  w.model->advanceTo(1.5);
  CHECK(frameIndex() == 1);
  CHECK(x() == Approx(1.5f));
  w.model->advanceTo(2.25);  // the second cycle started at 2
  CHECK(w.node("M").get<FieldType::SFTime>("cycleTime", -1.0) == Approx(2.0));
  CHECK(x() == Approx(0.25f));
  // next while it plays: from frame 0 to frame 1, and it goes on from there.
  w.send("M", "next", FieldValue::make<FieldType::SFBool>(true));
  w.model->advanceTo(2.5);
  CHECK(x() == Approx(1.25f));
  // frameIncrement -1: from the end frame back to the start.
  w.send("M", "frameIncrement", FieldValue::make<FieldType::SFInt32>(-1));
  w.send("M", "enabled", FieldValue::make<FieldType::SFBool>(false));
  w.model->advanceTo(3.0);
  w.send("M", "enabled", FieldValue::make<FieldType::SFBool>(true));  // starts again at 3
  w.model->advanceTo(3.5);
  CHECK(x() == Approx(1.5f));
  CHECK(frameIndex() == 1);
}

TEST_CASE("H-Anim: channelsEnabled turns off single channels, or whole joints as X_ITE reads it",
          "[runtime][hanim]") {
  // Root: X, Y and Z position; shoulder: Z then X rotation. Frame 1 holds (1, 2, 3) and
  // 90 degrees about z and x; the motion is held there (frameIncrement 0, frameIndex 1).
  const auto world = [](const std::string& enabled) {
    return x3dWorld(R"(
DEF H HAnimHumanoid {
  skeleton DEF R HAnimJoint { name "humanoid_root" children DEF A HAnimJoint { name "l_shoulder" } }
  joints [ USE R USE A ]
  motions DEF M HAnimMotion { joints "humanoid_root l_shoulder" frameIncrement 0 frameIndex 1
    channels "3 Xposition Yposition Zposition 2 Zrotation Xrotation"
    values [ 0 0 0 0 0,  1 2 3 90 90 ] channelsEnabled [ )" +
                    enabled + R"( ] }
}
)");
  };
  const auto pose = [](RunningWorld& w) {
    w.model->advanceTo(0.1);
    const vrml::Rotation r = w.node("A").get<FieldType::SFRotation>("rotation", vrml::Rotation{});
    return std::pair{w.node("R").get<FieldType::SFVec3f>("translation", glm::vec3(-1)),
                     glm::angleAxis(r.w, glm::normalize(glm::vec3(r.x, r.y, r.z)))};
  };
  const glm::quat z90 = glm::angleAxis(glm::radians(90.0f), glm::vec3(0, 0, 1));
  const glm::quat x90 = glm::angleAxis(glm::radians(90.0f), glm::vec3(1, 0, 0));
  const auto same = [](const glm::quat& a, const glm::quat& b) {
    return std::abs(glm::dot(a, b)) == Approx(1.0f).margin(1e-5);
  };
  {  // Every channel on (five values): the whole frame.
    RunningWorld w(world("TRUE TRUE TRUE TRUE TRUE"));
    const auto [t, r] = pose(w);
    CHECK(near(t, {1, 2, 3}));
    CHECK(same(r, z90 * x90));
  }
  {  // Y position and X rotation off: read as if the channels were not listed.
    RunningWorld w(world("TRUE FALSE TRUE TRUE FALSE"));
    const auto [t, r] = pose(w);
    CHECK(near(t, {1, 0, 3}));
    CHECK(same(r, z90));
  }
  {  // Two values for two joints: per joint (X_ITE): the root is left alone.
    RunningWorld w(world("FALSE TRUE"));
    const auto [t, r] = pose(w);
    CHECK(near(t, {0, 0, 0}));
    CHECK(same(r, z90 * x90));
  }
}
