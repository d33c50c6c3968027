// X3D RigidBodyPhysics' collidables in the traversal (X3D 4.0 clauses 37.4.3, 37.4.4): a
// CollidableShape draws its shape, a CollidableOffset its collidable, each moved by its
// translation and rotation; a disabled one (it collides with nothing) still shows, as X_ITE
// draws it.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>

TEST_CASE("collidables: CollidableShape and CollidableOffset place their shapes", "[scene][x3d]") {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
CollidableOffset { translation 0 5 0 collidable CollidableShape {
  translation 2 0 0 rotation 0 0 1 1.5707963 shape Shape { geometry Box {} } } }
CollidableShape { enabled FALSE shape Shape { geometry Sphere {} } }
)",
                                                                     "rb.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal t(scene);
  gs::scene::TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 2);
  const glm::mat4& m = frame.shapes[0].model;
  CHECK(m[3].x == Approx(2.0f));
  CHECK(m[3].y == Approx(5.0f));
  CHECK(m[0].y == Approx(1.0f).margin(1e-6));  // X turned onto Y
}
