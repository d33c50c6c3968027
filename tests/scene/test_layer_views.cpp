// X3D Layering (clause 35): a layer other than the active one that holds a Viewpoint is
// placed so that the world's camera (the active layer's) sees it as its own Viewpoint would
// (scene/src/traversal.cpp, Walk::layerWithOwnView), one without a Viewpoint as the default
// Viewpoint would; the active layer's bindables are bound.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>

TEST_CASE("Layers: a non-active layer is seen through its own Viewpoint", "[scene][x3d]") {
  // Layer 1 (active): the camera at x = 10 looking down -x. Layer 2: its Viewpoint 5 m in
  // front of its box. Its box must land 5 m in front of the world camera.
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
LayerSet { activeLayer 1 order [ 1 2 ] layers [
  Layer { children [ Viewpoint { position 10 0 0 orientation 0 1 0 1.5707963 }
                     Shape { geometry Sphere {} } ] }
  Layer { children [ Viewpoint { position 0 0 5 } Shape { geometry Box {} } ] } ] }
)",
                                                                     "layers.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal t(scene);
  const gs::scene::Camera camera = t.boundViewpointCamera();
  CHECK(camera.position.x == Approx(10.0f));  // the active layer's Viewpoint is bound
  gs::scene::TraversalFrame frame;
  t.collect(camera, frame);
  REQUIRE(frame.shapes.size() == 2);
  const auto& box = frame.shapes[1].layer == 2 ? frame.shapes[1] : frame.shapes[0];
  REQUIRE(box.layer == 2);
  const glm::vec3 at(box.model[3]);
  CHECK(at.x == Approx(5.0f).margin(1e-4));
  CHECK(at.y == Approx(0.0f).margin(1e-4));
  CHECK(at.z == Approx(0.0f).margin(1e-4));
}

TEST_CASE("Layers: a non-active layer without a Viewpoint is seen from the default one",
          "[scene][x3d]") {
  // X3D 4.0 clause 35.2.1: each layer has its own bindable stacks, so layer 2, which has no
  // Viewpoint, is seen from the default Viewpoint (0 0 10, 23.4.6), not from the user's:
  // its box at z = 5 is 5 m in front of the world camera (a heads-up display stays put).
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
LayerSet { activeLayer 1 order [ 1 2 ] layers [
  Layer { children [ Viewpoint { position 10 0 0 orientation 0 1 0 1.5707963 }
                     Shape { geometry Sphere {} } ] }
  Layer { children Transform { translation 0 0 5 children Shape { geometry Box {} } } } ] }
)",
                                                                     "layers.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal t(scene);
  const gs::scene::Camera camera = t.boundViewpointCamera();
  gs::scene::TraversalFrame frame;
  t.collect(camera, frame);
  REQUIRE(frame.shapes.size() == 2);
  const auto& box = frame.shapes[1].layer == 2 ? frame.shapes[1] : frame.shapes[0];
  REQUIRE(box.layer == 2);
  const glm::vec3 at(box.model[3]);
  CHECK(at.x == Approx(5.0f).margin(1e-4));
  CHECK(at.y == Approx(0.0f).margin(1e-4));
  CHECK(at.z == Approx(0.0f).margin(1e-4));
}
