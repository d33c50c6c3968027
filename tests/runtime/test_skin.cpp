// The Skin extension node (docs/vrml-extensions.md; glTF 2.0 clause 3.8): the execution
// model writes the skinned vertices after each cascade.
#include "runtime_fixture.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

using gs::test::RunningWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

// Three vertices: the first bound to joint 0, the second to joint 1, the third half and
// half. Joint 1 sits at y = 2 with the inverse bind matrix that undoes it (column-major:
// the translation is elements 12-14), so the rest pose is unchanged until it moves.
// The skinned node itself is translated by 5 in x: glTF ignores a skinned node's own
// transform, so the coordinates are written in its space (minus 5 in x).
const char* kWorld = R"(
DEF ROOT Transform { children [
  DEF J0 Transform {}
  DEF J1 Transform { translation 0 2 0 }
  DEF MESH Transform { translation 5 0 0 children Shape { geometry IndexedFaceSet {
    coord DEF C Coordinate { point [0 0 0, 1 0 0, 0 1 0] } coordIndex [0 1 2 -1] } } }
] }
DEF S Skin {
  skeleton USE ROOT
  joints [USE J0, USE J1]
  inverseBindMatrices [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1,
                       1 0 0 0 0 1 0 0 0 0 1 0 0 -2 0 1]
  skinnedTransform USE MESH
  coord USE C
  restPoint [0 0 0, 1 0 0, 0 1 0]
  vertexJoints [0 0 0 0, 1 0 0 0, 0 1 0 0]
  vertexWeights [1 0 0 0, 1 0 0 0, 0.5 0.5 0 0]
}
)";

std::vector<glm::vec3> points(const RunningWorld& w) {
  return w.node("C").field("point")->get<FieldType::MFVec3f>();
}

}  // namespace

TEST_CASE("Skin: the rest pose in the skinned node's space, then joints move vertices",
          "[runtime][skin]") {
  RunningWorld w(kWorld);
  w.model->advanceTo(0.1);
  auto p = points(w);
  REQUIRE(p.size() == 3);
  CHECK(p[0] == glm::vec3(-5, 0, 0));
  CHECK(p[1] == glm::vec3(-4, 0, 0));
  CHECK(p[2] == glm::vec3(-5, 1, 0));
  // Joint 1 one metre up: vertex 1 follows it, vertex 2 half as far.
  w.send("J1", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(0, 3, 0)));
  p = points(w);
  CHECK(p[0] == glm::vec3(-5, 0, 0));
  CHECK(p[1] == glm::vec3(-4, 1, 0));
  CHECK(p[2].y == Approx(1.5));
  // The skinned node's own transform does not move the skin in the world.
  w.send("MESH", "set_translation", FieldValue::make<FieldType::SFVec3f>(glm::vec3(1, 0, 0)));
  p = points(w);
  CHECK(p[0] == glm::vec3(-1, 0, 0));
  // A rotation of the root turns joints and skinned node alike: nothing changes locally.
  w.send("ROOT", "set_rotation",
         FieldValue::make<FieldType::SFRotation>(gs::vrml::Rotation(0, 1, 0, 1)));
  const auto q = points(w);
  for (std::size_t i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) CHECK(q[i][k] == Approx(p[i][k]).margin(1e-5));
}

TEST_CASE("Skin: bad counts are one error and leave the mesh as it is", "[runtime][skin]") {
  RunningWorld w(R"(
DEF C Coordinate { point [0 0 0, 1 0 0] }
DEF S Skin { coord USE C restPoint [9 9 9, 9 9 9] vertexJoints [0 0 0] vertexWeights [1 0 0] }
)");
  w.model->advanceTo(0.1);
  w.model->advanceTo(0.2);
  CHECK(points(w) == std::vector<glm::vec3>{{0, 0, 0}, {1, 0, 0}});
  std::size_t errors = 0;
  for (const auto& d : w.model->diagnostics().items)
    if (d.severity == gs::vrml::Severity::error && d.message.find("Skin S") != std::string::npos)
      ++errors;
  CHECK(errors == 1);
}

TEST_CASE("Skin: the corpus's skinned glTF models move their vertices with their joints",
          "[runtime][skin][corpus]") {
  if (!gs::test::haveCorpus("gltf")) return;
  const auto dir = gs::test::corpusDir() / "gltf/castle/animation";
  for (const char* model : {"gltf_skinned_animation/fox_from_khronos/Fox.gltf",
                            "blender_skinned_animation/skinned_anim.glb",
                            "gltf_skinned_animation/animals_from_quaternius/Bunny.gltf"}) {
    INFO(model);
    auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile((dir / model).string()));
    REQUIRE(scene->diagnostics.errorCount() == 0);
    gs::runtime::ExecutionModel runtime(scene, 0.0);
    // The first skinned Coordinate, as skinned at two times of the looping animation.
    const gs::vrml::Node* coord = nullptr;
    for (const auto& n : scene->rootNodes)
      if (n->typeName() == "Skin") {
        coord = n->field("coord")->get<FieldType::SFNode>().get();
        break;
      }
    REQUIRE(coord != nullptr);
    const auto rest = coord->field("point")->get<FieldType::MFVec3f>();
    runtime.advanceTo(0.25);
    const auto a = coord->field("point")->get<FieldType::MFVec3f>();
    runtime.advanceTo(0.75);
    const auto b = coord->field("point")->get<FieldType::MFVec3f>();
    // A world loaded at that time (as --snapshot --time 0.75 loads it) is skinned at once.
    auto again = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile((dir / model).string()));
    gs::runtime::ExecutionModel late(again, 0.75);
    for (const auto& n : again->rootNodes)
      if (n->typeName() == "Skin") {
        const auto& c = *n->field("coord")->get<FieldType::SFNode>();
        CHECK(c.field("point")->get<FieldType::MFVec3f>() == b);
        break;
      }
    std::string messages;
    for (const auto& d : runtime.diagnostics().items) messages += d.format() + "\n";
    INFO(messages);
    CHECK(runtime.diagnostics().errorCount() == 0);
    REQUIRE(a.size() == rest.size());
    REQUIRE(b.size() == rest.size());
    CHECK(a != rest);
    CHECK(b != a);
    // Skinning moves, it does not explode: every vertex stays within the rest pose's
    // bounding box grown by its own size.
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : rest) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const glm::vec3 pad = hi - lo;
    for (const glm::vec3& p : b) {
      CHECK(glm::all(glm::greaterThanEqual(p, lo - pad)));
      CHECK(glm::all(glm::lessThanEqual(p, hi + pad)));
    }
  }
}
