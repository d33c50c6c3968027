// X3D 4.0's bboxDisplay (X3DBoundedObject, clause 10.3.1) in the traversal: a node's box
// outlined by 12 white lines after its children, in their coordinates, as X_ITE draws it
// (create3000's EnvironmentalSensor/TransformSensor.x3d).
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace {

gs::scene::TraversalFrame collected(gs::scene::SceneTraversal& t, bool picking = false) {
  gs::scene::TraversalFrame frame;
  frame.recordPaths = picking;
  t.collect(t.boundViewpointCamera(), frame);
  return frame;
}

}  // namespace

TEST_CASE("bboxDisplay outlines a node's box in its children's coordinates", "[scene][x3d]") {
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
DEF T Transform { translation 3 0 0 scale 2 2 2 bboxDisplay TRUE children [
  Transform { translation 1 0 0 children Shape { geometry Box { size 2 2 2 } } }
  Shape { geometry Sphere { radius 0.5 } }
] }
Transform { bboxDisplay TRUE bboxCenter 0 5 0 bboxSize 1 2 3 }
Transform { bboxDisplay TRUE visible FALSE children Shape { geometry Box {} } }
Transform { children Shape { geometry Box {} } }
)";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "bbox.x3dv"));
  CHECK(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal t(scene);
  const gs::scene::TraversalFrame frame = collected(t);
  // T's two shapes and its outline; the outline given by bboxSize; the plain Box.
  REQUIRE(frame.shapes.size() == 5);
  const gs::scene::ShapeInstance& outline = frame.shapes[2];
  const gs::vrml::Mesh& lines = t.mesh(*outline.geometry);
  CHECK(lines.primitive == gs::vrml::Primitive::lines);
  CHECK(lines.indices.size() == 24);  // 12 edges
  // The children's box: the Box from 0 to 2 along x, the Sphere within it; drawn in T's
  // coordinates (x from 3).
  CHECK(lines.bounds.min == glm::vec3(-0.5f, -1.0f, -1.0f));
  CHECK(lines.bounds.max == glm::vec3(2.0f, 1.0f, 1.0f));
  CHECK(outline.model[3].x == Approx(3.0f));
  CHECK(outline.model[0].x == Approx(2.0f));
  const gs::vrml::Mesh& given = t.mesh(*frame.shapes[3].geometry);
  CHECK(given.bounds.min == glm::vec3(-0.5f, 4.0f, -1.5f));
  CHECK(given.bounds.max == glm::vec3(0.5f, 6.0f, 1.5f));
  // The outline's mesh comes back after the cache dropped its arrays (as the renderer
  // does once a mesh is on the GPU).
  t.dropMeshArrays(*outline.geometry);
  CHECK(t.mesh(*outline.geometry).indices.size() == 24);
  // Not picked: a picking traversal has no outlines.
  gs::scene::SceneTraversal picking(scene);
  CHECK(collected(picking, true).shapes.size() == 3);
}
