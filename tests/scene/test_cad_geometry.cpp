// X3D's CADGeometry structure (X3D 4.0 clause 32) in the traversal: CADAssembly and
// CADLayer group, CADPart places its children as a Transform does, CADFace draws the
// node in its `shape` field.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;

namespace {

const std::string kCadWorld = R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT CADGeometry:2
CADLayer { name "layer" children [
  CADAssembly { name "assembly" children [
    CADPart { name "part" translation 2 0 0 scale 1 3 1 children [
      CADFace { name "face" shape Shape { geometry Box {} } }
      CADFace { name "empty" }
    ] }
  ] }
] }
)";

}  // namespace

TEST_CASE("CAD geometry: CADPart places its faces, CADFace draws its shape", "[scene][x3d]") {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(kCadWorld, "cad.x3dv"));
  INFO((scene->diagnostics.items.empty() ? "" : scene->diagnostics.items.front().message));
  CHECK(scene->diagnostics.items.empty());  // the component is implemented: no warning
  SceneTraversal t(scene);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 1);
  const glm::mat4& m = frame.shapes[0].model;
  CHECK(m[3].x == Approx(2.0f));
  CHECK(m[1].y == Approx(3.0f));
  const auto bounds = t.worldBounds();
  CHECK(bounds.max.x == Approx(3.0f));
  CHECK(bounds.max.y == Approx(3.0f));

  // A CADPart moved (as the runtime writes an exposedField) moves its faces.
  REQUIRE(scene->rootNodes.size() == 1);
  const auto& assembly = scene->rootNodes[0]->mfnode("children").at(0);
  const auto& part = assembly->mfnode("children").at(0);
  REQUIRE(part->typeId() == gs::vrml::NodeTypeId::CADPart);
  part->setField(
      static_cast<std::size_t>(part->type().findField("translation")),
      gs::vrml::FieldValue::make<gs::vrml::FieldType::SFVec3f>(glm::vec3(-4.0f, 0.0f, 0.0f)));
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 1);
  CHECK(frame.shapes[0].model[3].x == Approx(-4.0f));
}
