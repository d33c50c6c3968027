// X3D NurbsSet (X3D 4.0 27.4.6) in the traversal: the NURBS surfaces of its `geometry`,
// drawn where Shapes hold them, are tessellated at its tessellationScale (X_ITE 15:
// floor(segments x scale)); the set draws nothing itself.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>

TEST_CASE("NurbsSet: its tessellationScale multiplies its surfaces' segments", "[scene][x3d]") {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
Shape { geometry DEF S NurbsPatchSurface { uDimension 2 vDimension 2 uOrder 2 vOrder 2
  uTessellation 4 vTessellation 3 controlPoint Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] } } }
Shape { geometry DEF T NurbsPatchSurface { uDimension 2 vDimension 2 uOrder 2 vOrder 2
  uTessellation 4 vTessellation 3 controlPoint Coordinate { point [ 0 0 0, 1 0 0, 0 1 0, 1 1 0 ] } } }
DEF SET NurbsSet { tessellationScale 2.5 geometry USE S }
)",
                                                                     "set.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal t(scene);
  gs::scene::TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 2);  // the set itself draws nothing
  // 4 x 2.5 = 10 and floor(3 x 2.5) = 7 segments: 11 x 8 grid points; T keeps 5 x 4.
  CHECK(t.mesh(*frame.shapes[0].geometry).positions.size() == 88);
  CHECK(t.mesh(*frame.shapes[1].geometry).positions.size() == 20);
  // A new tessellationScale is taken up at the next mesh.
  gs::vrml::Node& set = *scene->rootNodes[2];
  set.setField(static_cast<std::size_t>(set.type().findField("tessellationScale")),
               gs::vrml::FieldValue::make<gs::vrml::FieldType::SFFloat>(1.0f));
  CHECK(t.mesh(*frame.shapes[0].geometry).positions.size() == 20);
}
