// X3D's StaticGroup (X3D 4.0 clause 10.4.3) and ViewpointGroup (23.4.6) in the traversal:
// neither is an X3DGroupingNode, both walk their children (shapes drawn, viewpoints bound).
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;

TEST_CASE("StaticGroup draws its children, ViewpointGroup offers its viewpoints", "[scene][x3d]") {
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
StaticGroup { children [
  Transform { translation 2 0 0 children Shape { geometry Box {} } }
  ViewpointGroup { children [
    Viewpoint { position 0 0 7 description "grouped" }
  ] }
] }
)";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "static.x3dv"));
  CHECK(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 1);
  CHECK(frame.shapes[0].model[3].x == Approx(2.0f));
  REQUIRE(t.viewpoints().size() == 1);
  CHECK(t.boundViewpointCamera().position.z == Approx(7.0f));
}

TEST_CASE("A viewpoint's own NavigationInfo, bound by the runtime, sets the navigation",
          "[scene][x3d]") {
  // X3D 4.0 clause 23.3.1: the NavigationInfo in a Viewpoint's navigationInfo field is in
  // no grouping node; bound with its Viewpoint, it is the world's navigation.
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
NavigationInfo { speed 2 }
Viewpoint { navigationInfo NavigationInfo { speed 7 type "FLY" } }
)";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "own_nav.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  CHECK(t.navigation().speed == 2.0f);  // the graph's first, without a runtime
  const gs::vrml::Node& viewpoint = *scene->rootNodes.at(1);
  gs::scene::BoundNodes bound;
  bound.viewpoint = &viewpoint;
  bound.navigationInfo = viewpoint.sfnode("navigationInfo").get();
  t.setBoundNodes(bound);
  CHECK(t.navigation().speed == 7.0f);
  CHECK(t.navigation().type == std::vector<std::string>{"FLY"});
}

TEST_CASE("ViewpointGroup: displayed, size and center decide whether its viewpoints are listed",
          "[scene][x3d]") {
  // X3D 4.0 clause 23.4.6, X_ITE 15's rule: listed when every group around is displayed
  // and holds the viewer in its box (a size of 0 0 0: everywhere).
  const std::string world = R"(#X3D V4.0 utf8
PROFILE Immersive
Transform { translation 50 0 0 children ViewpointGroup { description "Outside" children [
  Viewpoint { description "Free" }
  ViewpointGroup { description "House" center 50 0 0 size 10 10 10
    children Viewpoint { description "Kitchen" } }
  ViewpointGroup { displayed FALSE children Viewpoint { description "Hidden" } }
] } }
)";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "groups.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  const auto& vps = t.viewpoints();
  REQUIRE(vps.size() == 3);  // all bindable
  CHECK(vps[0].groups == std::vector<std::string>{"Outside"});
  CHECK(vps[1].groups == std::vector<std::string>{"Outside", "House"});
  // The house's box is centred at 50 0 0 in the group, 100 0 0 in the world.
  const glm::vec3 far(0.0f, 0.0f, 10.0f), inHouse(102.0f, 0.0f, 1.0f);
  CHECK(vps[0].listedAt(far));
  CHECK_FALSE(vps[1].listedAt(far));  // the viewer is outside the house's box
  CHECK(vps[1].listedAt(inHouse));
  CHECK_FALSE(vps[2].listedAt(far));  // displayed FALSE
  CHECK_FALSE(vps[2].listedAt(inHouse));
}
